// One student's checkpoint as the instructor opens it from the class table: its state and time,
// the live progress line, and its evidence as the server recorded it (GET /api/checkpoints in
// that world: the instructor names the world with ?world=), with a link to the student's signed
// report. The evidence reads as the report does: the flight's picture first (the page's capture
// of its 3D view, else the drone's track drawn by the server: the report's JSON carries it),
// then its facts, then each timeline as a table in local time; the raw JSON is folded below,
// cut at MAX_CHARS so a long track cannot swamp the page.
import type { Checkpoint, Checkpoints, Report, TimelineEntry } from "../protocol.gen";
import { CHECKPOINTS_URL, errorOf, reportUrl } from "../guide/contract";

const MAX_CHARS = 6000;
const MAX_ROWS = 40;  // a timeline's last rows, as the report shows them

const node = <K extends keyof HTMLElementTagNameMap>(tag: K, text = "", cls = ""): HTMLElementTagNameMap[K] => {
  const e = document.createElement(tag);
  if (text) e.textContent = text;
  if (cls) e.className = cls;
  return e;
};
const cut = (text: string): string => (text.length > MAX_CHARS ? `${text.slice(0, MAX_CHARS)}\n… (${text.length - MAX_CHARS} more characters)` : text);
// The lab's clock reads as Unix time (node_runtime/bus/clock.py): shown in the instructor's own time zone.
const localTime = (t_s: number): string => new Date(t_s * 1000).toLocaleTimeString();
const isPicture = (v: unknown): v is string => typeof v === "string" && /^data:image\/(png|svg\+xml|jpeg);/.test(v);
const isTimeline = (v: unknown): v is TimelineEntry[] => Array.isArray(v) && v.length > 0 && v.every(
  (e) => typeof e === "object" && e !== null && typeof (e as TimelineEntry).t_s === "number" && "what" in e);
const isFact = (v: unknown): boolean => v === null || ["string", "number", "boolean"].includes(typeof v)
  || (Array.isArray(v) && v.length <= 4 && v.every((x) => typeof x === "number"));
const shown = (v: unknown): string => (typeof v === "string" ? v : JSON.stringify(v));

function picture(src: string, alt: string): HTMLElement {
  const img = node("img");
  img.src = src; img.alt = alt;
  return img;
}

function facts(evidence: Record<string, unknown>): HTMLElement | null {
  const rows = Object.entries(evidence).filter(([, v]) => isFact(v) && !isPicture(v));
  if (!rows.length) return null;
  const table = node("table", "", "facts");
  for (const [k, v] of rows) {
    const tr = node("tr");
    tr.append(node("th", k), node("td", cut(shown(v))));
    table.append(tr);
  }
  return table;
}

function timeline(name: string, entries: TimelineEntry[]): HTMLElement {
  const box = node("section", "", "timeline");
  const last = entries.slice(-MAX_ROWS);
  const more = entries.length > last.length ? ` (the last ${last.length} of ${entries.length})` : "";
  box.append(node("h4", `${name}${more}`));
  const table = node("table");
  const head = node("tr");
  for (const title of ["time", "what", "value", "by"]) head.append(node("th", title));
  table.append(head);
  for (const e of last) {
    const tr = node("tr");
    tr.append(node("td", localTime(e.t_s)), node("td", e.what), node("td", cut(shown(e.value))), node("td", e.by ?? ""));
    table.append(tr);
  }
  box.append(table);
  return box;
}

function raw(evidence: Record<string, unknown>): HTMLElement {
  const details = node("details");
  details.append(node("summary", "the evidence as recorded (JSON)"), node("pre", cut(JSON.stringify(evidence, null, 1))));
  return details;
}

function render(box: HTMLElement, student: string, world: string, c: Checkpoint, drawn: string | null): void {
  const head = node("h3", `${student}: ${c.title}`);
  const state = node("p", c.state === "done" && c.done_at ? `done at ${new Date(c.done_at).toLocaleString()}` : c.state.replace("_", " "));
  const progress = node("p", c.progress, "muted");
  const report = node("a", "this student's report (HTML)");
  report.href = `${reportUrl("html")}&world=${encodeURIComponent(world)}`;
  report.target = "_blank";
  const parts: HTMLElement[] = [head, state, progress];
  const evidence = c.evidence;
  if (!evidence) {
    parts.push(node("p", "no evidence yet: not done", "muted"));
  } else {
    if (drawn) parts.push(picture(drawn, `${c.title}: the flight`));
    for (const [k, v] of Object.entries(evidence)) if (isPicture(v)) parts.push(picture(v, k));
    const table = facts(evidence);
    if (table) parts.push(table);
    for (const [k, v] of Object.entries(evidence)) if (isTimeline(v)) parts.push(timeline(k, v));
    parts.push(raw(evidence));
  }
  parts.push(report);
  box.replaceChildren(...parts);
}

/** The checkpoint's picture as the student's report has it (null: none, or the report failed). */
async function drawnPicture(world: string, checkpoint: string): Promise<string | null> {
  const reply = await fetch(`${reportUrl("json")}&world=${encodeURIComponent(world)}`, { cache: "no-store" });
  if (!reply.ok) return null;
  const report = await reply.json() as Partial<Report>;
  return report.checkpoints?.find((x) => x.name === checkpoint)?.picture ?? null;
}

/** Show ``checkpoint`` of ``world`` in the dialog ``dialog`` (its body is ``box``). */
export async function openEvidence(dialog: HTMLDialogElement, box: HTMLElement, student: string, world: string,
  checkpoint: string): Promise<void> {
  box.replaceChildren(node("p", "loading…", "muted"));
  if (!dialog.open) dialog.showModal();
  const reply = await fetch(`${CHECKPOINTS_URL}?world=${encodeURIComponent(world)}`, { cache: "no-store" });
  if (!reply.ok) { box.replaceChildren(node("p", `could not load: ${await errorOf(reply)}`, "bad")); return; }
  const data = await reply.json() as Checkpoints;
  const c = data.checkpoints.find((x) => x.name === checkpoint);
  if (!c) { box.replaceChildren(node("p", `no checkpoint ${checkpoint} in ${world}`, "bad")); return; }
  const drawn = c.evidence ? await drawnPicture(world, checkpoint).catch(() => null) : null;
  render(box, student, world, c, drawn);
}
