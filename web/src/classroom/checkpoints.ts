// The instructor's view of the class's checkpoints: a table of student × checkpoint with the
// time each was done (GET /api/classroom/checkpoints, every two seconds), each cell opening that
// student's evidence (evidence.ts); the class's answers to one chosen question side by side; and
// the links to the CSV export and to every student's report in one zip; and a report file
// checked against this server's signature (verify.ts).
import type { Checkpoint, Checkpoints, ClassCheckpoints, ClassStudent } from "../protocol.gen";
import { CHECKPOINTS_URL, errorOf } from "../guide/contract";
import { openEvidence } from "./evidence";
import { startVerify } from "./verify";

const REFRESH_MS = 2000;
const TABLE_URL = "/api/classroom/checkpoints";
const MARK: Record<Checkpoint["state"], string> = { done: "\u2713", in_progress: "\u2026", not_started: "\u2013" };

const $ = <E extends HTMLElement = HTMLElement>(id: string): E => document.getElementById(id) as E;
const state = { table: null as ClassCheckpoints | null, questions: new Map<string, string>(), chosen: "" };

const time = (iso: string): string => new Date(iso).toLocaleTimeString([], { hour12: false });

function cell(row: HTMLTableRowElement, s: ClassStudent, name: string): void {
  const td = row.insertCell();
  const c = s.cells[name];
  if (!c) { td.textContent = "–"; return; }
  if (c.state === "unreachable") {
    td.className = "cell unreachable";
    td.textContent = "? unreachable";
    td.title = `${s.name}: ${s.unreachable ?? "its world worker did not answer"}`;
    return;
  }
  const text = c.state === "done" && c.done_at ? `${MARK.done} ${time(c.done_at)}` : `${MARK[c.state]} ${c.state.replace("_", " ")}`;
  if (s.joined === false) {  // no world to open the evidence of until they join again
    td.className = `cell ${c.state} not-joined`;
    td.textContent = text;
    td.title = `${s.name}: ${name}, as saved (not joined since the class server started)`;
    return;
  }
  const b = document.createElement("button");
  b.type = "button";
  b.className = `cell ${c.state}`;
  b.dataset.checkpoint = name;
  b.textContent = text;
  b.title = `${s.name}: ${name} (open its evidence)`;
  td.append(b);
}

// Drawn again only when something in it changed, so that a click never meets a button being replaced.
let drawn = "";
function drawTable(t: ClassCheckpoints): void {
  const key = JSON.stringify([t.checkpoints, t.students.map((s) => [s.name, s.world, s.cells, s.joined])]);
  if (key === drawn) return;
  drawn = key;
  const head = $<HTMLTableRowElement>("checkpoints-head");
  head.replaceChildren(...["Student", ...t.checkpoints].map((n) => Object.assign(document.createElement("th"), { textContent: n })));
  const body = $<HTMLTableSectionElement>("checkpoints-rows");
  body.replaceChildren();
  for (const s of t.students) {
    const row = body.insertRow();
    row.dataset.student = s.name;
    row.dataset.world = s.world ?? s.name;
    row.insertCell().textContent = s.joined === false ? `${s.name} (not joined)` : s.name;
    for (const name of t.checkpoints) cell(row, s, name);
  }
}

function drawAnswers(t: ClassCheckpoints): void {
  const select = $<HTMLSelectElement>("question");
  const ids = [...new Set([...state.questions.keys(), ...t.students.flatMap((s) => Object.keys(s.answers))])];
  const labels = ids.map((id) => (state.questions.get(id) ? `${id}: ${state.questions.get(id)}` : id));
  if ([...select.options].map((o) => o.text).join("\n") !== labels.join("\n")) {
    select.replaceChildren(...ids.map((id, i) => new Option(labels[i], id)));
    if (ids.includes(state.chosen)) select.value = state.chosen;
  }
  state.chosen = select.value;
  $("answers").replaceChildren(...t.students.map((s) => {
    const card = document.createElement("article");
    card.dataset.student = s.name;
    const text = s.answers[state.chosen] ?? "";
    card.append(Object.assign(document.createElement("h4"), { textContent: s.name }),
      Object.assign(document.createElement("p"), { textContent: text || "(no answer)", className: text ? "" : "muted" }));
    return card;
  }));
}

// The questions' texts: the same in every world, so the first joined student's world says them.
async function learnQuestions(t: ClassCheckpoints): Promise<void> {
  const first = t.students.find((s) => s.joined !== false);
  if (state.questions.size || !first) return;
  const reply = await fetch(`${CHECKPOINTS_URL}?world=${encodeURIComponent(first.world ?? first.name)}`, { cache: "no-store" });
  if (!reply.ok) return;
  const data = await reply.json() as Checkpoints;
  for (const q of data.questions) state.questions.set(q.id, q.text);
}

let asking = false;
async function refresh(): Promise<void> {
  if (asking) return;  // a slow server: one request at a time
  asking = true;
  try {
    const reply = await fetch(TABLE_URL, { cache: "no-store" });
    if (!reply.ok) throw new Error(await errorOf(reply));
    const t = await reply.json() as ClassCheckpoints;
    state.table = t;
    drawTable(t);
    drawAnswers(t);
    $("checkpoints-status").textContent = `${t.students.length} student${t.students.length === 1 ? "" : "s"}`;
    if (!state.questions.size) await learnQuestions(t).then(() => drawAnswers(t)).catch(() => undefined);
  } catch (err) {
    $("checkpoints-status").textContent = `checkpoints unavailable: ${err instanceof Error ? err.message : String(err)}`;
  } finally {
    asking = false;
  }
}

/** Keep the class's checkpoint table and answers current. */
export function startCheckpoints(): void {
  $<HTMLSelectElement>("question").addEventListener("change", () => { if (state.table) drawAnswers(state.table); });
  $("evidence-close").addEventListener("click", () => $<HTMLDialogElement>("evidence").close());
  $("checkpoints-rows").addEventListener("click", (e) => {
    const b = e.target instanceof Element ? e.target.closest<HTMLElement>("button.cell") : null;
    const row = b?.closest<HTMLElement>("tr");
    if (!b || !row) return;
    void openEvidence($<HTMLDialogElement>("evidence"), $("evidence-body"), row.dataset.student ?? "",
      row.dataset.world ?? "", b.dataset.checkpoint ?? "");
  });
  startVerify($<HTMLInputElement>("verify-file"), $("verify-result"));
  void refresh();
  setInterval(() => void refresh(), REFRESH_MS);
}
