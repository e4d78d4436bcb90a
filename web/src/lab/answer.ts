// The first visible answer to a key: the setpoint marker at the page's prediction (predict.ts),
// drawn in the next frame, and the time that took ("key → answer drawn": from the keydown
// event's timeStamp to the end of the frame that showed it).
//
// Two ways to draw it (docs/teleop.md compares them; bench/teleop_latency.py measures both):
//   - "dom" (the default): a flat orange disc over the canvas, placed at the prediction projected
//     with viser's camera, in the key handler itself; the next 3D frame is skipped, so that frame
//     commits without waiting for the software renderer, and the 3D marker takes over one frame later;
//   - "scene": the 3D marker moved in the next 3D frame, so the answer waits for that frame.
// Either way the 3D marker stands at the prediction until the bus's setpoint confirms or
// overrules it, and at the bus's setpoint after that.
import { notify } from "./listeners";
import type { V3 } from "./pose_ring";
import { poses } from "./poses";
import { predict } from "./predict";
import { scene } from "./scene";
import type { Object3D } from "./viser";

const STORE_PATH = "teleop.marker";
const MARKER_RADIUS_M = 0.15;  // the 3D marker's (server/packages/visualizer/gui_controller.py)
const KEEP = 1000;

export type AnswerPath = "dom" | "scene";
/** One answer drawn: from the keydown (ms), in how many frames, how far the marker moved (m). */
export interface Drawn { latencyMs: number; frames: number; movedM: number | null; path: AnswerPath }
interface Mark { t0: number; renders: number; ticks: number; done: boolean; from: V3 | null; path: AnswerPath }
interface Finished { t0: number; frames: number; movedM: number | null; path: AnswerPath }

function storedPath(): AnswerPath { return localStorage.getItem(STORE_PATH) === "scene" ? "scene" : "dom"; }

export const answer = {
  path: storedPath(),
  drawn: [] as Drawn[],
  skipped: 0,
  setPath: (path: AnswerPath): void => { answer.path = path; localStorage.setItem(STORE_PATH, path); },
};
let pending: Mark | null = null;  // the keydown being timed
let skipNext = false;  // skip the next 3D render (dom path)

const ghost = document.createElement("div");
ghost.id = "teleop-ghost";
ghost.hidden = true;

const marker = (): Object3D | null => scene.ref(scene.vehicle?.setpoint);
const distance = (a: V3, b: V3): number => Math.hypot(...a.map((x, i) => x - b[i]!));

// Where a world point shows on the page, and how big a marker-sized ball there looks (px).
const project = (p: V3): { x: number; y: number; r: number } | null => {
  const v = scene.viser;
  if (!v?.canvas) return null;
  const at = scene.toThree(p);
  const away = at.distanceTo(v.camera.position);
  at.project(v.camera);
  if (at.z > 1 || at.z < -1) return null;  // behind the camera or past its far plane
  const box = v.canvas.getBoundingClientRect();
  const radius = MARKER_RADIUS_M / (away * Math.tan((v.camera.fov * Math.PI) / 360)) * (box.height / 2);
  return { x: box.left + ((at.x + 1) / 2) * box.width, y: box.top + ((1 - at.y) / 2) * box.height, r: radius };
};

const finish = new MessageChannel();  // runs after the frame that showed the answer is committed
finish.port1.onmessage = (ev: MessageEvent<Finished>) => {
  const entry: Drawn = { latencyMs: performance.now() - ev.data.t0, frames: ev.data.frames, movedM: ev.data.movedM,
    path: ev.data.path };
  answer.drawn.push(entry);
  if (answer.drawn.length > KEEP) answer.drawn.shift();
  notify(scene.listeners, { type: "drawn", ...entry });
};
const done = (mark: Mark, movedM: number | null): void => {
  mark.done = true;
  const finished: Finished = { t0: mark.t0, frames: mark.ticks + 1, movedM, path: mark.path };
  finish.port2.postMessage(finished);
  if (pending === mark) pending = null;
};

/** Draw each prediction at once, and time it. */
export function startAnswer(): void {
  const mount = (): void => { document.body.append(ghost); };
  if (document.body) mount(); else addEventListener("DOMContentLoaded", mount);
  predict.markerPosition = () => marker()?.position.toArray() ?? null;

  predict.listeners.push((prediction) => {
    const v = scene.viser;
    if (!v) return;
    v.requestRender();
    if (!prediction.key) return;
    const from = marker()?.position.toArray() ?? null;
    // Count animation frames from the key to the one that shows the answer: this rAF is
    // requested after the render's, so in each frame it runs after the drawing.
    const mark: Mark = { t0: prediction.key.timeStamp, renders: scene.renders, ticks: 0, done: false, from,
      path: answer.path };
    const tick = (): void => { if (!mark.done) { mark.ticks++; requestAnimationFrame(tick); } };
    if (pending) pending.done = true;
    pending = mark;
    const spot = answer.path === "dom" ? project(prediction.p) : null;
    if (spot) {
      ghost.style.cssText = `left:${spot.x - spot.r}px;top:${spot.y - spot.r}px;width:${2 * spot.r}px;height:${2 * spot.r}px`;
      ghost.hidden = false;
      skipNext = true;
      requestAnimationFrame(() => done(mark, from ? distance(prediction.p, from) : null));
    }
    requestAnimationFrame(tick);
  });

  scene.beforeFrame.push(() => {
    const m = marker();
    const sp = predict.prediction?.p ?? poses.setpoint;
    if (m && sp) { m.position.set(sp[0], sp[1], sp[2]); m.updateMatrixWorld(true); }
    const r = scene.renderer;
    if (r && !r.__teleopRender) {  // the dom path's skipped frame: no drawing, so no read-back to wait for
      const render = r.render.bind(r);
      r.__teleopRender = render;
      r.render = (...args: unknown[]): unknown => {
        if (skipNext) { skipNext = false; answer.skipped++; scene.viser?.requestRender(); return undefined; }
        return render(...args);
      };
    }
  });
  scene.afterFrame.push(() => {
    if (!ghost.hidden && !skipNext) ghost.hidden = true;  // the 3D marker is there now
    if (!pending || pending.done || pending.path !== "scene" || scene.renders === pending.renders) return;
    const at = marker()?.position.toArray() ?? null;
    done(pending, at && pending.from ? distance(at, pending.from) : null);
  });
}
