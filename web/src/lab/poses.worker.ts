// The drone's pose stream, off the page's main thread. This worker holds the topic echoes of
// /uav/sensors/gps (its newest message every POSE_PERIOD_MS) and /uav/input/position and decodes
// every message as it arrives.
//
// When the page is cross-origin isolated it shares a ring of the last RING poses with the page
// (a SharedArrayBuffer, see poses.ts) and posts only a wake-up, and only when the page has read
// the ring since the last one: however long a frame keeps the main thread busy, at most one
// message waits for it, and when it runs it reads the ring as it is then, the newest pose
// included. Otherwise it posts every message as it arrives.
import type { EchoFrame, PoseStamped, Vector3 } from "../protocol.gen";
import { CONTROL_BYTES, POSE_PERIOD_MS, RING, SLOT, type SharedMessage, type WorkerMessage } from "./pose_ring";

/** The worker's global scope, as far as this worker uses it (the page's lib has no worker types). */
interface WorkerScope {
  location: Location;
  postMessage(message: WorkerMessage): void;
  onmessage: ((ev: MessageEvent<SharedMessage | undefined>) => void) | null;
}
const scope = self as unknown as WorkerScope;
const RETRY_MS = 1000;
const base = (scope.location.protocol === "https:" ? "wss://" : "ws://") + scope.location.host + "/ws/topics/";
const nowEpochMs = (): number => performance.timeOrigin + performance.now();
let ctl: Int32Array | null = null;
let data: Float64Array | null = null;

const wake = (control: Int32Array): void => {
  if (Atomics.compareExchange(control, 2, 0, 1) === 0) scope.postMessage({ type: "wake" });
};

function echo<M>(topic: string, query: string, onMsg: (msg: M, arrived: number) => void): void {
  const open = (): void => {
    const ws = new WebSocket(base + topic + "?" + query);
    ws.onmessage = (ev: MessageEvent<string>) => {
      let frame: EchoFrame;
      try { frame = JSON.parse(ev.data) as EchoFrame; } catch { return; }
      onMsg(frame.msg as M, nowEpochMs());
    };
    ws.onclose = () => setTimeout(open, RETRY_MS);
  };
  open();
}

echo<PoseStamped>("uav/sensors/gps", `throttle_rate=${POSE_PERIOD_MS}`, (m, arrived) => {
  const p = m.pose.position, q = m.pose.orientation;
  const stamp = m.header.stamp.sec + m.header.stamp.nanosec * 1e-9;
  if (!ctl || !data) {
    scope.postMessage({ type: "pose", sample: { stamp, p: [p.x, p.y, p.z], q: [q.w, q.x, q.y, q.z], arrived } });
    return;
  }
  const at = (Atomics.load(ctl, 0) % RING) * SLOT;
  data.set([stamp, p.x, p.y, p.z, q.w, q.x, q.y, q.z, arrived], at);
  Atomics.add(ctl, 0, 1);  // after the slot is written: the page reads only whole poses
  wake(ctl);
});
echo<Vector3>("uav/input/position", "queue_length=10", (m, arrived) => {
  if (!ctl || !data) { scope.postMessage({ type: "setpoint", setpoint: { p: [m.x, m.y, m.z], arrived } }); return; }
  data.set([m.x, m.y, m.z, arrived], RING * SLOT);
  Atomics.add(ctl, 1, 1);
  wake(ctl);
});

scope.onmessage = (ev) => {
  if (ev.data && ev.data.type === "shared") {
    ctl = new Int32Array(ev.data.buffer, 0, 4);
    data = new Float64Array(ev.data.buffer, CONTROL_BYTES);
  }
};
