// The student's workbench: the lab page as panes that share the window, never on top of one
// another. A toolbar across the top (the guide's header when it is folded, the tools link, the
// world's controls, the code and tools toggles, the help), and below it, side by side: the guide,
// the 3D scene (viser's #root, with the HUD in its corner) and the code view (tree, editor and the
// run's output). split.js draws the gutters between them; the sizes the student drags to are
// saved in the browser for each set of open panes.
//
// Folding: the guide folds to its header, which moves into the toolbar; the code view closes
// to its toggle. Each change of the open panes lays the splits out again, and viser's canvas
// follows its pane's size (it measures its container).
import Split from "split.js";
import { guide } from "../guide/panel";
import { LAYOUT_EVENT } from "./layout";
import { scene } from "./scene";

const STORE_SIZES = "teleop.workbench.sizes";
const GUTTER_PX = 6;
/** The smallest each pane is dragged to (px). */
const MIN_PX: Record<PaneName, number> = { guide: 200, scene: 320, code: 320 };
/** The first sizes of each set of open panes (% of the width): the scene keeps the most. */
const DEFAULT_SIZES: Record<string, number[]> = {
  "guide,scene,code": [17, 47, 36],
  "guide,scene": [24, 76],
  "scene,code": [55, 45],
  scene: [100],
};
const RESET_ROCKET_URL = "/api/rocket/reset";
const ROCKET_VIEW = "Rocket";
const RESET_SHOWN_MS = 1500;

export type PaneName = "guide" | "scene" | "code";

export const workbench = {
  /** The panes shown now, left to right. */
  open: [] as PaneName[],
  /** Their sizes, % of the width, as split.js last laid them out. */
  sizes: [] as number[],
  el: null as HTMLElement | null,
  toolbar: null as HTMLElement | null,
  panes: {} as Partial<Record<PaneName, HTMLElement>>,
  /** The code view's open state, set by codeview.ts; the panes follow it. */
  codeOpen: false,
  arrange: (): void => arrange(),
  resetRocket: (): Promise<boolean> => resetRocket(),
};

let split: ReturnType<typeof Split> | null = null;
let openKey = "";

const savedSizes = (): Record<string, number[]> => {
  try {
    return JSON.parse(localStorage.getItem(STORE_SIZES) ?? "{}") as Record<string, number[]>;
  } catch {
    return {};
  }
};
const saveSizes = (key: string, sizes: number[]): void => {
  localStorage.setItem(STORE_SIZES, JSON.stringify({ ...savedSizes(), [key]: sizes.map((s) => Math.round(s * 10) / 10) }));
};

const keepKeyboard = (e: HTMLElement): void => {
  e.tabIndex = -1;  // never tabbed to, and a click leaves the keyboard with the 3D view
  e.addEventListener("mousedown", (ev) => ev.preventDefault());
};
const toolButton = (id: string, label: string, title: string, onClick: () => void): HTMLButtonElement => {
  const b = document.createElement("button");
  b.type = "button"; b.id = id; b.textContent = label; b.title = title;
  keepKeyboard(b);
  b.addEventListener("click", () => { onClick(); b.blur(); });
  return b;
};

/** The guide where its fold says: its pane when open, the toolbar's slot when folded. */
function placeGuide(): boolean {
  const el = document.getElementById("teleop-guide");
  const pane = workbench.panes.guide, slot = document.getElementById("teleop-toolbar-guide");
  if (!el || !pane || !slot) return false;
  const home = guide.folded ? slot : pane;
  if (el.parentElement !== home) home.append(el);
  return !guide.folded;
}

/** Lay the splits out for the panes open now; the saved sizes of this set, else its defaults. */
function arrange(): void {
  const panes = workbench.panes;
  if (!panes.scene) return;
  const open: PaneName[] = [];
  if (placeGuide()) open.push("guide");
  open.push("scene");
  if (workbench.codeOpen && panes.code) open.push("code");
  const key = open.join(",");
  if (key === openKey && split) return;
  split?.destroy();
  split = null;
  for (const name of ["guide", "scene", "code"] as const) {
    const pane = panes[name];
    if (!pane) continue;
    pane.hidden = !open.includes(name);
    pane.style.width = "";
  }
  const saved = savedSizes()[key];
  const sizes = saved?.length === open.length ? saved : DEFAULT_SIZES[key]!;
  workbench.open = open; workbench.sizes = sizes;
  openKey = key;
  if (open.length === 1) panes.scene.style.width = "100%";  // alone: split.js sizes only two or more
  else {
    split = Split(open.map((n) => panes[n]!), {
      sizes, minSize: open.map((n) => MIN_PX[n]), gutterSize: GUTTER_PX, snapOffset: 0,
      gutter: () => { const g = document.createElement("div"); g.className = "teleop-gutter"; g.title = "Drag to size the panes"; return g; },
      onDrag: () => dispatchEvent(new Event(LAYOUT_EVENT)),
      onDragEnd: (s) => { workbench.sizes = s; saveSizes(key, s); dispatchEvent(new Event("resize")); },
    });
  }
  dispatchEvent(new Event("resize"));  // viser's canvas and the overlays follow the new size
}

