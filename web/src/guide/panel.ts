// The guide panel: the lab's checkpoints in order (from GET /api/checkpoints, in the server's
// words), each with its state (not started, in progress, done at a time), its live progress
// line, its steps (the page's way first, the terminal's as the alternative, or what runs already)
// and its questions as answer boxes; then the questions of no checkpoint, and the report to
// download. It folds to its header bar (remembered in the browser) and layout.ts keeps it clear
// of the HUD, viser's notices and its panel. Buttons never take the keyboard from the 3D view;
// keys typed in an answer box stop at the panel, so neither the keyboard node nor viser's camera
// sees them.
import { LAYOUT_EVENT } from "../lab/layout";
import { answerBox, type AnswerBox } from "./answers";
import type { Checkpoint, Checkpoints, Question, Step } from "../protocol.gen";
import { reportUrl } from "./contract";
import { graphFigure, type GraphFigure } from "./graph";
import { progress } from "./progress";
import { GUIDE_CSS } from "./style";

const STORE_FOLDED = "teleop.guide";
const OPEN_FROM_PX = 1000;  // narrower than this, a first visit starts folded (as viser's panel does)
const STATE_LABEL = { not_started: "not started", in_progress: "in progress", done: "done" } as const;

export const guide = {
  folded: false,
  answers: new Map<string, AnswerBox>(),
  graph: null as GraphFigure | null,
  fold: (folded: boolean): void => fold(folded, true),
};

const el = document.createElement("section");
el.id = "teleop-guide";
el.setAttribute("aria-label", "Lab guide");
const header = document.createElement("header");
const foldButton = document.createElement("button");
const summary = document.createElement("span");
const body = document.createElement("div");
const list = document.createElement("ol");
const others = document.createElement("div");
const report = document.createElement("div");
const error = document.createElement("p");
let structure = "";

const keepKeyboard = (b: HTMLElement): void => {
  b.tabIndex = -1;
  b.addEventListener("mousedown", (e) => e.preventDefault());
};

function fold(folded: boolean, remember: boolean): void {
  guide.folded = folded;
  el.classList.toggle("folded", folded);
  foldButton.textContent = folded ? "Guide \u25B8" : "Guide \u25BE";
  foldButton.setAttribute("aria-expanded", String(!folded));
  if (remember) localStorage.setItem(STORE_FOLDED, folded ? "folded" : "open");
  window.dispatchEvent(new Event(LAYOUT_EVENT));
  if (!folded) void guide.graph?.refresh();
}

const time = (iso: string): string => {
  const d = new Date(iso);
  const today = d.toDateString() === new Date().toDateString();
  return today ? d.toLocaleTimeString([], { hour12: false }) : d.toLocaleString([], { hour12: false });
};

// A step: what to do, then how in the page, then the terminal's way as the alternative; or,
// when its nodes run already, only that (nothing to ask).
function stepItem(step: Step): HTMLLIElement {
  const li = document.createElement("li");
  if (step.already) {
    li.className = "already";
    li.textContent = `\u2713 ${step.already}`;
    return li;
  }
  li.append(step.text);
  if (step.page) {
    const page = document.createElement("div");
    page.className = "page";
    page.textContent = step.page;
    li.append(page);
  }
  if (step.commands.length) {
    const terminal = document.createElement("div");
    terminal.className = "terminal";
    terminal.append(step.page ? "Or in a terminal:" : "In a terminal:");
    for (const command of step.commands) {
      const code = document.createElement("code");
      code.textContent = command;
      terminal.append(" ", code);
    }
    li.append(terminal);
  }
  return li;
}

function stepList(c: Checkpoint): HTMLOListElement {
  const ol = document.createElement("ol");
  ol.className = "steps";
  ol.append(...c.steps.map(stepItem));
  return ol;
}

