// The page's HUD and help overlay. The HUD has the view switch (Rocket, Quadrotor; follow the
// drone or keep the arena fixed), the key channel's state with the keys held lit up, the drone's
// setpoint, and two latencies:
//   - key → answer drawn: from a move keydown to the end of the frame that drew the setpoint
//     marker moved (answer.ts; the page predicts the marker, so this is one frame's work);
//   - key → drone moving: from a move keydown to the first drone pose, received back in this
//     page, that shows the drone answering it: tilted 0.3 degrees more towards the key's direction
//     than at the keydown (a quadrotor starts moving by tilting; hover jitter stays under 0.1
//     degrees in 50 ms), or moved 2 cm that way (1 cm for up and down, which needs no tilt).
// Both start at the keydown event's timeStamp: when the browser took the key, before any wait for
// the page's main thread. docs/teleop.md has what each one contains.
import { keys } from "./keys";
import { LAYOUT_EVENT } from "./layout";
import type { Q4, V3 } from "./pose_ring";
import { poses } from "./poses";
import { predict } from "./predict";
import { quality } from "./quality";
import { scene } from "./scene";

type Axis = 0 | 1 | 2;
const MOVE: Record<string, [Axis, 1 | -1] | undefined> = {
  ArrowRight: [0, 1], ArrowLeft: [0, -1], ArrowUp: [1, 1], ArrowDown: [1, -1],
  PageUp: [2, 1], PageDown: [2, -1], w: [2, 1], s: [2, -1],
};
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
const tiltToward = (q: Q4, axis: Axis): number => {
  const [w, x, y, z] = q;
  if (axis === 0) return Math.asin(Math.max(-1, Math.min(1, 2 * (w * y - z * x))));
  if (axis === 1) return -Math.atan2(2 * (w * x + y * z), 1 - 2 * (x * x + y * y));
  return 0;
};

/** A move key being timed: when it went down (ms), its axis and sign, and the drone then. */
interface Pending { t0: number; axis: Axis; sign: number; start: V3 | null; tilt0: number }

export const hud = {
  latencies: [] as number[],
  drawn: [] as number[],
  skipped: 0,
  pending: null as Pending | null,
  speed: 0,
  pose: null as V3 | null,
  quat: null as Q4 | null,
  stamp: 0,
  setpoint: null as V3 | null,
  poseRate: 0,
};

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
const part = (selector: string): HTMLElement => el.querySelector<HTMLElement>(selector)!;

const button = (label: string, pressed: boolean, onClick: () => void): HTMLButtonElement => {
  const b = document.createElement("button");
  b.type = "button"; b.textContent = label; b.tabIndex = -1;
  b.setAttribute("aria-pressed", String(pressed));
  b.addEventListener("mousedown", (e) => e.preventDefault());  // keep the keyboard where it is
  b.addEventListener("click", () => { onClick(); b.blur(); });
  return b;
};
const renderViews = (): void => {
  const box = part(".views");
  box.replaceChildren();
  if (!scene.ready) return;
  for (const v of scene.views) {
    box.append(button(v.name, scene.view?.name === v.name, () => scene.setView(v.name)));
  }
  const view = scene.view;
  if (view?.follow) {
    box.append(button("follow", scene.follow, () => scene.setView(view.name, true)),
      button("arena", !scene.follow, () => scene.setView(view.name, false)));
  }
};

const fmt = (v: number[]): string => v.map((x) => x.toFixed(2)).join(", ");
const median = (a: number[]): number | null => {
  if (!a.length) return null;
  const s = [...a].sort((x, y) => x - y);
  return s[Math.floor(s.length / 2)] ?? null;
};
const figure = (name: string, values: number[]): string => {
  const last = values[values.length - 1] ?? null;
  const med = median(values.slice(-20));
  return `<div><b>${name}</b> ${last === null ? "–" : last.toFixed(0) + " ms"}${med === null ? "" : " (median " + med.toFixed(0) + ")"}</div>`;
};
const render = (): void => {
  const conn = part(".conn");
  conn.textContent = keys.connected ? "keys" : "keys offline";
  conn.className = "conn " + (keys.connected ? "on" : "off");
  const q = quality;
  const sp = predict.current();
  part(".figures").innerHTML =
    `<div><b>setpoint</b> ${"(" + fmt(sp) + ") m"}</div>` +
    figure("key → answer drawn", hud.drawn) + figure("key → drone moving", hud.latencies) +
    `<div class="dim">poses ${hud.poseRate}/s` + (q.fps !== null ? ` · ${q.fps.toFixed(0)} fps` : "") +
    (q.frameMs ? ` · frame ${q.frameMs.toFixed(0)} ms` : "") + ` · pixels ×${q.dpr}` + "</div>";
};
const lightKeys = (): void => {
  for (const cap of el.querySelectorAll<HTMLElement>("kbd[data-key]")) {
    cap.classList.toggle("held", keys.held.has(cap.dataset.key ?? ""));
  }
};

const onPoses = (samples: { stamp: number; p: V3; q: Q4 }[], received: number): void => {
  for (const s of samples) {
    if (hud.pose && s.stamp > hud.stamp) {
      const from = hud.pose;
      hud.speed = Math.hypot(...s.p.map((v, i) => v - from[i]!)) / (s.stamp - hud.stamp);
    }
    hud.stamp = s.stamp; hud.pose = s.p; hud.quat = s.q;
    const pend = hud.pending;
    if (!pend?.start) continue;
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
};
const onKey = (e: KeyboardEvent, k: string): void => {
  lightKeys();
  if (e.type !== "keydown") return;
  if (e.key === "?") { help.hidden = !help.hidden; window.dispatchEvent(new Event(LAYOUT_EVENT)); return; }
  const move = MOVE[k];
  if (e.repeat || !move) return;
  if (hud.speed > STILL_M_S) { hud.skipped++; hud.pending = null; return; }
  const [axis, sign] = move;
  hud.pending = { t0: e.timeStamp, axis, sign, start: hud.pose ? [...hud.pose] as V3 : null,
    tilt0: hud.quat ? tiltToward(hud.quat, axis) : 0 };
};

/** Show the HUD and the help (hidden until "?"), and keep them current. */
export function startHud(): void {
  scene.listeners.push((event) => {
    if (event.type === "view" || event.type === "ready") renderViews();
    if (event.type === "drawn") { hud.drawn.push(event.latencyMs); if (hud.drawn.length > KEEP) hud.drawn.shift(); }
  });
  poses.listeners.push((samples, _setpoint, received) => onPoses(samples, received));
  keys.listeners.push(onKey);
  addEventListener("blur", lightKeys);
  setInterval(render, 250);
  const mount = (): void => { document.body.append(el, help); render(); renderViews(); };
  if (document.body) mount(); else addEventListener("DOMContentLoaded", mount);
}
