// The ring of poses the pose worker shares with the page (a SharedArrayBuffer): its layout,
// written by poses.worker.ts and read by poses.ts.

export const RING = 64;
/** How often the page takes the drone's pose (ms): it asks the server for the newest
 * /uav/sensors/gps message at most this often (the echo's throttle_rate), about 50 of the
 * dynamics' 100 a second. The page draws the drone between poses at the display's rate, so this
 * loses nothing it shows, and each open page costs the server two thirds of what every pose did. */
export const POSE_PERIOD_MS = 20;
export const SLOT = 9;  // stamp (s, sim time), x, y, z (m), w, qx, qy, qz, arrival in the worker (epoch ms)
export const SETPOINT_SLOT = 4;  // x, y, z (m), arrival (epoch ms): after the ring
export const CONTROL_BYTES = 16;  // Int32Array [poses written, setpoints written, wake pending, unused]
export const BUFFER_BYTES = CONTROL_BYTES + (RING * SLOT + SETPOINT_SLOT) * 8;

export type V3 = [number, number, number];
export type Q4 = [number, number, number, number];  // w, x, y, z

/** A drone pose: sim-time stamp (s), position (m), orientation and arrival here (epoch ms). */
export interface PoseSample { stamp: number; p: V3; q: Q4; arrived: number }
/** The setpoint (m) and its arrival (epoch ms). */
export interface SetpointSample { p: V3; arrived: number }

/** Worker → page, when the page is not cross-origin isolated (or to wake it when it is). */
export type WorkerMessage =
  | { type: "wake" }
  | { type: "pose"; sample: PoseSample }
  | { type: "setpoint"; setpoint: SetpointSample };
/** Page → worker: the shared ring. */
export interface SharedMessage { type: "shared"; buffer: SharedArrayBuffer }
