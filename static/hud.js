// The page's HUD and help overlay. The HUD has the view switch (Rocket, Quadrotor; follow the
// drone or keep the arena fixed), the key channel's state with the keys held lit up, the drone's
// setpoint, and two latencies:
//   - key → answer drawn: from a move keydown to the end of the frame that drew the setpoint
//     marker moved (static/scene.js; the page predicts the marker, so this is one frame's work);
//   - key → drone moving: from a move keydown to the first drone pose, received back in this
//     page, that shows the drone answering it: tilted 0.3 degrees more towards the key's direction
//     than at the keydown (a quadrotor starts moving by tilting; hover jitter stays under 0.1
//     degrees in 50 ms), or moved 2 cm that way (1 cm for up and down, which needs no tilt).
// Both start at the keydown event's timeStamp: when the browser took the key, before any wait for
// the page's main thread. docs/teleop.md has what each one contains.
(() => {
  "use strict";
  const MOVE = { ArrowRight: [0, 1], ArrowLeft: [0, -1], ArrowUp: [1, 1], ArrowDown: [1, -1],
    PageUp: [2, 1], PageDown: [2, -1], w: [2, 1], s: [2, -1] };
  const CAPS = [["ArrowLeft", "←"], ["ArrowUp", "↑"], ["ArrowDown", "↓"], ["ArrowRight", "→"],
    ["PageUp", "PgUp"], ["PageDown", "PgDn"], ["w", "W"], ["s", "S"], ["a", "a"]];
  const MOTION_M = 0.02;
  const MOTION_Z_M = 0.01;
  const TILT_RAD = 0.3 * Math.PI / 180;
  const STILL_M_S = 0.1;  // a press made while the drone still moves is not timed: it may already be
  // swinging the key's way (an overshoot's return) and would look answered at once
  const ANSWER_WAIT_MS = 3000;
  const KEEP = 1000;
  // Tilt towards +x is pitch up, towards +y is roll down (the controller's sign convention).
  const tiltToward = (q, axis) => {  // q: [w, x, y, z]
    const [w, x, y, z] = q;
    if (axis === 0) return Math.asin(Math.max(-1, Math.min(1, 2 * (w * y - z * x))));
    if (axis === 1) return -Math.atan2(2 * (w * x + y * z), 1 - 2 * (x * x + y * y));
    return 0;
  };
  const hud = { latencies: [], drawn: [], skipped: 0, pending: null, speed: 0, pose: null, setpoint: null, poseRate: 0 };
  window.__teleopHud = hud;
  const poses = window.__teleopPoses, scene = window.__teleopScene;

  const el = document.createElement("div");
  el.id = "teleop-hud";
  el.innerHTML = `<div class="views" role="group" aria-label="View"></div>
    <div class="row"><span class="conn"></span><span class="caps">${CAPS.map(([k, label]) =>
      `<kbd data-key="${k}">${label}</kbd>`).join("")}</span></div>
    <div class="row figures"></div><div class="hint">? for help</div>`;
  const help = document.createElement("div");
  help.id = "teleop-help";
  help.hidden = true;
  help.innerHTML = `<h3>Keys</h3><table>
    <tr><td><kbd>a</kbd></td><td>abort the rocket during the countdown</td></tr>
    <tr><td><kbd>→</kbd> <kbd>←</kbd></td><td>drone +x / −x (right / left on screen)</td></tr>
    <tr><td><kbd>↑</kbd> <kbd>↓</kbd></td><td>drone +y / −y (away / towards you)</td></tr>
    <tr><td><kbd>PgUp</kbd>/<kbd>W</kbd> <kbd>PgDn</kbd>/<kbd>S</kbd></td><td>drone up / down</td></tr>
    <tr><td><kbd>?</kbd></td><td>show or hide this help</td></tr></table>
    <p>Click the 3D view first so the page has the keyboard. The orange ball is the setpoint: it
    moves the moment you press a key, and the drone flies to it. <b>Rocket</b> and <b>Quadrotor</b>
    switch the view; <b>follow</b> keeps the camera on the drone, <b>arena</b> holds it still.
    The Teleop panel sets the key mode (1 m per press, or hold to move). Leaving the window
    releases every key.</p>`;

  const button = (label, pressed, onClick) => {
    const b = document.createElement("button");
    b.type = "button"; b.textContent = label; b.tabIndex = -1;
    b.setAttribute("aria-pressed", String(pressed));
    b.addEventListener("mousedown", (e) => e.preventDefault());  // keep the keyboard where it is
    b.addEventListener("click", (e) => { onClick(); e.currentTarget.blur(); });
    return b;
  };
  const renderViews = () => {
    const box = el.querySelector(".views");
    box.replaceChildren();
    if (!scene.ready) return;
    for (const v of scene.views) {
      box.append(button(v.name, scene.view && scene.view.name === v.name, () => scene.setView(v.name)));
    }
    if (scene.view && scene.view.follow) {
      box.append(button("follow", scene.follow, () => scene.setView(scene.view.name, true)),
        button("arena", !scene.follow, () => scene.setView(scene.view.name, false)));
    }
  };
  scene.listeners.push((event) => {
    if (event.type === "view" || event.type === "ready") renderViews();
    if (event.type === "drawn") { hud.drawn.push(event.latencyMs); if (hud.drawn.length > KEEP) hud.drawn.shift(); }
  });

  const fmt = (v) => v.map((x) => x.toFixed(2)).join(", ");
  const median = (a) => { if (!a.length) return null; const s = [...a].sort((x, y) => x - y); return s[Math.floor(s.length / 2)]; };
  const figure = (name, values) => {
    const last = values.length ? values[values.length - 1] : null;
    const med = median(values.slice(-20));
    return `<div><b>${name}</b> ${last === null ? "–" : last.toFixed(0) + " ms"}${med === null ? "" : " (median " + med.toFixed(0) + ")"}</div>`;
  };
  const render = () => {
    const keys = window.__teleopKeys || { connected: false };
    const conn = el.querySelector(".conn");
    conn.textContent = keys.connected ? "keys" : "keys offline";
    conn.className = "conn " + (keys.connected ? "on" : "off");
    const q = window.__teleopQuality;
    const predict = window.__teleopPredict;
    const sp = predict ? predict.current() : poses.setpoint;
    el.querySelector(".figures").innerHTML =
      `<div><b>setpoint</b> ${sp ? "(" + fmt(sp) + ") m" : "–"}</div>` +
      figure("key → answer drawn", hud.drawn) + figure("key → drone moving", hud.latencies) +
      `<div class="dim">poses ${hud.poseRate}/s` + (q && q.fps !== null ? ` · ${q.fps.toFixed(0)} fps` : "") +
      (q && q.frameMs ? ` · frame ${q.frameMs.toFixed(0)} ms` : "") + (q ? ` · pixels ×${q.dpr}` : "") + "</div>";
  };
  const lightKeys = () => {
    const held = window.__teleopKeys ? window.__teleopKeys.held : new Set();
    for (const cap of el.querySelectorAll("kbd[data-key]")) cap.classList.toggle("held", held.has(cap.dataset.key));
  };

  poses.listeners.push((samples, _setpoint, received) => {
    for (const s of samples) {
      if (hud.pose && s.stamp > hud.stamp) {
        hud.speed = Math.hypot(...s.p.map((v, i) => v - hud.pose[i])) / (s.stamp - hud.stamp);
      }
      hud.stamp = s.stamp; hud.pose = s.p; hud.quat = s.q;
      const pend = hud.pending;
      if (!pend || !pend.start) continue;
      const moved = (s.p[pend.axis] - pend.start[pend.axis]) * pend.sign;
      const tilted = (tiltToward(s.q, pend.axis) - pend.tilt0) * pend.sign;
      const answered = pend.axis === 2 ? moved >= MOTION_Z_M : moved >= MOTION_M || tilted >= TILT_RAD;
      if (answered) {
        hud.latencies.push(received - pend.t0); hud.pending = null;
        if (hud.latencies.length > KEEP) hud.latencies.shift();
      } else if (received - pend.t0 > ANSWER_WAIT_MS) hud.pending = null;
    }
    hud.poseRate = poses.arrivals.length;
    hud.setpoint = poses.setpoint;
  });
  const onKey = (e, k) => {
    lightKeys();
    if (e.type !== "keydown") return;
    if (e.key === "?") { help.hidden = !help.hidden; window.dispatchEvent(new Event("teleop-layout")); return; }
    if (e.repeat || !MOVE[k]) return;
    if (hud.speed > STILL_M_S) { hud.skipped++; hud.pending = null; return; }
    const axis = MOVE[k][0];
    hud.pending = { t0: e.timeStamp, axis, sign: MOVE[k][1], start: hud.pose && [...hud.pose],
      tilt0: hud.quat ? tiltToward(hud.quat, axis) : 0 };
  };
  if (window.__teleopKeys) window.__teleopKeys.listeners.push(onKey);
  addEventListener("blur", lightKeys);
  setInterval(render, 250);
  const mount = () => { document.body.append(el, help); render(); renderViews(); };
  if (document.body) mount(); else addEventListener("DOMContentLoaded", mount);
})();
