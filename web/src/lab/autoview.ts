// Show what the student's code does: when the drone sets off on a flight (it leaves the place
// where it rested by more than FLIGHT_M) while the view shows something else, the view switches
// to the drone and follows it, without a click. "Something else" is another lab's view (the
// rocket's), or the drone's own arena camera once the drone leaves its picture. It happens once
// per flight: a student who picks another view during the flight keeps it until the drone has
// rested and sets off again. Whoever flies it (a node of the student's, a REST publisher, the
// Message Publisher panel, the keys), the page sees the flight in the pose stream (poses.ts).
import type { PoseSample, V3 } from "./pose_ring";
import { poses } from "./poses";
import { scene } from "./scene";

const REST_M = 0.05;  // the drone rests while it stays this close ...
const REST_S = 1.0;  // ... for this long, on the sim's clock (its poses' stamps)
const FLIGHT_M = 0.5;  // and flies once it is this far from where it rested
const IN_PICTURE = 0.9;  // in the picture: within this fraction of the canvas's half-size of its centre

export const autoview = {
  /** Where the drone last rested (m), and whether it has left it. */
  rest: null as V3 | null,
  flying: false,
  /** The view has been switched, or chosen by the student, during this flight. */
  settled: false,
  switches: 0,
  enabled: true,
};
let anchor: { p: V3; stamp: number } | null = null;
let switching = false;

const dist = (a: V3, b: V3): number => Math.hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);

/** Whether the camera shows the drone at ``p``: its own view following it, or inside the picture. */
function shows(p: V3): boolean {
  const view = scene.view, viser = scene.viser;
  if (!view || !viser || view.follow?.node !== scene.vehicle?.node) return false;
  if (scene.follow) return true;
  viser.camera.updateMatrixWorld();
  const ndc = scene.toThree(p).project(viser.camera);
  return ndc.z < 1 && Math.abs(ndc.x) < IN_PICTURE && Math.abs(ndc.y) < IN_PICTURE;
}

function track(s: PoseSample): void {
  if (!anchor || dist(s.p, anchor.p) > REST_M) anchor = { p: s.p, stamp: s.stamp };
  else if (s.stamp - anchor.stamp >= REST_S) {
    autoview.rest = anchor.p; autoview.flying = false; autoview.settled = false;
  }
  if (autoview.rest && !autoview.flying && dist(s.p, autoview.rest) > FLIGHT_M) autoview.flying = true;
}

function onPoses(samples: PoseSample[]): void {
  for (const s of samples) track(s);
  const latest = samples[samples.length - 1];
  if (!latest || !autoview.enabled || !scene.ready || !autoview.flying || autoview.settled) return;
  if (shows(latest.p)) return;
  const view = scene.views.find((v) => v.follow && v.follow.node === scene.vehicle?.node);
  if (!view) return;
  autoview.settled = true;
  autoview.switches++;
  switching = true;
  try { scene.setView(view.name, true); } finally { switching = false; }
}

/** Watch the drone's poses, and the student's own choices of view. */
export function startAutoview(): void {
  poses.listeners.push((samples) => onPoses(samples));
  scene.listeners.push((event) => {
    if (event.type === "view" && !switching && autoview.flying) autoview.settled = true;
  });
}
