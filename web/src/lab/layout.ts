// Where things go inside the scene's pane of the workbench (workbench.ts places the panes), so
// that none covers another: the HUD in its top-left corner with viser's notices moved below it,
// viser's control panel at its top right (minimised to a strip when the pane is narrow), and the
// help overlay in the largest free area between them. It runs on resize, when the help opens or
// closes, and twice a second (notices and the panel come and go on their own).
import { scene } from "./scene";

/** Dispatch this on window to lay the overlays out again now (the help opened or closed). */
export const LAYOUT_EVENT = "teleop-layout";
const GAP = 8;
const MARGIN = 16;
const HUD_INSET = 10;  // the HUD's distance from its pane's top-left corner
const COLLAPSE_BELOW_PX = 1000;  // a window narrower than this: the panel starts as a strip
const PANEL_SCENE_MIN_PX = 700;  // and a scene pane narrower than this: no room for it beside the HUD
const HELP_WIDTH = 460;
const MIN_HELP_WIDTH = 280;
const STRIP_MAX_PX = 60;  // a minimised panel is about 41 px high
const CLICK_AGAIN_MS = 1500;  // a click toggles: never a second one before the first has shown

export const layout = {
  collapsedPanel: false,
  lastWidth: null as number | null,
  boxes: null as Record<string, DOMRect | null> | null,
  layout: (): void => layOut(),
};

const rect = (e: Element | null): DOMRect | null => (e ? e.getBoundingClientRect() : null);
// The 3D view's width: its pane's in the workbench.
const viewWidth = (): number => document.getElementById("root")?.clientWidth || window.innerWidth;
const sceneBox = (): DOMRect =>
  rect(document.getElementById("teleop-pane-scene")) ?? new DOMRect(0, 0, window.innerWidth, window.innerHeight);
const panelEl = (): Element | null => document.querySelector('[data-testid="floating-panel"]');

// Minimise the panel when the page opens narrow or is made narrow: a narrow window, the code view
// open (the scene's pane is then small, and kept uncovered), or a scene pane too narrow for the
// panel beside the HUD. When that ends, a panel minimised here opens again; what the student does
// with it meanwhile is theirs. viser resets the panel when it connects, so a wish stands until
// the panel is as wished.
let wantStrip = false, wantOpen = false, autoStrip = false, wasNarrow: boolean | null = null, clickedAt = -Infinity;
const codeOpen = (): boolean => document.getElementById("teleop-code")?.hidden === false;
const isNarrow = (): boolean =>
  window.innerWidth < COLLAPSE_BELOW_PX || codeOpen() || viewWidth() < PANEL_SCENE_MIN_PX;
const clickOnce = (button: HTMLElement | null): void => {
  if (button && performance.now() - clickedAt > CLICK_AGAIN_MS) { button.click(); clickedAt = performance.now(); }
};
const collapsePanelIfNarrow = (): void => {
  if (!panelEl() || !scene.ready) return;  // viser rebuilds its panel when it connects
  const narrow = isNarrow();
  if (narrow && wasNarrow !== true) { wantStrip = true; wantOpen = false; }
  if (!narrow && wasNarrow === true && autoStrip) { wantOpen = true; wantStrip = false; }
  wasNarrow = narrow;
  layout.lastWidth = viewWidth();
  const expand = document.querySelector<HTMLElement>('[aria-label="Expand panel"]');
  if (wantStrip) {
    if (expand) {
      wantStrip = false; autoStrip = true; layout.collapsedPanel = true;
      if (document.activeElement === expand) expand.blur();  // viser hands it focus; Space would reopen it
      return;
    }
    clickOnce(document.querySelector<HTMLElement>('[aria-label="Minimize panel"]'));
  } else if (wantOpen) {
    if (!expand) { wantOpen = false; autoStrip = false; layout.collapsedPanel = false; return; }
    clickOnce(expand);
  }
};

// The HUD grows when its telemetry arrives: lay out again at once, so viser's notices below it
// never sit under it until the next interval.
const resized = typeof ResizeObserver === "function" ? new ResizeObserver(() => layOut()) : null;
let observedHud: HTMLElement | null = null;