function questionEl(q: Question): HTMLElement {
  const box = answerBox(q, () => void progress.refresh());
  guide.answers.set(q.id, box);
  if (q.shows_graph) {
    guide.graph ??= graphFigure();
    box.el.insertBefore(guide.graph.el, box.el.querySelector("textarea"));
  }
  return box.el;
}

// The checkpoints' and questions' names decide the panel's structure: built again only when
// they change (answer boxes keep their text and focus otherwise).
function build(data: Checkpoints): void {
  guide.answers.clear();
  const names = new Set(data.checkpoints.map((c) => c.name));
  list.replaceChildren(...data.checkpoints.map((c) => {
    const li = document.createElement("li");
    li.className = "checkpoint";
    li.dataset.name = c.name;
    li.innerHTML = `<div class="head"><b></b><span class="badge"></span></div><div class="progress"></div>`;
    li.append(stepList(c), ...data.questions.filter((q) => q.checkpoint === c.name).map(questionEl));
    return li;
  }));
  const rest = data.questions.filter((q) => !names.has(q.checkpoint));
  others.replaceChildren(...(rest.length ? [Object.assign(document.createElement("h4"), { textContent: "Questions" })] : []),
    ...rest.map(questionEl));
}

function update(data: Checkpoints): void {
  const key = JSON.stringify([data.checkpoints.map((c) => [c.name, c.steps]), data.questions.map((q) => [q.id, q.text])]);
  if (key !== structure) { build(data); structure = key; }
  for (const c of data.checkpoints) {
    const li = list.querySelector<HTMLElement>(`li.checkpoint[data-name="${CSS.escape(c.name)}"]`)!;
    li.dataset.state = c.state;
    li.querySelector("b")!.textContent = c.title;
    li.querySelector(".badge")!.textContent = c.state === "done" && c.done_at
      ? `done ${time(c.done_at)}` : STATE_LABEL[c.state];
    li.querySelector(".progress")!.textContent = c.progress;
  }
  for (const q of data.questions) guide.answers.get(q.id)?.update(q);
  const done = data.checkpoints.filter((c) => c.state === "done").length;
  summary.textContent = `${done} of ${data.checkpoints.length} checkpoints done`;
  window.dispatchEvent(new Event(LAYOUT_EVENT));
}

function mount(): void {
  const style = document.createElement("style");
  style.textContent = GUIDE_CSS;
  foldButton.type = "button";
  foldButton.className = "fold";
  keepKeyboard(foldButton);
  foldButton.addEventListener("click", () => { fold(!guide.folded, true); foldButton.blur(); });
  summary.className = "summary";
  summary.textContent = "loading the checkpoints…";
  header.append(foldButton, summary);
  body.className = "body";
  list.className = "checkpoints";
  report.className = "report";
  report.innerHTML = `<span>Your report:</span>`;
  for (const format of ["html", "json"] as const) {
    const a = document.createElement("a");
    a.href = reportUrl(format); a.download = ""; a.className = `download-${format}`;
    a.textContent = `Download report (${format.toUpperCase()})`;
    keepKeyboard(a);
    report.append(a);
  }
  error.className = "error";
  error.setAttribute("role", "status");
  body.append(list, others, report, error);
  el.append(header, body);
  for (const type of ["keydown", "keyup", "keypress"]) {
    el.addEventListener(type, (e) => { if (e.target !== el && e.target instanceof HTMLTextAreaElement) e.stopPropagation(); });
  }
  document.head.append(style);
  document.body.append(el);
  const stored = localStorage.getItem(STORE_FOLDED);
  fold(stored ? stored === "folded" : window.innerWidth < OPEN_FROM_PX, false);
}

/** Show the guide, and keep it current with the world's checkpoints. */
export function startGuide(): void {
  progress.listeners.push((data) => update(data));
  setInterval(() => { error.textContent = progress.error ? `checkpoints unavailable: ${progress.error}` : ""; }, 1000);
  if (document.body) mount(); else addEventListener("DOMContentLoaded", mount);
}
