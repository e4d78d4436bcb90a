// The code view's place in the lab page: a "Code" toggle in the workbench's toolbar, and a pane
// of the workbench (workbench.ts) beside the 3D view, sized by the gutter between them. The
// editor itself (web/src/editor, CodeMirror) is a bundle of its own, loaded the first time the
// pane opens, so the lab page's first load stays light. Whether it was open is kept in the
// browser: a reload opens it again.
//
// The pane owns its keys: keys.ts sends none typed in it to the lab's keyboard, and its keydown
// and keyup stop at its edge, so viser's camera keys do not move the view while the student types.
import type { CodeViewHandle } from "../editor/main";
import { workbench } from "./workbench";

/** The attribute keys.ts looks for: keys typed inside such an element never fly the drone. */
export const OWN_KEYS_ATTR = "data-teleop-own-keys";
const EDITOR_BUNDLE = "/static/build/editor.js";
/** Whether the code view was open, kept in the browser so a reload brings it back as it was. */
const STORE_OPEN = "teleop.code.open";
const CSS = `
  #teleop-code {
    box-sizing: border-box; display: flex; flex-direction: column; min-width: 0; background: #fff; color: #222;
    font: 13px/1.4 system-ui, sans-serif;
  }
  #teleop-code[hidden] { display: none; }
  #teleop-code > .loading { padding: 12px; }
`;

export const codeview = {
  open: false,
  loaded: false,
  error: null as string | null,
};

let panel: HTMLElement | null = null;
let tab: HTMLButtonElement | null = null;
let handle: CodeViewHandle | null = null;

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

const wasOpen = (): boolean => {
  try {
    return localStorage.getItem(STORE_OPEN) === "1";
  } catch {
    return false;  // storage refused (a private window's policy): the view starts closed
  }
};
const keepOpen = (open: boolean): void => {
  try {
    localStorage.setItem(STORE_OPEN, open ? "1" : "0");
  } catch {
    // storage refused: the state lasts as long as the page
  }
};

function setOpen(open: boolean): void {
  if (!panel || !tab) return;
  codeview.open = open;
  keepOpen(open);
  panel.hidden = !open;
  tab.setAttribute("aria-pressed", String(open));
  tab.setAttribute("aria-expanded", String(open));
  workbench.codeOpen = open;
  workbench.arrange();
  if (open && !codeview.loaded && !codeview.error && !panel.dataset.loading) {
    panel.dataset.loading = "1";
    void loadEditor(panel);
  }
  handle?.shown(open);
}

function addPanel(): void {
  if (document.getElementById("teleop-code")) return;
  const style = document.createElement("style");
  style.textContent = CSS;
  tab = document.createElement("button");
  tab.id = "teleop-code-tab";
  tab.type = "button";
  tab.textContent = "</> Code";
  tab.title = "Your workspace: edit, run and stop your own nodes (opens or closes the code pane)";
  tab.tabIndex = -1;  // as the tools link: a click never leaves keyboard focus on it
  tab.addEventListener("mousedown", (e) => e.preventDefault());
  tab.setAttribute("aria-pressed", "false");
  tab.addEventListener("click", () => { setOpen(!codeview.open); tab?.blur(); });
  panel = document.createElement("section");
  panel.id = "teleop-code";
  panel.hidden = true;
  panel.setAttribute(OWN_KEYS_ATTR, "");
  panel.setAttribute("aria-label", "Code view");
  for (const type of ["keydown", "keyup", "keypress"]) panel.addEventListener(type, (e) => e.stopPropagation());
  document.head.append(style);
  document.body.append(panel, tab);
  if (wasOpen()) setOpen(true);  // the workbench, built next, lays the pane out
}

/** Add the tab and the (closed) panel once the page has a body. */
export function startCodeView(): void {
  if (document.body) addPanel();
  else document.addEventListener("DOMContentLoaded", addPanel);
}
