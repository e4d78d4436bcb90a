// The first visible answer to a key: the setpoint marker at the page's prediction
// (static/predict.js), drawn in the next frame, and the time that took ("key → answer drawn":
// from the keydown event's timeStamp to the end of the frame that showed it).
//
// Two ways to draw it (docs/teleop.md compares them; bench/teleop_latency.py measures both):
//   - "dom" (the default): a flat orange disc over the canvas, placed at the prediction projected
//     with viser's camera, in the key handler itself; the next 3D frame is skipped, so that frame
//     commits without waiting for the software renderer, and the 3D marker takes over one frame later;
//   - "scene": the 3D marker moved in the next 3D frame, so the answer waits for that frame.
// Either way the 3D marker stands at the prediction until the bus's setpoint confirms or
// overrules it, and at the bus's setpoint after that.
(() => {
  "use strict";
  const STORE_PATH = "teleop.marker";
  const MARKER_RADIUS_M = 0.15;  // the 3D marker's (server/packages/visualizer/gui_controller.py)
  const KEEP = 1000;
  const state = { path: localStorage.getItem(STORE_PATH) === "scene" ? "scene" : "dom", drawn: [], skipped: 0 };
  window.__teleopAnswer = state;
  const scene = window.__teleopScene, poses = window.__teleopPoses, predict = window.__teleopPredict;
  let pending = null;  // the keydown being timed
  let skipNext = false;  // skip the next 3D render (dom path)

  const ghost = document.createElement("div");
  ghost.id = "teleop-ghost";
  ghost.hidden = true;
  const mount = () => document.body.append(ghost);
  if (document.body) mount(); else addEventListener("DOMContentLoaded", mount);

  state.setPath = (path) => { state.path = path; localStorage.setItem(STORE_PATH, path); };
  const marker = () => scene.ref(scene.vehicle && scene.vehicle.setpoint);
  predict.markerPosition = () => { const m = marker(); return m ? m.position.toArray() : null; };

  // Where a world point shows on the page, and how big a marker-sized ball there looks (px).
  const project = (p) => {
    const v = scene.viser;
    if (!v || !v.canvas) return null;
    const at = scene.toThree(p);
    const distance = at.distanceTo(v.camera.position);
    at.project(v.camera);
    if (at.z > 1 || at.z < -1) return null;  // behind the camera or past its far plane
    const box = v.canvas.getBoundingClientRect();
    const radius = MARKER_RADIUS_M / (distance * Math.tan((v.camera.fov * Math.PI) / 360)) * (box.height / 2);
    return { x: box.left + ((at.x + 1) / 2) * box.width, y: box.top + ((1 - at.y) / 2) * box.height, r: radius };
  };

  const finish = new MessageChannel();  // runs after the frame that showed the answer is committed
  finish.port1.onmessage = (ev) => {
    const entry = { latencyMs: performance.now() - ev.data.t0, frames: ev.data.frames, movedM: ev.data.movedM, path: ev.data.path };
    state.drawn.push(entry);
    if (state.drawn.length > KEEP) state.drawn.shift();
    for (const listener of scene.listeners) {
      try { listener({ type: "drawn", ...entry }); } catch (err) { console.error(err); }
    }
  };
  const done = (mark, movedM) => {
    mark.done = true;
    finish.port2.postMessage({ t0: mark.t0, frames: mark.ticks + 1, movedM, path: mark.path });
    if (pending === mark) pending = null;
  };

  predict.listeners.push((prediction) => {
    const v = scene.viser;
    if (!v) return;
    v.requestRender();
    if (!prediction.key) return;
    const m = marker();
    const from = m ? m.position.toArray() : null;
    // Count animation frames from the key to the one that shows the answer: this rAF is
    // requested after the render's, so in each frame it runs after the drawing.
    const mark = { t0: prediction.key.timeStamp, renders: scene.renders, ticks: 0, done: false, from, path: state.path };
    const tick = () => { if (!mark.done) { mark.ticks++; requestAnimationFrame(tick); } };
    if (pending) pending.done = true;
    pending = mark;
    const spot = state.path === "dom" ? project(prediction.p) : null;
    if (spot) {
      ghost.style.cssText = `left:${spot.x - spot.r}px;top:${spot.y - spot.r}px;width:${2 * spot.r}px;height:${2 * spot.r}px`;
      ghost.hidden = false;
      skipNext = true;
      requestAnimationFrame(() => done(mark, from ? Math.hypot(...prediction.p.map((x, i) => x - from[i])) : null));
    }
    requestAnimationFrame(tick);
  });

  scene.beforeFrame.push(() => {
    const m = marker();
    const sp = predict.prediction ? predict.prediction.p : poses.setpoint;
    if (m && sp) { m.position.set(sp[0], sp[1], sp[2]); m.updateMatrixWorld(true); }
    const r = scene.renderer;
    if (r && !r.__teleopRender) {  // the dom path's skipped frame: no drawing, so no read-back to wait for
      const render = r.render;
      r.__teleopRender = render;
      r.render = function (...args) {
        if (skipNext) { skipNext = false; state.skipped++; scene.viser.requestRender(); return undefined; }
        return render.apply(this, args);
      };
    }
  });
  scene.afterFrame.push(() => {
    if (!ghost.hidden && !skipNext) ghost.hidden = true;  // the 3D marker is there now
    if (!pending || pending.done || pending.path !== "scene" || scene.renders === pending.renders) return;
    const m = marker();
    const at = m ? m.position.toArray() : null;
    done(pending, at && pending.from ? Math.hypot(...at.map((x, i) => x - pending.from[i])) : null);
  });
})();
