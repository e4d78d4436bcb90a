// The drone's poses and setpoint in the page, from poses.worker.ts. Keeps the last poses
// (sim-time stamped), learns how the sim's clock maps onto the page's, and answers "where is the
// drone at this display time" by interpolating between poses, or extrapolating a little past the
// newest one, so the drawn drone moves at the display's rate rather than in steps.
//
// The page is cross-origin isolated (the server sends the headers), so the worker writes poses
// into a shared ring and wakes the page with at most one message; the page reads the ring then,
// and again at the start of every frame it draws (sync()). Without isolation the worker posts
// each pose.
import { notify, type Listeners } from "./listeners";
import {
  BUFFER_BYTES, CONTROL_BYTES, RING, SETPOINT_SLOT, SLOT,
  type PoseSample, type Q4, type SetpointSample, type V3, type WorkerMessage,
} from "./pose_ring";

const KEEP = 64;
const MARGIN = 4;  // ring slots the worker may be rewriting while the page reads
const EXTRAPOLATE_MAX_S = 0.1;  // past this, the drone is drawn where it was last seen
const OFFSET_BUCKET_MS = 1000;  // the clock offset is the least delay seen over the last 4 s
const OFFSET_BUCKETS = 4;
export const WORKER_URL = "/page/poses.worker.js";

/** The drone's pose at a page time: position (m), orientation, velocity (m/s), and how far
 * past the newest pose it was extrapolated (s). */
export interface PoseAt { p: V3; q: Q4; v: V3; extrapolated: number }

export const poses = {
  samples: [] as PoseSample[],
  setpoint: null as V3 | null,
  setpointAt: 0,
  /** Called with each batch: new poses, a new setpoint (or null), when the page took them (ms). */
  listeners: [] as Listeners<[PoseSample[], SetpointSample | null, number]>,
  batches: 0,
  offsetMs: null as number | null,
  arrivals: [] as number[],
  worker: null as Worker | null,
  shared: false,
  /** Everything the worker wrote since the last read, now. */
  sync: (): void => {},
  poseAt: (epochMs: number): PoseAt | null => poseAt(epochMs),
  latest: (): PoseSample | null => poses.samples[poses.samples.length - 1] ?? null,
  nowEpochMs: (): number => performance.timeOrigin + performance.now(),
};
let buckets: Array<[number, number]> = [];  // [start epoch ms, least (arrival - stamp) in it]

const learnOffset = (s: PoseSample): void => {
  const delay = s.arrived - s.stamp * 1000;
  const start = Math.floor(s.arrived / OFFSET_BUCKET_MS) * OFFSET_BUCKET_MS;
  const last = buckets[buckets.length - 1];
  if (last && last[0] === start) last[1] = Math.min(last[1], delay);
  else { buckets.push([start, delay]); if (buckets.length > OFFSET_BUCKETS) buckets = buckets.slice(1); }
  poses.offsetMs = Math.min(...buckets.map((b) => b[1]));
};

const deliver = (samples: PoseSample[], setpoint: SetpointSample | null, received: number): void => {
  for (const s of samples) {
    const prev = poses.samples[poses.samples.length - 1];
    if (prev && s.stamp <= prev.stamp) continue;  // a reconnect may repeat one
    poses.samples.push(s);
    poses.arrivals.push(s.arrived);
    learnOffset(s);
  }
  if (poses.samples.length > KEEP) poses.samples.splice(0, poses.samples.length - KEEP);
  const since = poses.nowEpochMs() - 1000;
  while (poses.arrivals.length && poses.arrivals[0]! < since) poses.arrivals.shift();
  if (setpoint) { poses.setpoint = setpoint.p; poses.setpointAt = received; }
  poses.batches++;
  notify(poses.listeners, samples, setpoint, received);
};

