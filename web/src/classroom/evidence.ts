// One student's checkpoint as the instructor opens it from the class table: its state and time,
// the live progress line, and its evidence as the server recorded it (GET /api/checkpoints in
// that world: the instructor names the world with ?world=), with a link to the student's signed
// report. Evidence is shown as it comes: pictures (data URLs) as images, text as text, anything
// else as indented JSON, cut at MAX_CHARS so a long timeline cannot swamp the page.
import type { Checkpoint, Checkpoints } from "../guide/contract";
import { CHECKPOINTS_URL, errorOf, reportUrl } from "../guide/contract";

const MAX_CHARS = 6000;

const node = <K extends keyof HTMLElementTagNameMap>(tag: K, text = "", cls = ""): HTMLElementTagNameMap[K] => {
  const e = document.createElement(tag);
  if (text) e.textContent = text;
  if (cls) e.className = cls;
  return e;
};
const cut = (text: string): string => (text.length > MAX_CHARS ? `${text.slice(0, MAX_CHARS)}\n… (${text.length - MAX_CHARS} more characters)` : text);

function value(v: unknown): HTMLElement {
  if (typeof v === "string" && /^data:image\/(png|svg\+xml|jpeg);/.test(v)) {
    const img = node("img");
    img.src = v; img.alt = "picture";
    return img;
  }
  if (typeof v === "string") return node(v.includes("\n") ? "pre" : "span", cut(v));
  if (typeof v === "number" || typeof v === "boolean" || v === null) return node("span", String(v));
  return node("pre", cut(JSON.stringify(v, null, 1)));
}

const wrap = (v: unknown): HTMLElement => { const dd = node("dd"); dd.append(value(v)); return dd; };

function render(box: HTMLElement, student: string, world: string, c: Checkpoint): void {
  const head = node("h3", `${student}: ${c.title}`);
  const state = node("p", c.state === "done" && c.done_at ? `done at ${new Date(c.done_at).toLocaleString()}` : c.state.replace("_", " "));
  const progress = node("p", c.progress, "muted");
  const report = node("a", "this student's report (HTML)");
  report.href = `${reportUrl("html")}&world=${encodeURIComponent(world)}`;
  report.target = "_blank";
  const list = node("dl");
  for (const [k, v] of Object.entries(c.evidence ?? {})) list.append(node("dt", k), wrap(v));
  box.replaceChildren(head, state, progress, c.evidence ? list : node("p", "no evidence yet: not done", "muted"), report);
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
  render(box, student, world, c);
}
