// The page's hand on viser's 3D view, through the scene and camera controls viser exposes on
// window.__viserMutable (viser 1.1.1 publishes it for end-to-end tests; the browser tests check
// it is there). Right before each frame is drawn (the scene's onBeforeRender) it puts the drone
// where the pose stream says it is at that instant (poses.ts), moves the camera after the drone,
// smoothly, when the view follows it, shortens the trail when quality.ts asks for less, and lets
// answer.ts place the setpoint marker. It switches the camera between the labs' views
// (GET /page/views), remembering the choice in the browser, and measures what each frame costs
// the main thread.
import type { FollowJson, PageViews, ViewJson } from "../protocol.gen";
import { notify, type Listeners } from "./listeners";
import { POSE_PERIOD_MS, type V3 } from "./pose_ring";
import { poses } from "./poses";
import { viserMutable, type Object3D, type Renderer, type Scene, type Vec3, type ViserMutable } from "./viser";

const STORE_VIEW = "teleop.view", STORE_FOLLOW = "teleop.follow";
// One pose period behind the stream: between two poses, or past the newest by a few ms when a pose
// comes late (the server's throttle sends them 20 ms apart or a little more), which poseAt carries on.
const DISPLAY_DELAY_MS = POSE_PERIOD_MS;
const POSE_STALE_MS = 1000;  // no pose for this long: leave the drone where the server drew it
const FOLLOW_TAU_S = 0.15;  // the camera's lag behind the drone
// How far the drone may wander (hovering) before the camera moves: each move draws frames for a
// quarter second, and a hover's drift past 1 cm kept a page drawing 15 frames a second at rest.
// 5 cm is under 10 pixels at the follow distance on a laptop's screen.
const FOLLOW_SLACK_M = 0.05;
// Keep frames coming while the drone moves: more than 5 mm or 0.5 degrees in the last 0.1 s of
// the pose stream. A hovering drone's jitter (a millimetre or two, back and forth) is not worth
// a frame, nor the wait that a key pressed then would have behind it.
const MOTION_WINDOW_MS = 100, MOVED_M = 0.005, TURNED_RAD = (0.5 * Math.PI) / 180;
const KEEP_FRAMES = 120;

/** What the scene tells its listeners: a view switched, the scene taken over, an answer drawn. */
export type SceneEvent =
  | { type: "view"; view: string; follow: boolean }
  | { type: "ready" }
  | { type: "drawn"; latencyMs: number; frames: number; movedM: number | null; path: string };

/** viser's handles once it has built its scene: what the page draws with. */
export type ReadyViser = ViserMutable & Required<Pick<ViserMutable, "scene" | "camera" | "cameraControl">>;
type Vec3Constructor = new (x: number, y: number, z: number) => Vec3;

export const scene = {
  views: [] as ViewJson[],
  view: null as ViewJson | null,
  follow: localStorage.getItem(STORE_FOLLOW) !== "fixed",
  ready: false,
  listeners: [] as Listeners<[SceneEvent]>,
  beforeFrame: [] as Listeners<[number]>,
  afterFrame: [] as Listeners<[]>,
  renders: 0,
  frameCosts: [] as number[],
  trailLimit: Infinity,
  viser: null as ReadyViser | null,
  renderer: null as Renderer | null,
  vehicle: null as FollowJson | null,
  ref: (name: string | null | undefined): Object3D | null => ref(name),
  toThree: (p: V3): Vec3 => toThree(p),
  setView: (name: string, follow?: boolean): void => setView(name, follow),
};
let V3c: Vec3Constructor | null = null;
let followPoint: Vec3 | null = null, lastFrame: number | null = -1, lastFollow = 0, drawStart: number | null = null;

function ref(name: string | null | undefined): Object3D | null {
  const viser = scene.viser;
  return typeof name === "string" && viser ? viser.nodeRefFromName[name] ?? null : null;
}

function toThree(p: V3): Vec3 {  // a world point (z up) to three.js's frame: viser turns its root to y up
  const viser = scene.viser!;
  const v = new V3c!(p[0], p[1], p[2]);
  const pose = viser.nodePoseData[""];  // the root's pose as the server set it, applied or not yet
  if (!pose) return v;
  const [w, x, y, z] = pose.wxyz;
  return v.applyQuaternion(viser.camera.quaternion.clone().set(x, y, z, w));
}

function setView(name: string, followIt: boolean | undefined): void {
  const follow = followIt ?? scene.follow;
  const view = scene.views.find((v) => v.name === name) ?? scene.views[0];
  const viser = scene.viser;
  if (!view || !viser) return;
  scene.view = view; scene.follow = follow;
  localStorage.setItem(STORE_VIEW, view.name);
  localStorage.setItem(STORE_FOLLOW, follow ? "follow" : "fixed");
  let position: V3 = view.position, target: V3 = view.look_at;
  const node = view.follow && follow ? ref(view.follow.node) : null;
  if (node && view.follow) {
    target = node.position.toArray();
    const offset = view.follow.offset;
    position = target.map((v, i) => v + offset[i]!) as V3;
  }
  const p = toThree(position), t = toThree(target);
  void viser.cameraControl.setLookAt(p.x, p.y, p.z, t.x, t.y, t.z, false);
  followPoint = null;
  notify(scene.listeners, { type: "view", view: view.name, follow });
}

