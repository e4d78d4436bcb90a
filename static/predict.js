// The setpoint a key will give, worked out in the page the moment the key goes down, so the
// marker can move in the next frame instead of after the round trip through the bus. It mirrors
// the drone keyboard manager's rules (server/packages/simple_control/keyboard_manager.py) with its
// live parameters, read from the REST API; the setpoint the bus then publishes corrects it.
(() => {
  "use strict";
  const DIRECTIONS = { ArrowRight: [1, 0, 0], ArrowLeft: [-1, 0, 0], ArrowUp: [0, 1, 0], ArrowDown: [0, -1, 0],
    PageUp: [0, 0, 1], w: [0, 0, 1], PageDown: [0, 0, -1], s: [0, 0, -1] };
  const START_M = [0, 0, 3];
  const ARENA_MIN_M = [-10, -10, 0], ARENA_MAX_M = [10, 10, 15];
  const PARAMS_POLL_MS = 3000;
  const MATCH_M = 0.1;  // a bus setpoint this close to the prediction confirms it
  const GRACE_MS = 250;  // a differing bus setpoint wins only after this (lab mode publishes the old one first)
  const EXPIRE_MS = 1000;  // no confirmation by then: the bus setpoint is what the drone flies to
  const state = { params: null, node: null, prediction: null, listeners: [], made: 0, confirmed: 0, overruled: 0 };
  window.__teleopPredict = state;
  const poses = window.__teleopPoses;

  const findManager = async () => {
    const graph = await (await fetch("/api/graph")).json();
    const pubs = new Set(graph.edges.filter((e) => e.kind === "publish" && e.to === "/uav/input/position").map((e) => e.from));
    const subs = graph.edges.filter((e) => e.kind === "subscribe" && e.from === "/keydown").map((e) => e.to);
    return subs.filter((n) => pubs.has(n));
  };
  const pollParams = async () => {  // the params stay as they were until the poll has new ones
    try {
      for (const name of state.node ? [state.node] : await findManager()) {
        const r = await fetch("/api/nodes/" + name.replace(/^\//, ""));
        const info = r.ok ? await r.json() : null;
        if (info && info.state === "active" && "hold_speed_m_s" in info.parameters) {
          state.node = name; state.params = info.parameters; return;
        }
      }
      state.node = null; state.params = null;  // gone, or renamed: look again next time
    } catch (err) { console.warn("teleop: no keyboard manager parameters", err); }
  };
  pollParams();
  setInterval(pollParams, PARAMS_POLL_MS);

  const clamp = (p) => p.map((v, i) => Math.min(Math.max(v, ARENA_MIN_M[i]), ARENA_MAX_M[i]));
  // Where the marker stands now: the live prediction, else the bus's setpoint, else where the
  // server drew the marker (static/scene.js sets markerPosition), else the manager's start.
  state.markerPosition = () => null;
  state.current = () => (state.prediction ? state.prediction.p : (poses.setpoint || state.markerPosition() || START_M));

  const predict = (held, key, down) => {
    const prm = state.params;
    const move = DIRECTIONS[key];
    if (!prm || !move) return null;
    const here = state.current();
    if (prm.mode !== "hold") {
      if (!down || (prm.mode === "lab" && move[2] !== 0)) return null;  // the handout moves in x and y only
      return clamp(here.map((v, i) => v + move[i] * prm.step_m));
    }
    const latest = poses.latest();
    if (!latest) return null;
    const dirs = [...held].map((k) => DIRECTIONS[k]).filter(Boolean);
    if (!dirs.length) {  // the last move key came up: stop where the drone will come to rest
      if (down) return null;
      const pose = poses.poseAt(poses.nowEpochMs());
      return clamp(latest.p.map((v, i) => v + (pose ? pose.v[i] : 0) * prm.brake_s));
    }
    const dir = [0, 1, 2].map((i) => dirs.reduce((s, d) => s + d[i], 0));
    const norm = Math.max(Math.hypot(...dir), 1e-9);
    const lead = prm.hold_speed_m_s * prm.lead_s;
    return clamp([0, 1, 2].map((i) => (dir[i] ? latest.p[i] + (dir[i] / norm) * lead : here[i])));
  };

  // keys.js calls this for every key, after sending it to the server.
  const onKey = (e, k) => {
    if (e.repeat) return;
    const held = window.__teleopKeys ? window.__teleopKeys.held : new Set();
    const p = predict(held, k, e.type === "keydown");
    if (!p) return;
    state.prediction = { p, made: performance.now(), key: e.type === "keydown" ? e : null };
    state.made++;
    for (const listener of state.listeners) {
      try { listener(state.prediction); } catch (err) { console.error(err); }
    }
  };
  if (window.__teleopKeys) window.__teleopKeys.listeners.push(onKey);

  // The bus's setpoint confirms the prediction (close to it) or, after a grace time, overrules it.
  poses.listeners.push((_samples, setpoint, received) => {
    const pred = state.prediction;
    if (!pred) return;
    if (setpoint && Math.hypot(...setpoint.p.map((v, i) => v - pred.p[i])) < MATCH_M) {
      state.prediction = null; state.confirmed++;
    } else if ((setpoint && received - pred.made > GRACE_MS) || received - pred.made > EXPIRE_MS) {
      state.prediction = null; state.overruled++;
    }
  });
  setInterval(() => {
    if (state.prediction && performance.now() - state.prediction.made > EXPIRE_MS) {
      state.prediction = null; state.overruled++;
    }
  }, 250);
})();
