// The drone's pose stream, off the page's main thread. This worker holds the topic echoes of
// /uav/sensors/gps (100 Hz) and /uav/input/position, decodes every message as it arrives, and
// hands the page one batch at a time, only when the page asks for the next: however long a frame
// keeps the main thread busy, at most one batch waits for it (the latest pose, with the few
// samples since the previous batch for interpolation), never a backlog of stale poses.
"use strict";
const MAX_SAMPLES = 32;  // 0.32 s of poses at 100 Hz; older ones would only be dropped by the page
const RETRY_MS = 1000;
const base = (self.location.protocol === "https:" ? "wss://" : "ws://") + self.location.host + "/ws/topics/";
const nowEpochMs = () => performance.timeOrigin + performance.now();

let wanted = false;
let samples = [];
let setpoint = null;

const flush = () => {
  if (!wanted || (!samples.length && !setpoint)) return;
  wanted = false;
  self.postMessage({ samples, setpoint });
  samples = [];
  setpoint = null;
};

const echo = (topic, onMsg) => {
  const open = () => {
    const ws = new WebSocket(base + topic + "?queue_length=10");
    ws.onmessage = (ev) => {
      try { onMsg(JSON.parse(ev.data).msg, nowEpochMs()); } catch (err) { return; }
      flush();
    };
    ws.onclose = () => setTimeout(open, RETRY_MS);
  };
  open();
};

// One pose: sim-time stamp (s), position (m), orientation (w, x, y, z), arrival here (epoch ms).
echo("uav/sensors/gps", (m, arrived) => {
  const p = m.pose.position, q = m.pose.orientation;
  samples.push({ stamp: m.header.stamp.sec + m.header.stamp.nanosec * 1e-9, p: [p.x, p.y, p.z],
    q: [q.w, q.x, q.y, q.z], arrived });
  if (samples.length > MAX_SAMPLES) samples.shift();
});
echo("uav/input/position", (m, arrived) => { setpoint = { p: [m.x, m.y, m.z], arrived }; });

self.onmessage = (ev) => {
  if (ev.data && ev.data.type === "pull") { wanted = true; flush(); }
};