let readPoses = 0, readSetpoints = 0;
const syncFrom = (ctl: Int32Array, data: Float64Array): void => {
  const received = performance.now();
  const written = Atomics.load(ctl, 0);
  const fresh: PoseSample[] = [];
  for (let n = Math.max(readPoses, written - RING + MARGIN); n < written; n++) {
    const d = data.subarray((n % RING) * SLOT, (n % RING + 1) * SLOT);
    fresh.push({ stamp: d[0]!, p: [d[1]!, d[2]!, d[3]!], q: [d[4]!, d[5]!, d[6]!, d[7]!], arrived: d[8]! });
  }
  readPoses = written;
  let setpoint: SetpointSample | null = null;
  const setpoints = Atomics.load(ctl, 1);
  if (setpoints !== readSetpoints) {
    readSetpoints = setpoints;
    const d = data.subarray(RING * SLOT, RING * SLOT + SETPOINT_SLOT);
    setpoint = { p: [d[0]!, d[1]!, d[2]!], arrived: d[3]! };
  }
  if (fresh.length || setpoint) deliver(fresh, setpoint, received);
};

const lerp = <T extends number[]>(a: T, b: T, f: number): T => a.map((v, i) => v + (b[i]! - v) * f) as T;
const nlerp = (a: Q4, b: Q4, f: number): Q4 => {  // quaternions a few degrees apart: normalised lerp
  const sign = a.reduce((d, v, i) => d + v * b[i]!, 0) < 0 ? -1 : 1;
  const q = a.map((v, i) => v + (sign * b[i]! - v) * f);
  const n = Math.hypot(...q);
  return q.map((v) => v / n) as Q4;
};

function poseAt(epochMs: number): PoseAt | null {
  const s = poses.samples;
  const last = s[s.length - 1];
  if (!last || poses.offsetMs === null) return null;
  const t = (epochMs - poses.offsetMs) / 1000;
  const prev = s.length > 1 ? s[s.length - 2]! : last;
  const dt = last.stamp - prev.stamp;
  const v: V3 = dt > 0 ? last.p.map((x, i) => (x - prev.p[i]!) / dt) as V3 : [0, 0, 0];
  if (t >= last.stamp) {
    const ahead = Math.min(t - last.stamp, EXTRAPOLATE_MAX_S);
    return { p: last.p.map((x, i) => x + v[i]! * ahead) as V3, q: last.q, v, extrapolated: ahead };
  }
  let i = s.length - 1;
  while (i > 0 && s[i - 1]!.stamp > t) i--;
  if (i === 0) return { p: s[0]!.p, q: s[0]!.q, v, extrapolated: 0 };
  const a = s[i - 1]!, b = s[i]!;
  const f = (t - a.stamp) / (b.stamp - a.stamp);
  return { p: lerp(a.p, b.p, f), q: nlerp(a.q, b.q, f), v, extrapolated: 0 };
}

/** Start the pose worker, sharing the ring with it when the page is cross-origin isolated. */
export function startPoses(): void {
  try {
    const worker = new Worker(WORKER_URL);
    poses.worker = worker;
    let ctl: Int32Array | null = null;
    worker.onmessage = (ev: MessageEvent<WorkerMessage>) => {
      const m = ev.data;
      if (m.type === "wake") { if (ctl) Atomics.store(ctl, 2, 0); poses.sync(); }  // clear first: a pose written now wakes again
      else if (m.type === "pose") deliver([m.sample], null, performance.now());
      else deliver([], m.setpoint, performance.now());
    };
    poses.shared = window.crossOriginIsolated && typeof SharedArrayBuffer === "function";
    if (poses.shared) {
      const buffer = new SharedArrayBuffer(BUFFER_BYTES);
      const control = new Int32Array(buffer, 0, 4), ring = new Float64Array(buffer, CONTROL_BYTES);
      ctl = control;
      poses.sync = () => syncFrom(control, ring);
      worker.postMessage({ type: "shared", buffer });
    }
  } catch (err) {
    console.error("teleop: no pose stream worker", err);
  }
}
