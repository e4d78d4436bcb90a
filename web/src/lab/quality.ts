// Keeps the page's frames short on a slow renderer by drawing less, never by handling keys or poses
// later: a ladder of levels, each lowering the pixel ratio of the 3D canvas, the drone's trail and
// how often the plots redraw. It steps down while frames cost the main thread more than BUDGET_MS
// and back up while they cost less than ROOM_MS. Software WebGL (no GPU, as SwiftShader or
// llvmpipe) starts two steps down. The pixel ratio goes through viser's own setting (its dev
// settings' fixedDpr), which also stops viser's adaptive ratio, whose floor (0.75) is too high for
// software WebGL.
import { scene } from "./scene";
import { viserTestpoints } from "./viser";

interface Level { dpr: number; trail: number; plotMs: number }
const LEVELS: Level[] = [  // pixel ratio (× the screen's), trail segments, least ms between plot redraws
  { dpr: 1.0, trail: Infinity, plotMs: 0 },
  { dpr: 0.75, trail: 100, plotMs: 0 },
  { dpr: 0.6, trail: 60, plotMs: 500 },
  { dpr: 0.5, trail: 30, plotMs: 1000 },
  { dpr: 0.4, trail: 15, plotMs: 2000 },
];
const SOFTWARE_START = 2;
const BUDGET_MS = 25;  // a frame's cost on the main thread: above this, draw less ...
const ROOM_MS = 8;  // ... below this, draw more
const DOWN_AFTER = 2, UP_AFTER = 5;  // seconds in a row
const MIN_FRAMES = 5;  // a second with fewer frames drawn is idle, not slow

export const quality = {
  level: 0,
  dpr: null as number | null,
  software: false,
  renderer: "",
  fps: null as number | null,
  frameMs: null as number | null,
  changes: 0,
  auto: true,
  setLevel: (level: number, auto?: boolean): void => setLevel(level, auto),
};
const levelOf = (i: number): Level => LEVELS[i] ?? LEVELS[0]!;

const detectSoftware = (): boolean => {
  try {
    const gl = document.createElement("canvas").getContext("webgl");
    const info = gl?.getExtension("WEBGL_debug_renderer_info");
    quality.renderer = gl && info ? String(gl.getParameter(info.UNMASKED_RENDERER_WEBGL)) : "";
    gl?.getExtension("WEBGL_lose_context")?.loseContext();
  } catch { quality.renderer = ""; }
  return /swiftshader|llvmpipe|softpipe|software/i.test(quality.renderer);
};

const throttlePlots = (minMs: number): void => {
  const charts = viserTestpoints()?.uplots ?? {};
  for (const { chart } of Object.values(charts)) {
    if (!chart.__teleopSetData) {  // wrap once: keep the newest data, draw it at most every minMs
      const draw = chart.setData.bind(chart);
      let last = 0, timer: ReturnType<typeof setTimeout> | null = null, args: unknown[] = [];
      chart.__teleopSetData = draw;
      chart.setData = (...a: unknown[]): unknown => {
        const wait = (chart.__teleopMinMs ?? 0) - (performance.now() - last);
        if (wait <= 0) { last = performance.now(); return draw(...a); }
        args = a;
        timer ??= setTimeout(() => { timer = null; last = performance.now(); draw(...args); }, wait);
        return undefined;
      };
    }
    chart.__teleopMinMs = minMs;
  }
};

function setLevel(level: number, auto: boolean | undefined): void {
  quality.level = Math.max(0, Math.min(LEVELS.length - 1, level));
  quality.auto = auto ?? quality.auto;
  quality.changes++;
  apply();
}

function apply(): void {
  const l = levelOf(quality.level);
  quality.dpr = Math.round(window.devicePixelRatio * l.dpr * 100) / 100;
  viserTestpoints()?.devSettings?.set({ fixedDpr: quality.dpr });
  scene.trailLimit = l.trail;
  throttlePlots(l.plotMs);
}

// Once a second while the scene draws: the median of what its frames cost the main thread
// (scene.ts measures each, from drawing to commit). A key or a pose that comes in during
// a frame waits for its end, so a frame must stay short, whatever the frame rate.
let lastRenders = 0, lastT = performance.now(), slow = 0, fast = 0;
const sample = (): void => {
  const now = performance.now();
  const drawn = scene.renders - lastRenders;
  const seconds = (now - lastT) / 1000;
  lastT = now;
  lastRenders = scene.renders;
  quality.fps = drawn / seconds;
  if (drawn < MIN_FRAMES) { quality.frameMs = null; return; }  // idle: nothing to judge by
  const recent = scene.frameCosts.slice(-drawn).sort((a, b) => a - b);
  quality.frameMs = recent[Math.floor(recent.length / 2)] ?? null;
  slow = quality.frameMs !== null && quality.frameMs > BUDGET_MS ? slow + 1 : 0;
  fast = quality.frameMs !== null && quality.frameMs < ROOM_MS ? fast + 1 : 0;
  if (!quality.auto) return;
  if (slow >= DOWN_AFTER && quality.level < LEVELS.length - 1) { quality.setLevel(quality.level + 1); slow = 0; }
  if (fast >= UP_AFTER && quality.level > 0) { quality.setLevel(quality.level - 1); fast = 0; }
};

/** Judge the frames once a second, from the level software WebGL starts at. */
export function startQuality(): void {
  setInterval(sample, 1000);
  setInterval(() => throttlePlots(levelOf(quality.level).plotMs), 2000);  // plots opened later
  quality.software = detectSoftware();
  const startWhenReady = (): void => {
    if (!viserTestpoints()?.devSettings) { setTimeout(startWhenReady, 100); return; }
    quality.setLevel(quality.software ? SOFTWARE_START : 0);
  };
  startWhenReady();
}
