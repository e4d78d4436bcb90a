// The join form of a class server: POST /api/classroom/join sets this browser's HTTP-only token
// cookie, and the page reloads into the student's own world.
import type { ErrorBody, JoinRequest, Joined } from "../protocol.gen";

const form = document.getElementById("join") as HTMLFormElement;
const status = document.getElementById("status")!;
const field = (id: string): string => (document.getElementById(id) as HTMLInputElement).value.trim();

form.addEventListener("submit", (event) => {
  event.preventDefault();
  void join({ name: field("name"), code: field("code") });
});

async function join(body: JoinRequest): Promise<void> {
  status.textContent = "starting your world…";
  try {
    const reply = await fetch("/api/classroom/join", {
      method: "POST",
      headers: { "Content-Type": "application/json" },
      body: JSON.stringify(body),
    });
    const data = await reply.json() as Joined | ErrorBody;
    if (!reply.ok || !("world" in data)) {
      const detail = "detail" in data ? data.detail : null;
      status.textContent = typeof detail === "string" ? detail : "the form is not complete";
      return;
    }
    status.textContent = `world ${data.world} is ready`;
    window.location.replace("/");
  } catch (err) {
    status.textContent = `the class server did not answer: ${String(err)}`;
  }
}
