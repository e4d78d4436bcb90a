// What the page uses of viser's client (viser 1.1.1): the scene, camera and controls it
// publishes on window.__viserMutable for end-to-end tests, and its test points (uPlot charts,
// dev settings). Only the members the page touches are declared; they are three.js objects and
// camera-controls' API, read at run time from viser's own bundle, never bundled here.

/** A three.js Vector3 (viser's instance: the page has no three.js of its own). */
export interface Vec3 {
  x: number;
  y: number;
  z: number;
  set(x: number, y: number, z: number): Vec3;
  toArray(): [number, number, number];
  applyQuaternion(q: Quat): Vec3;
  distanceTo(v: Vec3): number;
  project(camera: Camera): Vec3;
  lerp(v: Vec3, alpha: number): Vec3;
}

export interface Quat {
  set(x: number, y: number, z: number, w: number): Quat;
  clone(): Quat;
}

export interface Object3D {
  position: Vec3;
  quaternion: Quat;
  geometry?: { isInstancedBufferGeometry?: boolean; instanceCount: number };
  updateMatrixWorld(force?: boolean): void;
  getWorldPosition(target: Vec3): Vec3;
  traverse(visit: (o: Object3D) => void): void;
}

export interface Camera extends Object3D {
  fov: number;
  updateMatrixWorld(): void;
}

/** The renderer three.js hands the scene's onBeforeRender; the page may wrap its render. */
export interface Renderer {
  render(...args: unknown[]): unknown;
  __teleopRender?: (...args: unknown[]) => unknown;
}

export type RenderHook = (this: unknown, renderer: Renderer, ...rest: unknown[]) => void;

export interface Scene {
  onBeforeRender: RenderHook;
  onAfterRender: (this: unknown, ...args: unknown[]) => void;
}

export interface CameraControl {
  setLookAt(px: number, py: number, pz: number, tx: number, ty: number, tz: number, smooth: boolean): unknown;
  getTarget(out: Vec3): Vec3;
  moveTo(x: number, y: number, z: number, smooth: boolean): unknown;
  update(delta: number): boolean;
}

export interface ViserMutable {
  scene?: Scene;
  camera?: Camera;
  cameraControl?: CameraControl;
  canvas?: HTMLCanvasElement;
  nodeRefFromName: Record<string, Object3D | undefined>;
  nodePoseData: Record<string, { wxyz: [number, number, number, number] } | undefined>;
  requestRender(): void;
}

export interface UPlotChart {
  setData(...args: unknown[]): unknown;
  __teleopSetData?: (...args: unknown[]) => unknown;
  __teleopMinMs?: number;
}

export interface ViserTestpoints {
  uplots?: Record<string, { chart: UPlotChart }>;
  devSettings?: { set(settings: { fixedDpr: number }): void };
}

declare global {
  interface Window {
    __viserMutable?: ViserMutable;
    __viserTestpoints?: ViserTestpoints;
  }
}

/** viser's scene handles, once its client has built them. */
export const viserMutable = (): ViserMutable | undefined => window.__viserMutable;
export const viserTestpoints = (): ViserTestpoints | undefined => window.__viserTestpoints;
