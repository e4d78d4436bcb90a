// The instructor's page: every world once a second (GET /api/classroom/worlds) in a table, and
// the controls (reset one or all, remove a student, publish in all worlds). Every drone in 3D is
// the class view's own viser page, in a frame (/instructor/view). The token is the page's
// HTTP-only cookie; these requests are same-origin.
"use strict";
(() => {
  const $ = (id) => document.getElementById(id);
  const say = (text) => { $("status").textContent = text; };

  async function call(method, url, body) {
    const reply = await fetch(url, {
      method,
      headers: body ? { "Content-Type": "application/json" } : {},
      body: body ? JSON.stringify(body) : undefined,
    });
    const data = await reply.json().catch(() => ({}));
    if (!reply.ok) throw new Error(typeof data.detail === "string" ? data.detail : `HTTP ${reply.status}`);
    return data;
  }

  function cell(row, text, cls) {
    const td = row.insertCell();
    td.textContent = text;
    if (cls) td.className = cls;
    return td;
  }

  function button(td, label, onClick) {
    const b = document.createElement("button");
    b.type = "button";
    b.textContent = label;
    b.addEventListener("click", onClick);
    td.append(b, " ");
  }

  function draw(worlds) {
    const body = $("worlds");
    body.replaceChildren();
    for (const w of worlds) {
      const row = body.insertRow();
      row.dataset.world = w.world;
      cell(row, w.student);
      cell(row, w.worker ? `${w.world} (on worker ${w.worker})` : w.world);
      const keys = w.keys_held || [];
      const crashed = w.crashed_nodes || [];
      cell(row, keys.length ? keys.join(", ") : "–", "num");
      cell(row, w.rocket ? `${w.rocket.phase} ${w.rocket.altitude_m} m` : "–");
      cell(row, w.drone ? w.drone.map((v) => v.toFixed(2)).join(", ") : "–", "num");
      if (w.lost) cell(row, w.lost, "bad");
      else if (w.worker_error) cell(row, w.worker_error, "bad");
      else cell(row, crashed.length ? crashed.join(", ") : "none", crashed.length ? "bad" : "");
      const actions = row.insertCell();
      button(actions, "Reset", () => act("POST", `/api/classroom/worlds/${encodeURIComponent(w.world)}/reset`, `reset ${w.world}`));
      button(actions, "Remove", () => {
        if (confirm(`Remove ${w.student}'s world? Their page stops working until they join again.`)) {
          act("DELETE", `/api/classroom/worlds/${encodeURIComponent(w.world)}`, `removed ${w.world}`);
        }
      });
    }
  }

  async function act(method, url, done, body) {
    try {
      await call(method, url, body);
      say(done);
      await refresh();
    } catch (err) {
      say(String(err.message || err));
    }
  }

  async function refresh() {
    try {
      const data = await call("GET", "/api/classroom/worlds");
      $("code").textContent = data.class_code;
      $("count").textContent = `${data.worlds.length} / ${data.max_worlds} worlds`;
      draw(data.worlds);
    } catch (err) {
      say(String(err.message || err));
    }
  }

  $("reset-all").addEventListener("click", () => act("POST", "/api/classroom/reset", "every world reset"));
  $("broadcast").addEventListener("click", () => {
    let msg;
    try {
      msg = JSON.parse($("b-msg").value);
    } catch (err) {
      say(`the message is not JSON: ${err.message}`);
      return;
    }
    const type = $("b-type").value.trim() || null;
    act("POST", "/api/classroom/broadcast", "published in every world", { topic: $("b-topic").value.trim(), msg, type });
  });
  refresh();
  setInterval(refresh, 1000);
})();
