// The instructor's load panel: the class server's load every few seconds (GET
// /api/classroom/load): the capacity verdict, each place's worlds, CPU, memory and its loop's
// scheduling class, each machine's world budget, the late worlds and the join queue, with a
// warning line when the class is near or at its capacity and a button that lets the oldest
// waiting join in.
import type { ClassLoadOut, ErrorBody, LetThrough, MachineOut, PlaceOut } from "../protocol.gen";

const REFRESH_MS = 3000;
const LOAD_URL = "/api/classroom/load";
const ADMIT_URL = "/api/classroom/queue/admit";

const $ = <E extends HTMLElement = HTMLElement>(id: string): E => document.getElementById(id) as E;

function place(p: PlaceOut): string {
  const where = p.place === "server" ? "this server" : `worker ${p.place}`;
  const cpu = p.cpu;
  const parts = [`${where}: ${p.worlds}/${p.max_worlds} worlds`];
  if (cpu) {
    parts.push(`CPU ${cpu.process_cores.toFixed(2)} core`);
    if (cpu.rss_mb !== null) parts.push(`${Math.round(cpu.rss_mb)} MiB`);
    if (cpu.host_busy !== null) parts.push(`machine ${Math.round(cpu.host_busy * 100)} % busy`);
    if (cpu.loop !== null) parts.push(cpu.loop === "realtime" ? "real-time loop" : "normal-priority loop");
    if (cpu.saturated) parts.push("saturated");
  }
  if (p.late) parts.push(`${p.late} late`);
  return parts.join(", ");
}

function machine(m: MachineOut, count: number): string {
  const which = count > 1 ? `machine ${m.machine.slice(0, 8)}` : "the machine";
  return `${which}: ${m.worlds} of its budget of ${m.budget} worlds (${m.cores} cores)`;
}

function line(text: string): HTMLLIElement {
  const li = document.createElement("li");
  li.textContent = text;
  return li;
}

function draw(load: ClassLoadOut): void {
  const verdict = $("load-verdict");
  verdict.textContent = load.capacity;
  verdict.className = `verdict ${load.capacity}`;
  $("load-summary").textContent =
    `${load.worlds} worlds, ${load.late} late, room for ${load.room} more`;
  const list = $("load-places");
  list.replaceChildren(
    ...load.places.map((p) => line(place(p))),
    ...load.machines.map((m) => line(machine(m, load.machines.length))),
  );
  const warning = $("load-warning");
  warning.hidden = load.capacity === "ok";
  warning.textContent = load.capacity === "full"
    ? `At capacity: new joins wait in the queue (${load.reasons.join("; ")}).`
    : `Near capacity: ${load.reasons.join("; ")}.`;
  const waiting = load.queue.waiting;
  $("load-queue").textContent = waiting.length
    ? `${waiting.length} waiting (of ${load.queue.size}): ${waiting.map((w) => `${w.student} ${Math.round(w.waited_s)} s`).join(", ")}`
    : "no join waits";
  $("load-admit").hidden = waiting.length === 0;
}

async function refresh(): Promise<void> {
  try {
    const reply = await fetch(LOAD_URL);
    const data = await reply.json() as ClassLoadOut | Partial<ErrorBody>;
    if (!reply.ok || !("capacity" in data)) {
      const detail = (data as Partial<ErrorBody>).detail;
      $("load-summary").textContent = typeof detail === "string" ? detail : `HTTP ${reply.status}`;
      return;
    }
    draw(data);
  } catch (err) {
    $("load-summary").textContent = `the class server did not answer: ${String(err)}`;
  }
}

async function admitOne(): Promise<void> {
  await fetch(ADMIT_URL, {
    method: "POST",
    headers: { "Content-Type": "application/json" },
    body: JSON.stringify({ count: 1 } satisfies LetThrough),
  });
  await refresh();
}

export function startLoad(): void {
  $("load-admit").addEventListener("click", () => void admitOne());
  void refresh();
  setInterval(() => void refresh(), REFRESH_MS);
}
