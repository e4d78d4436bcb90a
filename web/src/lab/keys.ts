// Key capture for the lab page: every key press goes to the server's keyboard over /ws/keys,
// as keydown/keyup frames, with sided modifier flags. The keys viser's camera would also take
// (arrows, WASDQE, space, page up/down) are stopped here, in the capture phase on window,
// before viser's listeners see them. A blur or a hidden tab releases every held key. The HUD
// (hud.ts) shows the channel's state and the keys held. Keys typed in a form field or in the code
// view (an element marked with codeview.ts's OWN_KEYS_ATTR) never reach the keyboard: only the
// 3D view flies the drone, and focus moving into the code view releases every held key.
import type { ControlFrame, KeyChannelError, KeyFrame } from "../protocol.gen";
import { OWN_KEYS_ATTR } from "./codeview";
import { notify, type Listeners } from "./listeners";

const CAMERA_KEYS = new Set(["ArrowUp", "ArrowDown", "ArrowLeft", "ArrowRight", "a", "d", "w", "s", "q", "e",
  " ", "PageUp", "PageDown"]);
type Modifier = "lshift" | "rshift" | "lctrl" | "rctrl" | "lalt" | "ralt" | "lmeta" | "rmeta";
const SIDED: Record<string, [Modifier, Modifier]> = {
  Shift: ["lshift", "rshift"], Control: ["lctrl", "rctrl"], Alt: ["lalt", "ralt"], Meta: ["lmeta", "rmeta"],
};
const HEARTBEAT_MS = 200;

/** A key as the page saw it, and its name (a letter in lower case). */
export type KeyListener = (e: KeyboardEvent, key: string) => void;

// listeners: other modules (the HUD, the prediction) see each key here, since this one stops the event.
export const keys = {
  connected: false,
  held: new Set<string>(),
  sent: 0,
  errors: [] as string[],
  listeners: [] as Listeners<[KeyboardEvent, string]>,
};

const mods: Record<Modifier, boolean> = {
  lshift: false, rshift: false, lctrl: false, rctrl: false, lalt: false, ralt: false, lmeta: false, rmeta: false,
};
let ws: WebSocket | null = null;
let retryMs = 250;

const send = (frame: KeyFrame | ControlFrame): void => {
  if (ws && ws.readyState === WebSocket.OPEN) { ws.send(JSON.stringify(frame)); keys.sent++; }
};
const connect = (): void => {
  ws = new WebSocket((location.protocol === "https:" ? "wss://" : "ws://") + location.host + "/ws/keys");
  ws.onopen = () => { keys.connected = true; retryMs = 250; };
  ws.onmessage = (ev: MessageEvent<string>) => {
    try {
      const f = JSON.parse(ev.data) as KeyChannelError;
      if (f.type === "error") keys.errors.push(f.error);
    } catch { /* not a frame of this channel */ }
  };
  ws.onclose = () => {
    keys.connected = false; keys.held.clear();
    setTimeout(connect, retryMs); retryMs = Math.min(retryMs * 2, 5000);
  };
};
const ownsKeys = (t: EventTarget | null): boolean => t instanceof Element && t.closest(`[${OWN_KEYS_ATTR}]`) !== null;
const typingInForm = (t: EventTarget | null): boolean => ownsKeys(t) ||
  (t instanceof HTMLElement && (/^(INPUT|TEXTAREA|SELECT)$/.test(t.tagName) || t.isContentEditable));
const keyName = (e: KeyboardEvent): string => (e.key.length === 1 ? e.key.toLowerCase() : e.key);

const onKey = (e: KeyboardEvent): void => {
  if (typingInForm(e.target) || e.key === "Unidentified" || e.key === "Dead") return;
  const k = keyName(e);
  const sided = SIDED[e.key];
  if (sided) mods[sided[e.location === 2 ? 1 : 0]] = e.type === "keydown";
  if (CAMERA_KEYS.has(k)) { e.stopImmediatePropagation(); e.preventDefault(); }
  if (e.type === "keydown") keys.held.add(k); else keys.held.delete(k);
  const frame: KeyFrame = { type: e.type === "keydown" ? "keydown" : "keyup", key: e.key, code: e.code,
    location: e.location, ...mods, caps: e.getModifierState("CapsLock"), num: e.getModifierState("NumLock"),
    t: performance.now() };
  if (e.repeat) frame.repeat = true;
  send(frame);
  notify(keys.listeners, e, k);
};
const releaseAll = (): void => {
  if (keys.held.size) send({ type: "release_all" });
  keys.held.clear();
  for (const m of Object.keys(mods) as Modifier[]) mods[m] = false;
};

/** Capture keys from now on, and keep the key channel open. */
export function startKeys(): void {
  addEventListener("keydown", onKey, true);
  addEventListener("keyup", onKey, true);
  addEventListener("blur", releaseAll);
  addEventListener("focusin", (e) => { if (ownsKeys(e.target)) releaseAll(); });
  document.addEventListener("visibilitychange", () => { if (document.hidden) releaseAll(); });
  addEventListener("pagehide", releaseAll);
  setInterval(() => send({ type: "heartbeat" }), HEARTBEAT_MS);
  connect();
}
