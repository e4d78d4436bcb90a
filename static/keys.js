// Key capture for the lab page: every key press goes to the server's keyboard over /ws/keys,
// as keydown/keyup frames, with sided modifier flags. The keys viser's camera would also take
// (arrows, WASDQE, space, page up/down) are stopped here, in the capture phase on window,
// before viser's listeners see them. A blur or a hidden tab releases every held key. The HUD
// (static/hud.js) shows the channel's state and the keys held.
(() => {
  "use strict";
  const CAMERA_KEYS = new Set(["ArrowUp", "ArrowDown", "ArrowLeft", "ArrowRight", "a", "d", "w", "s", "q", "e",
    " ", "PageUp", "PageDown"]);
  const SIDED = { Shift: ["lshift", "rshift"], Control: ["lctrl", "rctrl"], Alt: ["lalt", "ralt"], Meta: ["lmeta", "rmeta"] };
  const HEARTBEAT_MS = 200;
  // listeners: other page scripts (the HUD) see each key here, since this script stops the event.
  const state = { connected: false, held: new Set(), sent: 0, errors: [], listeners: [] };
  window.__teleopKeys = state;
  const mods = { lshift: false, rshift: false, lctrl: false, rctrl: false, lalt: false, ralt: false, lmeta: false, rmeta: false };
  let ws = null;
  let retryMs = 250;

  const send = (frame) => {
    if (ws && ws.readyState === WebSocket.OPEN) { ws.send(JSON.stringify(frame)); state.sent++; }
  };
  const connect = () => {
    ws = new WebSocket((location.protocol === "https:" ? "wss://" : "ws://") + location.host + "/ws/keys");
    ws.onopen = () => { state.connected = true; retryMs = 250; };
    ws.onmessage = (ev) => { try { const f = JSON.parse(ev.data); if (f.type === "error") state.errors.push(f.error); } catch (_) {} };
    ws.onclose = () => {
      state.connected = false; state.held.clear();
      setTimeout(connect, retryMs); retryMs = Math.min(retryMs * 2, 5000);
    };
  };
  const typingInForm = (t) => t && (/^(INPUT|TEXTAREA|SELECT)$/.test(t.tagName) || t.isContentEditable);
  const keyName = (e) => (e.key.length === 1 ? e.key.toLowerCase() : e.key);

  const onKey = (e) => {
    if (typingInForm(e.target) || e.key === "Unidentified" || e.key === "Dead") return;
    const k = keyName(e);
    if (SIDED[e.key]) mods[SIDED[e.key][e.location === 2 ? 1 : 0]] = e.type === "keydown";
    if (CAMERA_KEYS.has(k)) { e.stopImmediatePropagation(); e.preventDefault(); }
    if (e.type === "keydown") state.held.add(k); else state.held.delete(k);
    const frame = { type: e.type, key: e.key, code: e.code, location: e.location, ...mods,
      caps: e.getModifierState("CapsLock"), num: e.getModifierState("NumLock"), t: performance.now() };
    if (e.repeat) frame.repeat = true;
    send(frame);
    for (const listener of state.listeners) { try { listener(e, k); } catch (err) { console.error(err); } }
  };
  const releaseAll = () => {
    if (state.held.size) send({ type: "release_all" });
    state.held.clear();
    for (const m of Object.keys(mods)) mods[m] = false;
  };

  addEventListener("keydown", onKey, true);
  addEventListener("keyup", onKey, true);
  addEventListener("blur", releaseAll);
  document.addEventListener("visibilitychange", () => { if (document.hidden) releaseAll(); });
  addEventListener("pagehide", releaseAll);
  setInterval(() => send({ type: "heartbeat" }), HEARTBEAT_MS);
  connect();
})();
