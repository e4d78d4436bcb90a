// The setpoint a key will give, worked out in the page the moment the key goes down, so the
// marker can move in the next frame instead of after the round trip through the bus. It mirrors
// the drone keyboard manager's rules (server/packages/simple_control/keyboard_manager.py) with its
// live parameters, read from the REST API; the setpoint the bus then publishes corrects it.
import type { GraphOut, KeyManagerParams, NodeDetailOut } from "../protocol.gen";
import { keys } from "./keys";
import { notify, type Listeners } from "./listeners";
import type { V3 } from "./pose_ring";
import { poses } from "./poses";

const DIRECTIONS: Record<string, V3 | undefined> = {
  ArrowRight: [1, 0, 0], ArrowLeft: [-1, 0, 0], ArrowUp: [0, 1, 0], ArrowDown: [0, -1, 0],
  PageUp: [0, 0, 1], w: [0, 0, 1], PageDown: [0, 0, -1], s: [0, 0, -1],
};
const START_M: V3 = [0, 0, 3];
const ARENA_MIN_M: V3 = [-10, -10, 0], ARENA_MAX_M: V3 = [10, 10, 15];
const PARAMS_POLL_MS = 3000;
const MATCH_M = 0.1;  // a bus setpoint this close to the prediction confirms it
const GRACE_MS = 250;  // a differing bus setpoint wins only after this (lab mode publishes the old one first)
const EXPIRE_MS = 1000;  // no confirmation by then: the bus setpoint is what the drone flies to
const SILENT_MS = 3000;  // no setpoint at all since the key: the prediction stands this long
// On a busy server the manager's answer may reach the page later than GRACE_MS, or even EXPIRE_MS:
// the setpoint from before the key then wins only at EXPIRE_MS, and silence only at SILENT_MS,
// so the marker does not go back for a moment before it goes forward (a CI run saw that).

/** A predicted setpoint (m), when it was made (ms), the keydown that made it (none on a keyup), the
 * bus's setpoint then (none yet), and whether a setpoint has come since. */
export interface Prediction { p: V3; made: number; key: KeyboardEvent | null; from: V3 | null; heard: boolean }

export const predict = {
  params: null as KeyManagerParams | null,
  node: null as string | null,
  prediction: null as Prediction | null,
  listeners: [] as Listeners<[Prediction]>,
  made: 0,
  confirmed: 0,
  overruled: 0,
  checks: 0,  // rounds of the expiry check
  // Where the server drew the marker: set by answer.ts, which finds it in the scene.
  markerPosition: (): V3 | null => null,
  // Where the marker stands now: the live prediction, else the bus's setpoint, else where the
  // server drew the marker, else the manager's start.
  current: (): V3 => predict.prediction?.p ?? poses.setpoint ?? predict.markerPosition() ?? START_M,
};

const getJson = async <T>(url: string): Promise<T> => (await fetch(url)).json() as Promise<T>;
const findManager = async (): Promise<string[]> => {
  const graph = await getJson<GraphOut>("/api/graph");
  const pubs = new Set(graph.edges.filter((e) => e.kind === "publish" && e.to === "/uav/input/position").map((e) => e.from));
  const subs = graph.edges.filter((e) => e.kind === "subscribe" && e.from === "/keydown").map((e) => e.to);
  return subs.filter((n) => pubs.has(n));
};
const pollParams = async (): Promise<void> => {  // the params stay as they were until the poll has new ones
  try {
    for (const name of predict.node ? [predict.node] : await findManager()) {
      const r = await fetch("/api/nodes/" + name.replace(/^\//, ""));
      const info = r.ok ? await r.json() as NodeDetailOut : null;
      if (info && info.state === "active" && "hold_speed_m_s" in info.parameters) {
        predict.node = name; predict.params = info.parameters as unknown as KeyManagerParams; return;
      }
    }
    predict.node = null; predict.params = null;  // gone, or renamed: look again next time
  } catch (err) { console.warn("teleop: no keyboard manager parameters", err); }
};

const clamp = (p: V3): V3 => p.map((v, i) => Math.min(Math.max(v, ARENA_MIN_M[i]!), ARENA_MAX_M[i]!)) as V3;

function predictSetpoint(held: Set<string>, key: string, down: boolean): V3 | null {
  const prm = predict.params;
  const move = DIRECTIONS[key];
  if (!prm || !move) return null;
  const here = predict.current();
  if (prm.mode !== "hold") {
    if (!down || (prm.mode === "lab" && move[2] !== 0)) return null;  // the handout moves in x and y only
    return clamp(here.map((v, i) => v + move[i]! * prm.step_m) as V3);
  }
  const latest = poses.latest();
  if (!latest) return null;
  const dirs = [...held].map((k) => DIRECTIONS[k]).filter((d): d is V3 => d !== undefined);
  if (!dirs.length) {  // the last move key came up: stop where the drone will come to rest
    if (down) return null;
    const pose = poses.poseAt(poses.nowEpochMs());
    return clamp(latest.p.map((v, i) => v + (pose ? pose.v[i]! : 0) * prm.brake_s) as V3);
  }
  const dir = [0, 1, 2].map((i) => dirs.reduce((s, d) => s + d[i]!, 0));
  const norm = Math.max(Math.hypot(...dir), 1e-9);
  const lead = prm.hold_speed_m_s * prm.lead_s;
  return clamp([0, 1, 2].map((i) => (dir[i] ? latest.p[i]! + (dir[i] / norm) * lead : here[i]!)) as V3);
}

// keys.ts calls this for every key, after sending it to the server.
const onKey = (e: KeyboardEvent, k: string): void => {
  if (e.repeat) return;
  const p = predictSetpoint(keys.held, k, e.type === "keydown");
  if (!p) return;
  const prediction: Prediction = {
    p, made: performance.now(), key: e.type === "keydown" ? e : null, from: poses.setpoint, heard: false,
  };
  predict.prediction = prediction;
  predict.made++;
  notify(predict.listeners, prediction);
};

/** Follow the keyboard manager's parameters, and predict on every key. */
export function startPredict(): void {
  void pollParams();
  setInterval(() => void pollParams(), PARAMS_POLL_MS);
  keys.listeners.push(onKey);

  // The bus's setpoint confirms the prediction (close to it) or, after a grace time, overrules it:
  // a new one after GRACE_MS, the one from before the key only at EXPIRE_MS, none at SILENT_MS.
  const near = (a: V3, b: V3): boolean => Math.hypot(...a.map((v, i) => v - b[i]!)) < MATCH_M;
  poses.listeners.push((_samples, setpoint, received) => {
    const pred = predict.prediction;
    if (!pred) return;
    const age = received - pred.made;
    if (setpoint) pred.heard = true;
    if (setpoint && near(setpoint.p, pred.p)) {
      predict.prediction = null; predict.confirmed++;
    } else if ((setpoint && !(pred.from && near(setpoint.p, pred.from)) && age > GRACE_MS)
      || age > (pred.heard ? EXPIRE_MS : SILENT_MS)) {
      predict.prediction = null; predict.overruled++;
    }
  });
  setInterval(() => {
    predict.checks++;
    const pred = predict.prediction;
    if (pred && performance.now() - pred.made > (pred.heard ? EXPIRE_MS : SILENT_MS)) {
      predict.prediction = null; predict.overruled++;
    }
  }, 250);
}
