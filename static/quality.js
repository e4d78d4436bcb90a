// Keeps the page's frames short on a slow renderer by drawing less, never by handling keys or poses
// later: a ladder of levels, each lowering the pixel ratio of the 3D canvas, the drone's trail and
// how often the plots redraw. It steps down while frames cost the main thread more than BUDGET_MS
// and back up while they cost less than ROOM_MS. Software WebGL (no GPU, as SwiftShader or
// llvmpipe) starts two steps down. The pixel ratio goes through viser's own setting (its dev settings' fixedDpr),
// which also stops viser's adaptive ratio, whose floor (0.75) is too high for software WebGL.
(() => {
  "use strict";
  const LEVELS = [  // pixel ratio (× the screen's), trail segments, least ms between plot redraws
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
  const state = { level: 0, dpr: null, software: false, renderer: "", fps: null, frameMs: null, changes: 0, auto: true };
  window.__teleopQuality = state;

  const detectSoftware = () => {
    try {
      const gl = document.createElement("canvas").getContext("webgl");
      const info = gl && gl.getExtension("WEBGL_debug_renderer_info");
      state.renderer = info ? String(gl.getParameter(info.UNMASKED_RENDERER_WEBGL)) : "";
      const ext = gl && gl.getExtension("WEBGL_lose_context");
      if (ext) ext.loseContext();
    } catch (err) { state.renderer = ""; }
    return /swiftshader|llvmpipe|softpipe|software/i.test(state.renderer);
  };

  const throttlePlots = (minMs) => {
    const charts = (window.__viserTestpoints && window.__viserTestpoints.uplots) || {};
    for (const { chart } of Object.values(charts)) {
      if (!chart.__teleopSetData) {  // wrap once: keep the newest data, draw it at most every minMs
        const draw = chart.setData.bind(chart);
        let last = 0, timer = null, args = null;
        chart.__teleopSetData = draw;
        chart.setData = (...a) => {
          const wait = chart.__teleopMinMs - (performance.now() - last);
          if (wait <= 0) { last = performance.now(); return draw(...a); }
          args = a;
          if (!timer) timer = setTimeout(() => { timer = null; last = performance.now(); draw(...args); }, wait);
          return undefined;
        };
      }
      chart.__teleopMinMs = minMs;
    }
  };

  const apply = () => {
    const l = LEVELS[state.level];
    const dev = window.__viserTestpoints && window.__viserTestpoints.devSettings;
    state.dpr = Math.round(window.devicePixelRatio * l.dpr * 100) / 100;
    if (dev) dev.set({ fixedDpr: state.dpr });
    if (window.__teleopScene) window.__teleopScene.trailLimit = l.trail;
    throttlePlots(l.plotMs);
  };
  state.setLevel = (level, auto = state.auto) => {
    state.level = Math.max(0, Math.min(LEVELS.length - 1, level));
    state.auto = auto;
    state.changes++;
    apply();
  };

  // Once a second while the scene draws: the median of what its frames cost the main thread
  // (static/scene.js measures each, from drawing to commit). A key or a pose that comes in during
  // a frame waits for its end, so a frame must stay short, whatever the frame rate.
  let lastRenders = 0, lastT = performance.now(), slow = 0, fast = 0;
  const sample = () => {
    const scene = window.__teleopScene;
    const now = performance.now();
    const drawn = scene ? scene.renders - lastRenders : 0;
    const seconds = (now - lastT) / 1000;
    lastT = now;
    if (!scene) return;
    lastRenders = scene.renders;
    state.fps = drawn / seconds;
    if (drawn < MIN_FRAMES) { state.frameMs = null; return; }  // idle: nothing to judge by
    const recent = scene.frameCosts.slice(-drawn).sort((a, b) => a - b);
    state.frameMs = recent[Math.floor(recent.length / 2)];
    slow = state.frameMs > BUDGET_MS ? slow + 1 : 0;
    fast = state.frameMs < ROOM_MS ? fast + 1 : 0;
    if (!state.auto) return;
    if (slow >= DOWN_AFTER && state.level < LEVELS.length - 1) { state.setLevel(state.level + 1); slow = 0; }
    if (fast >= UP_AFTER && state.level > 0) { state.setLevel(state.level - 1); fast = 0; }
  };
  setInterval(sample, 1000);
  setInterval(() => throttlePlots(LEVELS[state.level].plotMs), 2000);  // plots opened later

  state.software = detectSoftware();
  const startWhenReady = () => {
    if (!window.__viserTestpoints || !window.__viserTestpoints.devSettings) { setTimeout(startWhenReady, 100); return; }
    state.setLevel(state.software ? SOFTWARE_START : 0);
  };
  startWhenReady();
})();
