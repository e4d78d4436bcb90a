// The code view's place in the lab page: a "Code" tab at the bottom right, and a panel on the
// right that the student sizes by dragging its left edge, with the 3D view beside it (viser's
// root shrinks to the space left). The editor itself (web/src/editor, CodeMirror) is a bundle of
// its own, loaded the first time the panel opens, so the lab page's first load stays light.
//
// The panel owns its keys: keys.ts sends none typed in it to the lab's keyboard, and its keydown
// and keyup stop at its edge, so viser's camera keys do not move the view while the student types.
import type { CodeViewHandle } from "../editor/main";

/** The attribute keys.ts looks for: keys typed inside such an element never fly the drone. */
export const OWN_KEYS_ATTR = "data-teleop-own-keys";
const EDITOR_BUNDLE = "/static/build/editor.js";
const WIDTH_KEY = "teleop.codeview.width";
const MIN_PX = 320;
const MIN_VIEW_PX = 240;  // the 3D view keeps at least this much
const CSS = `
  #teleop-code-tab {
    position: fixed; right: 14px; bottom: 14px; z-index: 1002; padding: 5px 12px; border-radius: 6px;
    font: 13px/1.3 system-ui, sans-serif; border: 1px solid #1f5fbf; cursor: pointer;
    background: rgba(255, 255, 255, 0.92); color: #1f5fbf; box-shadow: 0 1px 4px rgba(0, 0, 0, 0.25);
  }
  #teleop-code-tab[hidden] { display: none; }
  #teleop-code {
    position: fixed; top: 0; right: 0; bottom: 0; z-index: 1003; box-sizing: border-box;
    display: flex; flex-direction: column; background: #fff; color: #222;
    border-left: 1px solid #bbb; box-shadow: -2px 0 8px rgba(0, 0, 0, 0.15);
    font: 13px/1.4 system-ui, sans-serif;
  }
  #teleop-code[hidden] { display: none; }
  #teleop-code > .grip {
    position: absolute; left: -4px; top: 0; bottom: 0; width: 8px; cursor: col-resize; z-index: 2;
  }
  #teleop-code > .loading { padding: 12px; }
`;

export const codeview = {
  open: false,
  loaded: false,
  widthPx: 0,
  error: null as string | null,
};

let panel: HTMLElement | null = null;
let tab: HTMLButtonElement | null = null;
let handle: CodeViewHandle | null = null;

const clampWidth = (px: number): number =>
  Math.round(Math.max(MIN_PX, Math.min(px, window.innerWidth - MIN_VIEW_PX)));

/** Give viser's root (the 3D view and its panel) the room the code view leaves. */
const fitView = (): void => {
  const root = document.getElementById("root");
  const width = codeview.open ? clampWidth(codeview.widthPx) : 0;
  if (panel) panel.style.width = `${width}px`;
  if (root) root.style.width = width ? `calc(100% - ${width}px)` : "";
  dispatchEvent(new Event("resize"));  // viser's canvas and the overlays' layout follow the size
};

const loadEditor = async (host: HTMLElement): Promise<void> => {
  const loading = document.createElement("div");
  loading.className = "loading";
  loading.textContent = "Loading the editor ...";
  host.append(loading);
  try {
    const url: string = EDITOR_BUNDLE;  // a runtime address: the editor is a bundle of its own
    const editor = (await import(url)) as typeof import("../editor/main");
    loading.remove();
    handle = editor.mountCodeView(host, { close: () => setOpen(false) });
    codeview.loaded = true;
  } catch (exc) {
    codeview.error = String(exc);
    loading.textContent = `The editor did not load: ${codeview.error}`;
  }
};

function setOpen(open: boolean): void {
  if (!panel || !tab) return;
  codeview.open = open;
  panel.hidden = !open;
  tab.hidden = open;
  tab.setAttribute("aria-expanded", String(open));
  fitView();
  if (open && !codeview.loaded && !codeview.error && !panel.dataset.loading) {
    panel.dataset.loading = "1";
    void loadEditor(panel);
  }
  handle?.shown(open);
}

const dragWidth = (grip: HTMLElement): void => {
  grip.addEventListener("pointerdown", (down) => {
    down.preventDefault();
    grip.setPointerCapture(down.pointerId);
    const move = (e: PointerEvent): void => {
      codeview.widthPx = clampWidth(window.innerWidth - e.clientX);
      fitView();
    };
    const up = (): void => {
      grip.removeEventListener("pointermove", move);
      localStorage.setItem(WIDTH_KEY, String(codeview.widthPx));
    };
    grip.addEventListener("pointermove", move);
    grip.addEventListener("pointerup", up, { once: true });
  });
};

function addPanel(): void {
  if (document.getElementById("teleop-code")) return;
  const style = document.createElement("style");
  style.textContent = CSS;
  tab = document.createElement("button");
  tab.id = "teleop-code-tab";
  tab.type = "button";
  tab.textContent = "</> Code";
  tab.title = "Your workspace: edit, run and stop your own nodes";
  tab.tabIndex = -1;  // as the tools link: a click never leaves keyboard focus on it
  tab.addEventListener("mousedown", (e) => e.preventDefault());
  tab.addEventListener("click", () => setOpen(true));
  panel = document.createElement("section");
  panel.id = "teleop-code";
  panel.hidden = true;
  panel.setAttribute(OWN_KEYS_ATTR, "");
  panel.setAttribute("aria-label", "Code view");
  for (const type of ["keydown", "keyup", "keypress"]) panel.addEventListener(type, (e) => e.stopPropagation());
  const grip = document.createElement("div");
  grip.className = "grip";
  grip.title = "Drag to size the code view";
  dragWidth(grip);
  panel.append(grip);
  const saved = Number(localStorage.getItem(WIDTH_KEY));
  codeview.widthPx = saved > 0 ? saved : Math.round(window.innerWidth * 0.5);
  document.head.append(style);
  document.body.append(panel, tab);
  addEventListener("resize", (e) => { if (e.isTrusted && codeview.open) fitView(); });
}

/** Add the tab and the (closed) panel once the page has a body. */
export function startCodeView(): void {
  if (document.body) addPanel();
  else document.addEventListener("DOMContentLoaded", addPanel);
}
