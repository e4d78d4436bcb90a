// The drone's poses and setpoint in the page, from static/poses.worker.js. Keeps the last poses
// (sim-time stamped), learns how the sim's clock maps onto the page's, and answers "where is the
// drone at this display time" by interpolating between poses, or extrapolating a little past the
// newest one, so the drawn drone moves at the display's rate rather than in steps.
(() => {
  "use strict";
  const KEEP = 64;
  const EXTRAPOLATE_MAX_S = 0.1;  // past this, the drone is drawn where it was last seen
  const OFFSET_BUCKET_MS = 1000;  // the clock offset is the least delay seen over the last 4 s
  const OFFSET_BUCKETS = 4;
  const state = { samples: [], setpoint: null, setpointAt: 0, listeners: [], batches: 0,
    offsetMs: null, arrivals: [], worker: null };
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

  const onBatch = (ev) => {
    const received = performance.now();
    const { samples, setpoint } = ev.data;
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
    state.worker.postMessage({ type: "pull" });  // ready for the next: never more than one queued
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
    state.worker = new Worker("/static/poses.worker.js");
    state.worker.onmessage = onBatch;
    state.worker.postMessage({ type: "pull" });
  } catch (err) {
    console.error("teleop: no pose stream worker", err);
  }
})();
