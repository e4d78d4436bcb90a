// The join form of a class server: POST /api/classroom/join sets this browser's HTTP-only token
// cookie, and the page reloads into the student's own world.
"use strict";
(() => {
  const form = document.getElementById("join");
  const status = document.getElementById("status");
  form.addEventListener("submit", async (event) => {
    event.preventDefault();
    const body = {
      name: document.getElementById("name").value.trim(),
      code: document.getElementById("code").value.trim(),
    };
    status.textContent = "starting your world…";
    try {
      const reply = await fetch("/api/classroom/join", {
        method: "POST",
        headers: { "Content-Type": "application/json" },
        body: JSON.stringify(body),
      });
      const data = await reply.json();
      if (!reply.ok) {
        status.textContent = typeof data.detail === "string" ? data.detail : "the form is not complete";
        return;
      }
      status.textContent = `world ${data.world} is ready`;
      window.location.replace("/");
    } catch (err) {
      status.textContent = `the class server did not answer: ${err}`;
    }
  });
})();