async function resetRocket(): Promise<boolean> {
  const b = document.getElementById("teleop-reset-rocket");
  try {
    const ok = (await fetch(RESET_ROCKET_URL, { method: "POST" })).ok;
    if (b) { b.dataset.done = ok ? "ok" : "failed"; setTimeout(() => delete b.dataset.done, RESET_SHOWN_MS); }
    return ok;
  } catch {
    return false;
  }
}

/** Toggle viser's control panel (telemetry, plots, Teleop, Message Publisher, Recording). */
function toggleTools(): void {
  const expand = document.querySelector<HTMLElement>('[aria-label="Expand panel"]');
  const minimise = document.querySelector<HTMLElement>('[aria-label="Minimize panel"]');
  (expand ?? minimise)?.click();
  setTimeout(() => dispatchEvent(new Event(LAYOUT_EVENT)), 100);
}

function buildToolbar(): HTMLElement {
  const bar = document.createElement("header");
  bar.id = "teleop-toolbar";
  bar.setAttribute("aria-label", "Lab toolbar");
  const guideSlot = document.createElement("div");
  guideSlot.id = "teleop-toolbar-guide";
  const spacer = document.createElement("span");
  spacer.className = "spacer";
  const world = document.createElement("div");
  world.className = "world";
  world.setAttribute("role", "group");
  world.setAttribute("aria-label", "World");
  const reset = toolButton("teleop-reset-rocket", "Reset rocket", "The rocket back on its pad; the countdown starts again",
    () => void resetRocket());
  reset.hidden = true;  // shown once the views say there is a rocket
  world.append(reset);
  const tools = toolButton("teleop-tools-toggle", "Panel", "Show or hide the lab's panel: telemetry, plots, Teleop, Message Publisher, Recording",
    toggleTools);
  const help = toolButton("teleop-help-toggle", "?", "The keys", () => {
    const h = document.getElementById("teleop-help");
    if (h) { h.hidden = !h.hidden; dispatchEvent(new Event(LAYOUT_EVENT)); }
  });
  bar.append(guideSlot, spacer, world, tools, help);
  scene.listeners.push((event) => {
    if (event.type === "ready") reset.hidden = !scene.views.some((v) => v.name === ROCKET_VIEW);
  });
  return bar;
}

function build(): void {
  if (document.getElementById("teleop-workbench")) return;
  const root = document.getElementById("root");
  const wb = document.createElement("div");
  wb.id = "teleop-workbench";
  const toolbar = buildToolbar();
  const row = document.createElement("div");
  row.id = "teleop-panes";
  const guidePane = document.createElement("aside");
  guidePane.id = "teleop-pane-guide";
  guidePane.className = "teleop-pane";
  guidePane.setAttribute("aria-label", "Guide pane");
  const scenePane = document.createElement("main");
  scenePane.id = "teleop-pane-scene";
  scenePane.className = "teleop-pane";
  scenePane.setAttribute("aria-label", "3D scene");
  row.append(guidePane, scenePane);
  wb.append(toolbar, row);
  document.body.prepend(wb);
  if (root) scenePane.append(root);  // viser's React root keeps its handle on the element
  const hud = document.getElementById("teleop-hud");
  if (hud) scenePane.append(hud);
  const link = document.getElementById("teleop-nav-tools");
  if (link) toolbar.insertBefore(link, toolbar.querySelector(".spacer"));
  workbench.el = wb; workbench.toolbar = toolbar;
  workbench.panes = { guide: guidePane, scene: scenePane };
  const code = document.getElementById("teleop-code");
  if (code) { row.append(code); workbench.panes.code = code; code.classList.add("teleop-pane"); }
  const tab = document.getElementById("teleop-code-tab");
  if (tab) toolbar.insertBefore(tab, toolbar.querySelector("#teleop-tools-toggle"));
  arrange();
}

/** Build the workbench once the page has a body and our overlays are in it; keep the guide's
 * pane with its fold. */
export function startWorkbench(): void {
  addEventListener(LAYOUT_EVENT, () => { if (workbench.el) arrange(); });
  if (document.body) build();
  else addEventListener("DOMContentLoaded", build);  // on window: after the overlays' own (document, window) listeners
}
