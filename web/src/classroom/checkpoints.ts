// The instructor's view of the class's checkpoints: a table of student × checkpoint with the
// time each was done (GET /api/classroom/checkpoints, every two seconds), each cell opening that
// student's evidence (evidence.ts); the class's answers to one chosen question side by side; and
// the links to the CSV export and to every student's report in one zip; and a report file
// checked against this server's signature (verify.ts).
import type { CheckState, ClassCheckpoints, ClassStudent, Checkpoints } from "../guide/contract";
import { CHECKPOINTS_URL, errorOf } from "../guide/contract";
import { openEvidence } from "./evidence";
import { startVerify } from "./verify";

const REFRESH_MS = 2000;
const TABLE_URL = "/api/classroom/checkpoints";
const MARK: Record<CheckState, string> = { done: "\u2713", in_progress: "\u2026", not_started: "\u2013" };

const $ = <E extends HTMLElement = HTMLElement>(id: string): E => document.getElementById(id) as E;
const state = { table: null as ClassCheckpoints | null, questions: new Map<string, string>(), chosen: "" };

const time = (iso: string): string => new Date(iso).toLocaleTimeString([], { hour12: false });

function cell(row: HTMLTableRowElement, s: ClassStudent, name: string): void {
  const td = row.insertCell();
  const c = s.cells[name];
  if (!c) { td.textContent = "–"; return; }
  const b = document.createElement("button");
  b.type = "button";
  b.className = `cell ${c.state}`;
  b.dataset.checkpoint = name;
  b.textContent = c.state === "done" && c.done_at ? `${MARK.done} ${time(c.done_at)}` : `${MARK[c.state]} ${c.state.replace("_", " ")}`;
  b.title = `${s.name}: ${name} (open its evidence)`;
  b.addEventListener("click", () => void openEvidence($<HTMLDialogElement>("evidence"), $("evidence-body"), s.name,
    s.world ?? s.name, name));
  td.append(b);
}

function drawTable(t: ClassCheckpoints): void {
  const head = $<HTMLTableRowElement>("checkpoints-head");
  head.replaceChildren(...["Student", ...t.checkpoints].map((n) => Object.assign(document.createElement("th"), { textContent: n })));
  const body = $<HTMLTableSectionElement>("checkpoints-rows");
  body.replaceChildren();
  for (const s of t.students) {
    const row = body.insertRow();
    row.dataset.student = s.name;
    row.insertCell().textContent = s.name;
    for (const name of t.checkpoints) cell(row, s, name);
  }
}

function drawAnswers(t: ClassCheckpoints): void {
  const select = $<HTMLSelectElement>("question");
  const ids = [...new Set([...state.questions.keys(), ...t.students.flatMap((s) => Object.keys(s.answers))])];
  if (select.options.length !== ids.length) {
    select.replaceChildren(...ids.map((id) => new Option(state.questions.get(id) ? `${id}: ${state.questions.get(id)}` : id, id)));
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

// The questions' texts: the same in every world, so the first student's world says them.
async function learnQuestions(t: ClassCheckpoints): Promise<void> {
  const first = t.students[0];
  if (state.questions.size || !first) return;
  const reply = await fetch(`${CHECKPOINTS_URL}?world=${encodeURIComponent(first.world ?? first.name)}`, { cache: "no-store" });
  if (!reply.ok) return;
  const data = await reply.json() as Checkpoints;
  for (const q of data.questions) state.questions.set(q.id, q.text);
}

async function refresh(): Promise<void> {
  try {
    const reply = await fetch(TABLE_URL, { cache: "no-store" });
    if (!reply.ok) throw new Error(await errorOf(reply));
    const t = await reply.json() as ClassCheckpoints;
    state.table = t;
    await learnQuestions(t).catch(() => undefined);
    drawTable(t);
    drawAnswers(t);
    $("checkpoints-status").textContent = `${t.students.length} student${t.students.length === 1 ? "" : "s"}`;
  } catch (err) {
    $("checkpoints-status").textContent = `checkpoints unavailable: ${err instanceof Error ? err.message : String(err)}`;
  }
}

/** Keep the class's checkpoint table and answers current. */
export function startCheckpoints(): void {
  $<HTMLSelectElement>("question").addEventListener("change", () => { if (state.table) drawAnswers(state.table); });
  $("evidence-close").addEventListener("click", () => $<HTMLDialogElement>("evidence").close());
  startVerify($<HTMLInputElement>("verify-file"), $("verify-result"));
  void refresh();
  setInterval(() => void refresh(), REFRESH_MS);
}
