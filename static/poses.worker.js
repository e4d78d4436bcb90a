// The drone's pose stream, off the page's main thread. This worker holds the topic echoes of
// /uav/sensors/gps (100 Hz) and /uav/input/position and decodes every message as it arrives.
//
// When the page is cross-origin isolated it shares a ring of the last RING poses with the page
// (a SharedArrayBuffer, see static/poses.js) and posts only a wake-up, and only when the page has
// read the ring since the last one: however long a frame keeps the main thread busy, at most one
// message waits for it, and when it runs it reads the ring as it is then, the newest pose
// included. Otherwise it posts every message as it arrives.
"use strict";
const RING = 64;
const SLOT = 9;  // stamp (s, sim time), x, y, z (m), w, qx, qy, qz, arrival here (epoch ms)
const RETRY_MS = 1000;
const base = (self.location.protocol === "https:" ? "wss://" : "ws://") + self.location.host + "/ws/topics/";
const nowEpochMs = () => performance.timeOrigin + performance.now();
let ctl = null, data = null;  // Int32Array [poses written, setpoints written, wake pending]; Float64Array

const wake = () => { if (Atomics.compareExchange(ctl, 2, 0, 1) === 0) self.postMessage({ type: "wake" }); };

const echo = (topic, onMsg) => {
  const open = () => {
    const ws = new WebSocket(base + topic + "?queue_length=10");
    ws.onmessage = (ev) => {
      let msg;
      try { msg = JSON.parse(ev.data).msg; } catch (err) { return; }
      onMsg(msg, nowEpochMs());
    };
    ws.onclose = () => setTimeout(open, RETRY_MS);
  };
  open();
};

echo("uav/sensors/gps", (m, arrived) => {
  const p = m.pose.position, q = m.pose.orientation;
  const stamp = m.header.stamp.sec + m.header.stamp.nanosec * 1e-9;
  if (!ctl) { self.postMessage({ type: "pose", sample: { stamp, p: [p.x, p.y, p.z], q: [q.w, q.x, q.y, q.z], arrived } }); return; }
  const at = (Atomics.load(ctl, 0) % RING) * SLOT;
  data.set([stamp, p.x, p.y, p.z, q.w, q.x, q.y, q.z, arrived], at);
  Atomics.add(ctl, 0, 1);  // after the slot is written: the page reads only whole poses
  wake();
});
echo("uav/input/position", (m, arrived) => {
  if (!ctl) { self.postMessage({ type: "setpoint", setpoint: { p: [m.x, m.y, m.z], arrived } }); return; }
  data.set([m.x, m.y, m.z, arrived], RING * SLOT);
  Atomics.add(ctl, 1, 1);
  wake();
});

self.onmessage = (ev) => {
  if (ev.data && ev.data.type === "shared") {
    ctl = new Int32Array(ev.data.buffer, 0, 4);
    data = new Float64Array(ev.data.buffer, 16);
  }
};
