// The drone's poses and setpoint in the page, from static/poses.worker.js. Keeps the last poses
// (sim-time stamped), learns how the sim's clock maps onto the page's, and answers "where is the
// drone at this display time" by interpolating between poses, or extrapolating a little past the
// newest one, so the drawn drone moves at the display's rate rather than in steps.
//
// The page is cross-origin isolated (server/viewer/page.py sends the headers), so the worker
// writes poses into a shared ring and wakes the page with at most one message; the page reads
// the ring then, and again at the start of every frame it draws (sync()). Without isolation the
// worker posts each pose.
(() => {
  "use strict";
  const KEEP = 64;
  const RING = 64, SLOT = 9;  // as in static/poses.worker.js
  const MARGIN = 4;  // ring slots the worker may be rewriting while the page reads
  const EXTRAPOLATE_MAX_S = 0.1;  // past this, the drone is drawn where it was last seen
  const OFFSET_BUCKET_MS = 1000;  // the clock offset is the least delay seen over the last 4 s
  const OFFSET_BUCKETS = 4;
  const state = { samples: [], setpoint: null, setpointAt: 0, listeners: [], batches: 0,
    offsetMs: null, arrivals: [], worker: null, shared: false, sync: () => {} };
  window.__teleopPoses = state;
  const nowEpochMs = () => performance.timeOrigin + performance.now();
  let buckets = [];  // [start epoch ms, least (arrival - stamp) in it]

  const learnOffset = (s) => {
    const delay = s.arrived - s.stamp * 1000;
    const start = Math.floor(s.arrived / OFFSET_BUCKET_MS) * OFFSET_BUCKET_MS;
    const last = buckets[buckets.length - 1];
    if (last && last[0] === start) last[1] = Math.min(last[1], delay);
    else { buckets.push([start, delay]); if (buckets.length > OFFSET_BUCKETS) buckets.shift(); }
    state.offsetMs = Math.min(...buckets.map((b) => b[1]));
  };

  const deliver = (samples, setpoint, received) => {
    for (const s of samples) {
      const prev = state.samples[state.samples.length - 1];
      if (prev && s.stamp <= prev.stamp) continue;  // a reconnect may repeat one
      state.samples.push(s);
      state.arrivals.push(s.arrived);
      learnOffset(s);
    }
    if (state.samples.length > KEEP) state.samples.splice(0, state.samples.length - KEEP);
    const since = nowEpochMs() - 1000;
    while (state.arrivals.length && state.arrivals[0] < since) state.arrivals.shift();
    if (setpoint) { state.setpoint = setpoint.p; state.setpointAt = received; }
    state.batches++;
    for (const listener of state.listeners) {
      try { listener(samples, setpoint, received); } catch (err) { console.error(err); }
    }
  };

  let ctl = null, data = null, readPoses = 0, readSetpoints = 0;
  // Everything the worker wrote since the last read, now.
  state.sync = () => {
    if (!ctl) return;
    const received = performance.now();
    const written = Atomics.load(ctl, 0);
    const fresh = [];
    for (let n = Math.max(readPoses, written - RING + MARGIN); n < written; n++) {
      const d = data.subarray((n % RING) * SLOT, (n % RING + 1) * SLOT);
      fresh.push({ stamp: d[0], p: [d[1], d[2], d[3]], q: [d[4], d[5], d[6], d[7]], arrived: d[8] });
    }
    readPoses = written;
    let setpoint = null;
    const setpoints = Atomics.load(ctl, 1);
    if (setpoints !== readSetpoints) {
      readSetpoints = setpoints;
      const d = data.subarray(RING * SLOT, RING * SLOT + 4);
      setpoint = { p: [d[0], d[1], d[2]], arrived: d[3] };
    }
    if (fresh.length || setpoint) deliver(fresh, setpoint, received);
  };
  const onMessage = (ev) => {
    const m = ev.data;
    if (m.type === "wake") { Atomics.store(ctl, 2, 0); state.sync(); }  // clear first: a pose written now wakes again
    else if (m.type === "pose") deliver([m.sample], null, performance.now());
    else if (m.type === "setpoint") deliver([], m.setpoint, performance.now());
  };

  const lerp = (a, b, f) => a.map((v, i) => v + (b[i] - v) * f);
  const nlerp = (a, b, f) => {  // quaternions (w, x, y, z) a few degrees apart: normalised lerp
    const sign = a.reduce((d, v, i) => d + v * b[i], 0) < 0 ? -1 : 1;
    const q = a.map((v, i) => v + (sign * b[i] - v) * f);
    const n = Math.hypot(...q);
    return q.map((v) => v / n);
  };

  // The drone's pose at a page time (epoch ms): { p, q, v, extrapolated } or null.
  state.poseAt = (epochMs) => {
    const s = state.samples;
    if (!s.length || state.offsetMs === null) return null;
    const t = (epochMs - state.offsetMs) / 1000;
    const last = s[s.length - 1];
    const prev = s.length > 1 ? s[s.length - 2] : last;
    const dt = last.stamp - prev.stamp;
    const v = dt > 0 ? last.p.map((x, i) => (x - prev.p[i]) / dt) : [0, 0, 0];
    if (t >= last.stamp) {
      const ahead = Math.min(t - last.stamp, EXTRAPOLATE_MAX_S);
      return { p: last.p.map((x, i) => x + v[i] * ahead), q: last.q, v, extrapolated: ahead };
    }
    let i = s.length - 1;
    while (i > 0 && s[i - 1].stamp > t) i--;
    if (i === 0) return { p: s[0].p, q: s[0].q, v, extrapolated: 0 };
    const a = s[i - 1], b = s[i];
    const f = (t - a.stamp) / (b.stamp - a.stamp);
    return { p: lerp(a.p, b.p, f), q: nlerp(a.q, b.q, f), v, extrapolated: 0 };
  };
  state.latest = () => state.samples[state.samples.length - 1] || null;
  state.nowEpochMs = nowEpochMs;

  try {
    state.worker = new Worker("/page/poses.worker.js");
    state.worker.onmessage = onMessage;
    state.shared = window.crossOriginIsolated === true && typeof SharedArrayBuffer === "function";
    if (state.shared) {
      const buffer = new SharedArrayBuffer(16 + (RING * SLOT + 4) * 8);
      ctl = new Int32Array(buffer, 0, 4);
      data = new Float64Array(buffer, 16);
      state.worker.postMessage({ type: "shared", buffer });
    }
  } catch (err) {
    console.error("teleop: no pose stream worker", err);
  }
})();
