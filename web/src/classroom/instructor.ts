// The instructor's page: every world once a second (GET /api/classroom/worlds) in a table, and
// the controls (reset one or all, remove a student, publish in all worlds, a student's code read-only:
// workspaces.ts). Every drone in 3D is
// the class view's own viser page, in a frame (/instructor/view). Below, the class's checkpoints
// (checkpoints.ts); beside the header, the server's load and the join queue (load.ts). The token is the page's
// HTTP-only cookie; these requests are same-origin.
import type { BroadcastRequest, ClassWorld, ClassWorlds, ErrorBody } from "../protocol.gen";
import { startCheckpoints } from "./checkpoints";
import { startLoad } from "./load";
import { openWorkspace } from "./workspaces";

const $ = <E extends HTMLElement = HTMLElement>(id: string): E => document.getElementById(id) as E;
const say = (text: string): void => { $("status").textContent = text; };
const messageOf = (err: unknown): string => (err instanceof Error ? err.message : String(err));

async function call<T>(method: string, url: string, body?: BroadcastRequest): Promise<T> {
  const reply = await fetch(url, {
    method,
    headers: body ? { "Content-Type": "application/json" } : {},
    body: body ? JSON.stringify(body) : null,
  });
  const data = await reply.json().catch(() => ({})) as T | Partial<ErrorBody>;
  if (!reply.ok) {
    const detail = (data as Partial<ErrorBody>).detail;
    throw new Error(typeof detail === "string" ? detail : `HTTP ${reply.status}`);
  }
  return data as T;
}

function button(td: HTMLTableCellElement, label: string, onClick: () => void): void {
  const b = document.createElement("button");
  b.type = "button";
  b.textContent = label;
  b.addEventListener("click", onClick);
  td.append(b, " ");
}

/** A new world's row: its cells, and its buttons, which stay while the row is redrawn. */
function newRow(body: HTMLTableSectionElement, w: ClassWorld): HTMLTableRowElement {
  const row = body.insertRow();
  row.dataset.world = w.world;
  for (let i = 0; i < 6; i++) row.insertCell();
  const actions = row.insertCell();
  const world = encodeURIComponent(w.world);
  button(actions, "Code", () => void openWorkspace(w.world, w.student));
  button(actions, "Reset", () => void act("POST", `/api/classroom/worlds/${world}/reset`, `reset ${w.world}`));
  button(actions, "Remove", () => {
    if (confirm(`Remove ${w.student}'s world? Their page stops working until they join again.`)) {
      void act("DELETE", `/api/classroom/worlds/${world}`, `removed ${w.world}`);
    }
  });
  return row;
}

function fill(row: HTMLTableRowElement, w: ClassWorld): void {
  const keys = w.keys_held ?? [];
  const crashed = w.crashed_nodes ?? [];
  const problem = w.lost ?? w.worker_error;
  const texts: [string, string][] = [
    [w.student, ""],
    [w.worker ? `${w.world} (on worker ${w.worker})` : w.world, ""],
    [keys.length ? keys.join(", ") : "–", "num"],
    [w.rocket ? `${w.rocket.phase} ${w.rocket.altitude_m} m` : "–", ""],
    [w.drone ? w.drone.map((v) => v.toFixed(2)).join(", ") : "–", "num"],
    problem ? [problem, "bad"] : [crashed.length ? crashed.join(", ") : "none", crashed.length ? "bad" : ""],
  ];
  texts.forEach(([text, cls], i) => {
    const td = row.cells[i];
    if (!td) return;
    if (td.textContent !== text) td.textContent = text;
    if (td.className !== cls) td.className = cls;
  });
}

// Rows are updated in place (a button under the pointer is never replaced mid-click), in the
// server's order; a world gone loses its row.
function draw(worlds: ClassWorld[]): void {
  const body = $<HTMLTableSectionElement>("worlds");
  const rows = new Map(Array.from(body.rows, (r) => [r.dataset.world ?? "", r]));
  worlds.forEach((w, i) => {
    let row = rows.get(w.world);
    rows.delete(w.world);
    if (row && row.cells[0]?.textContent !== w.student) {  // removed, and joined again by another
      row.remove();
      row = undefined;
    }
    row ??= newRow(body, w);
    fill(row, w);
    if (body.rows[i] !== row) body.insertBefore(row, body.rows[i] ?? null);
  });
  for (const gone of rows.values()) gone.remove();
}

async function act(method: string, url: string, done: string, body?: BroadcastRequest): Promise<void> {
  try {
    await call<unknown>(method, url, body);
    say(done);
    await refresh();
  } catch (err) {
    say(messageOf(err));
  }
}

async function refresh(): Promise<void> {
  try {
    const data = await call<ClassWorlds>("GET", "/api/classroom/worlds");
    $("code").textContent = data.class_code;
    $("count").textContent = `${data.worlds.length} / ${data.max_worlds} worlds`;
    draw(data.worlds);
  } catch (err) {
    say(messageOf(err));
  }
}

$("reset-all").addEventListener("click", () => void act("POST", "/api/classroom/reset", "every world reset"));
$("broadcast").addEventListener("click", () => {
  let msg: Record<string, unknown>;
  try {
    msg = JSON.parse($<HTMLInputElement>("b-msg").value) as Record<string, unknown>;
  } catch (err) {
    say(`the message is not JSON: ${messageOf(err)}`);
    return;
  }
  const type = $<HTMLInputElement>("b-type").value.trim() || null;
  const body: BroadcastRequest = { topic: $<HTMLInputElement>("b-topic").value.trim(), msg, type };
  void act("POST", "/api/classroom/broadcast", "published in every world", body);
});
void refresh();
setInterval(() => void refresh(), 1000);
startCheckpoints();
startLoad();