function followCamera(viser: ReadyViser, node: Object3D, now: number): void {
  const cc = viser.cameraControl;
  const goal = node.getWorldPosition(new V3c!(0, 0, 0));
  const dt = Math.min(Math.max((now - lastFollow) / 1000, 0), 0.2);
  lastFollow = now;
  if (!followPoint) followPoint = cc.getTarget(new V3c!(0, 0, 0));
  if (followPoint.distanceTo(goal) < FOLLOW_SLACK_M) return;
  followPoint.lerp(goal, 1 - Math.exp(-dt / FOLLOW_TAU_S));
  void cc.moveTo(followPoint.x, followPoint.y, followPoint.z, false);
  cc.update(0);  // this frame, not the next: the camera and the drone move together
  viser.camera.updateMatrixWorld();
}

function limitTrail(): void {
  const trail = ref(scene.vehicle?.trail);
  if (!trail) return;
  trail.traverse((o) => {
    if (o.geometry?.isInstancedBufferGeometry) o.geometry.instanceCount = scene.trailLimit;
  });
}

function beforeRender(viser: ReadyViser, renderer: Renderer): void {
  const now = document.timeline.currentTime as number | null;
  if (now === lastFrame) return;  // once per frame, however many passes draw it
  lastFrame = now;
  drawStart = performance.now();
  scene.renderer = renderer;
  scene.renders++;
  poses.sync();  // the newest poses the worker has, for this frame
  const drone = ref(scene.vehicle?.node);
  const latest = poses.latest();
  if (drone && latest && poses.nowEpochMs() - latest.arrived < POSE_STALE_MS) {
    const pose = poses.poseAt(poses.nowEpochMs() - DISPLAY_DELAY_MS)!;
    drone.position.set(pose.p[0], pose.p[1], pose.p[2]);
    drone.quaternion.set(pose.q[1], pose.q[2], pose.q[3], pose.q[0]);
    drone.updateMatrixWorld(true);
    const before = poses.poseAt(poses.nowEpochMs() - DISPLAY_DELAY_MS - MOTION_WINDOW_MS)!;
    const moved = Math.hypot(...pose.p.map((v, i) => v - before.p[i]!));
    const dot = Math.min(1, Math.abs(pose.q.reduce((d, v, i) => d + v * before.q[i]!, 0)));
    if (moved > MOVED_M || 2 * Math.acos(dot) > TURNED_RAD) viser.requestRender();
  }
  notify(scene.beforeFrame, now ?? 0);
  if (drone && scene.follow && scene.view?.follow) followCamera(viser, drone, now ?? 0);
  limitTrail();
}

// A task posted while drawing runs once the frame is committed (in software WebGL, after the
// picture has been read back from the renderer): the main thread's whole cost of the frame,
// which keys and poses wait behind. quality.ts keeps it short.
const frameChannel = new MessageChannel();
frameChannel.port1.onmessage = (ev: MessageEvent<number>) => {
  scene.frameCosts.push(performance.now() - ev.data);
  if (scene.frameCosts.length > KEEP_FRAMES) scene.frameCosts.shift();
};
function afterRender(): void {
  if (drawStart === null) return;
  frameChannel.port2.postMessage(drawStart);
  drawStart = null;
  notify(scene.afterFrame);
}

function hook(viser: ReadyViser, three: Scene): void {
  const before = three.onBeforeRender, after = three.onAfterRender;
  three.onBeforeRender = function (renderer, ...rest) { before.call(this, renderer, ...rest); beforeRender(viser, renderer); };
  three.onAfterRender = function (...args) { after.apply(this, args); afterRender(); };
}

const isReady = (viser: ViserMutable | undefined): viser is ReadyViser =>
  !!viser && !!viser.scene && !!viser.cameraControl && !!viser.camera;

/** Wait for viser's scene, camera controls and the labs' nodes, then take over the camera. */
export function startScene(): void {
  const start = async (): Promise<void> => {
    const views = await (await fetch("/page/views")).json() as PageViews;
    scene.views = views.views;
    const followed = scene.views.find((v) => v.follow);
    scene.vehicle = followed?.follow ?? null;
    const wanted = localStorage.getItem(STORE_VIEW);
    const first = scene.views.some((v) => v.name === wanted) ? wanted! : views.suggested ?? "";
    const labNodes = (viser: ViserMutable): number =>
      Object.keys(viser.nodeRefFromName).filter((n) => n.split("/").length > 2).length;
    const poll = (): void => {
      const viser = viserMutable();
      if (!isReady(viser) || labNodes(viser) === 0) {
        setTimeout(poll, 100);
        return;
      }
      scene.viser = viser;
      V3c = viser.camera.position.constructor as Vec3Constructor;
      hook(viser, viser.scene);
      // viser applies its initial camera in an effect after the scene arrives: go after it.
      requestAnimationFrame(() => requestAnimationFrame(() => {
        setView(first, scene.follow);
        scene.ready = true;
        notify(scene.listeners, { type: "ready" });
      }));
    };
    poll();
  };
  start().catch((err) => console.error("teleop: no camera views", err));
}
