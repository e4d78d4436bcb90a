// The page's HUD and help overlay. The HUD shows the key channel's state and the keys held
// (from keys.js), the drone's current setpoint, how many drone poses arrive per second, and
// the measured key-to-motion latency: from a move keydown in this page to the first drone pose,
// received back in this page, that shows the drone answering it: tilted 0.3 degrees more towards
// the key's direction than at the keydown (a quadrotor starts moving by tilting; hover jitter
// stays under 0.1 degrees in 50 ms), or moved 2 cm that way (1 cm for up and down, which needs
// no tilt). Poses and setpoints come from the topic echo WebSockets, as `ros2 topic echo` sees them.
(() => {
  "use strict";
  const MOVE = { ArrowRight: [0, 1], ArrowLeft: [0, -1], ArrowUp: [1, 1], ArrowDown: [1, -1],
    PageUp: [2, 1], PageDown: [2, -1], w: [2, 1], s: [2, -1] };
  const MOTION_M = 0.02;
  const MOTION_Z_M = 0.01;
  const TILT_RAD = 0.3 * Math.PI / 180;
  // Tilt towards +x is pitch up, towards +y is roll down (the controller's sign convention).
  const tiltToward = (q, axis) => {
    if (axis === 0) return Math.asin(Math.max(-1, Math.min(1, 2 * (q.w * q.y - q.z * q.x))));
    if (axis === 1) return -Math.atan2(2 * (q.w * q.x + q.y * q.z), 1 - 2 * (q.x * q.x + q.y * q.y));
    return 0;
  };
  const STILL_M_S = 0.1;  // a press made while the drone still moves is not timed: it may already be
  // swinging the key's way (an overshoot's return) and would look answered at once
  const hud = { setpoint: null, pose: null, quat: null, speed: 0, poseTimes: [], latencies: [], skipped: 0,
    pending: null, poseRate: 0 };
  window.__teleopHud = hud;

  const el = document.createElement("div");
  el.id = "teleop-hud";
  const help = document.createElement("div");
  help.id = "teleop-help";
  help.hidden = true;
  help.innerHTML = `<h3>Keys</h3><table>
    <tr><td><kbd>a</kbd></td><td>abort the rocket during the countdown</td></tr>
    <tr><td><kbd>→</kbd> <kbd>←</kbd></td><td>drone +x / −x (right / left on screen)</td></tr>
    <tr><td><kbd>↑</kbd> <kbd>↓</kbd></td><td>drone +y / −y (away / towards you)</td></tr>
    <tr><td><kbd>PgUp</kbd>/<kbd>W</kbd> <kbd>PgDn</kbd>/<kbd>S</kbd></td><td>drone up / down</td></tr>
    <tr><td><kbd>?</kbd></td><td>show or hide this help</td></tr></table>
    <p>Click the 3D view first so the page has the keyboard. The Teleop panel sets the key mode
    (1 m per press, or hold to move) and the hold speed. Leaving the window releases every key.</p>`;

  const fmt = (v) => v.map((x) => x.toFixed(2)).join(", ");
  const median = (a) => { if (!a.length) return null; const s = [...a].sort((x, y) => x - y); return s[Math.floor(s.length / 2)]; };
  const render = () => {
    const keys = window.__teleopKeys || { connected: false, held: new Set() };
    const last = hud.latencies.length ? hud.latencies[hud.latencies.length - 1] : null;
    const med = median(hud.latencies.slice(-20));
    el.innerHTML =
      `<div><b>keys</b> ${keys.connected ? "connected" : "offline"}${keys.held.size ? " · held: " + [...keys.held].join(" ") : ""}</div>` +
      `<div><b>setpoint</b> ${hud.setpoint ? "(" + fmt(hud.setpoint) + ") m" : "–"}</div>` +
      `<div><b>poses</b> ${hud.poseRate.toFixed(0)}/s</div>` +
      `<div><b>key→motion</b> ${last === null ? "–" : last.toFixed(0) + " ms"}${med === null ? "" : " (median " + med.toFixed(0) + " ms)"}</div>` +
      `<div class="hint">? for help</div>`;
  };

  const echo = (topic, onMsg) => {
    const open = () => {
      const ws = new WebSocket((location.protocol === "https:" ? "wss://" : "ws://") + location.host + "/ws/topics/" + topic + "?queue_length=10");
      ws.onmessage = (ev) => onMsg(JSON.parse(ev.data).msg, performance.now());
      ws.onclose = () => setTimeout(open, 1000);
    };
    open();
  };
  echo("uav/input/position", (m) => { hud.setpoint = [m.x, m.y, m.z]; });
  echo("uav/sensors/gps", (m, now) => {
    const p = m.pose.position;
    const stamp = m.header.stamp.sec + m.header.stamp.nanosec * 1e-9;  // sim time: no network jitter
    if (hud.pose && hud.stamp !== undefined && stamp > hud.stamp) {
      hud.speed = Math.hypot(p.x - hud.pose[0], p.y - hud.pose[1], p.z - hud.pose[2]) / (stamp - hud.stamp);
    }
    hud.stamp = stamp;
    hud.pose = [p.x, p.y, p.z];
    hud.quat = m.pose.orientation;
    hud.poseTimes.push(now);
    const pend = hud.pending;
    if (pend && pend.start) {
      const moved = (hud.pose[pend.axis] - pend.start[pend.axis]) * pend.sign;
      const tilted = (tiltToward(hud.quat, pend.axis) - pend.tilt0) * pend.sign;
      const answered = pend.axis === 2 ? moved >= MOTION_Z_M : moved >= MOTION_M || tilted >= TILT_RAD;
      if (answered) { hud.latencies.push(now - pend.t0); hud.pending = null; if (hud.latencies.length > 1000) hud.latencies.shift(); }
      else if (now - pend.t0 > 3000) hud.pending = null;
    }
  });
  const onKey = (e, k) => {
    if (e.type !== "keydown") return;
    if (e.key === "?") { help.hidden = !help.hidden; return; }
    if (e.repeat || !MOVE[k]) return;
    if (hud.speed > STILL_M_S) { hud.skipped++; hud.pending = null; return; }
    const axis = MOVE[k][0];
    hud.pending = { t0: e.timeStamp, axis, sign: MOVE[k][1], start: hud.pose && [...hud.pose],
      tilt0: hud.quat ? tiltToward(hud.quat, axis) : 0 };
  };
  if (window.__teleopKeys) window.__teleopKeys.listeners.push(onKey);
  setInterval(() => {
    const now = performance.now();
    hud.poseTimes = hud.poseTimes.filter((t) => now - t <= 1000);
    hud.poseRate = hud.poseTimes.length;
    render();
  }, 250);
  addEventListener("DOMContentLoaded", () => { document.body.append(el, help); render(); });
})();