// The HUD's corner: viser's notices go below it. Returns the right edge of the column they make.
const placeColumn = (): number | null => {
  const hud = document.getElementById("teleop-hud");
  if (!hud) return null;
  if (resized && hud !== observedHud) {
    if (observedHud) resized.unobserve(observedHud);
    resized.observe(hud);
    observedHud = hud;
  }
  // The HUD in the pane's corner; below viser's panel when it is a strip that would reach it.
  const pane = sceneBox(), panel = rect(panelEl());
  const reaches = !!panel && panel.height > 0 && panel.height <= STRIP_MAX_PX
    && panel.left < pane.left + HUD_INSET + hud.offsetWidth + GAP;
  hud.style.top = `${reaches ? panel.bottom - pane.top + GAP : HUD_INSET}px`;
  const notices = document.querySelector<HTMLElement>(".mantine-Notifications-root");
  const below = rect(hud)!.bottom + GAP;
  if (notices?.offsetParent) {
    const origin = rect(notices.offsetParent)!.top;
    document.documentElement.style.setProperty("--teleop-notices-top", `${below - origin}px`);
  }
  const boxes = [hud, notices].map(rect).filter((r): r is DOMRect => !!r && r.width > 0);
  return Math.max(...boxes.map((r) => r.right));
};

interface Region { x0: number; x1: number; y0: number; y1: number }
interface Fit { r: Region; width: number; height: number }

// The help overlay in the scene pane's free area right of the column: beside the panel, or below
// it when the panel is a strip; whichever lets it be widest.
const placeHelp = (columnRight: number): void => {
  const help = document.getElementById("teleop-help");
  if (!help || help.hidden) return;
  const box = sceneBox();
  const W = box.right, H = box.bottom, top = box.top + MARGIN;
  const panel = rect(panelEl());
  const left = columnRight + MARGIN;
  const regions: Region[] = [{ x0: left, x1: W - MARGIN, y0: top, y1: H - MARGIN }];
  if (panel?.width) {
    regions[0]!.x1 = Math.min(regions[0]!.x1, panel.left - MARGIN);
    regions.push({ x0: left, x1: W - MARGIN, y0: panel.bottom + MARGIN, y1: H - MARGIN });
  }
  const fits: Fit[] = regions.map((r) => {
    const width = Math.max(0, Math.min(HELP_WIDTH, r.x1 - r.x0));
    help.style.width = `${width}px`;
    return { r, width, height: help.offsetHeight };
  });
  const fitting = fits.filter((f) => f.width >= MIN_HELP_WIDTH && f.height <= f.r.y1 - f.r.y0);
  if (!fitting.length && panel && panel.height > STRIP_MAX_PX) {
    wantStrip = true;  // no room beside the panel: the help asked for is worth more than the panel
    return;
  }
  const best = fitting.sort((a, b) => b.width - a.width)[0]
    ?? fits.sort((a, b) => b.width * (b.r.y1 - b.r.y0) - a.width * (a.r.y1 - a.r.y0))[0]!;
  help.style.width = `${best.width}px`;
  help.style.maxHeight = `${best.r.y1 - best.r.y0}px`;
  help.style.left = `${(best.r.x0 + best.r.x1 - best.width) / 2}px`;
  help.style.top = `${Math.max(best.r.y0, (best.r.y0 + best.r.y1 - Math.min(best.height, best.r.y1 - best.r.y0)) / 2)}px`;
};

function layOut(): void {
  collapsePanelIfNarrow();
  const columnRight = placeColumn();
  if (columnRight !== null) placeHelp(columnRight);
  const ids = ["teleop-toolbar", "teleop-nav-tools", "teleop-hud", "teleop-guide", "teleop-help"];
  layout.boxes = Object.fromEntries(ids.map((id) => [id, rect(document.getElementById(id))]));
}

/** Lay the overlays out on resize, on LAYOUT_EVENT and twice a second. */
export function startLayout(): void {
  addEventListener("resize", layOut);
  addEventListener(LAYOUT_EVENT, layOut);
  setInterval(layOut, 500);
}
