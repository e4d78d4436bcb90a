// The tools page, like rqt: the computation graph (rqt_graph), node and topic info, a topic's
// rate (ros2 topic hz) and a live echo (ros2 topic echo), plus topic and node lists.
// It polls /api/graph once a second and rebuilds the drawing only when the graph's version
// changes (and what is shown changed with it). Plain DOM and SVG; the layout is layout.ts.
import type {
  EchoFrame, GraphOut, NodeDetailOut, NodeSummaryOut, RateOut, TopicDetail, TopicSummary,
} from "../protocol.gen";
import { drawGraph, viewOf, type Kind, type Mode, type View, type ViewBox } from "./drawing";
import { assignLayers, backEdges, crossings, layout, type Point } from "./layout";

const POLL_MS = 1000;
const ECHO_RETRY_MS = 2000;
const MAX_FIT_SCALE = 1.5;  // a small graph is not blown up past this
const MIN_FIT_SCALE = 0.85;  // a big graph is not shrunk past this (its text stays readable): pan to see the rest
const MIN_PANEL_H = 180;  // px; the panel grows with the drawing's height up to the window's, less the toolbar
const PANEL_MARGIN_PX = 20;

interface Selected { kind: Kind; name: string }

const $ = <E extends Element = HTMLElement>(sel: string): E => document.querySelector<E>(sel)!;
const svg = $<SVGSVGElement>("#graph");
const state = {
  graph: null as GraphOut | null, key: null as string | null, signature: null as string | null, redraws: 0,
  mode: $<HTMLSelectElement>("#mode").value as Mode, hideDebug: $<HTMLInputElement>("#hide-debug").checked,
  selected: null as Selected | null, bounds: null as ViewBox | null, view: null as ViewBox | null, userView: false,
  echo: null as WebSocket | null, echoPaused: false, echoFrames: 0,
};

// -- small helpers -------------------------------------------------------------------------
type Attrs = Record<string, string | ((e: Event) => void)>;
function el(tag: string, attrs: Attrs = {}, ...children: Array<Node | string>): HTMLElement {
  const node = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) {
    if (typeof v === "function") node.addEventListener(k.slice(2), v);
    else if (k === "class") node.className = v;
    else node.setAttribute(k, v);
  }
  for (const c of children) node.append(c);
  return node;
}
const isHidden = (name: string): boolean => name.split("/").some((t) => t.startsWith("_"));
const path = (name: string): string => name.replace(/^\/+/, "").split("/").map(encodeURIComponent).join("/");
class HttpError extends Error {
  constructor(readonly status: number, url: string) { super(`${status} ${url}`); }
}
async function getJSON<T>(url: string): Promise<T> {
  const response = await fetch(url, { cache: "no-store" });
  if (!response.ok) throw new HttpError(response.status, url);
  return response.json() as Promise<T>;
}
const statusOf = (err: unknown): number | null => (err instanceof HttpError ? err.status : null);
const fmt = (x: number | null | undefined, digits = 3): string => (x === null || x === undefined ? "–" : Number(x).toFixed(digits));
const link = (kind: Kind, name: string): HTMLElement =>
  el("a", { class: "link", href: "#", onclick: (e) => { e.preventDefault(); select(kind, name); } }, name);

// -- drawing (drawing.ts) ---------------------------------------------------------------
function draw(view: View): void {
  state.bounds = drawGraph(svg, view);
  fitPanel();
  $("#graph-empty").hidden = view.vertices.length > 0;
  state.redraws++;
  svg.dataset.redraws = String(state.redraws);
  markSelection();
}

function render(): void {
  if (!state.graph) return;
  const view = viewOf(state.graph, state.mode);
  const signature = JSON.stringify([state.mode, view]);
  if (signature === state.signature) return;  // a new version that changed nothing shown here
  state.signature = signature;
  draw(view);
}

// -- pan and zoom --------------------------------------------------------------------------
function setViewBox(v: ViewBox): void {
  state.view = v;
  svg.setAttribute("viewBox", `${v.x} ${v.y} ${v.w} ${v.h}`);
}
// Size the panel to the drawing at the scale it will be drawn (a wide, short graph needs little
// height; a tall one takes up to the window), then show it all, or as much as is readable.
function fitPanel(): void {
  const panel = $("#graph-panel");
  const b = state.bounds;
  if (!b) return;
  const scale = Math.max(Math.min(panel.clientWidth / b.w, MAX_FIT_SCALE), MIN_FIT_SCALE);
  const want = b.h * scale + 2;
  const room = innerHeight - $("#toolbar").offsetHeight - PANEL_MARGIN_PX;
  panel.style.height = `${Math.round(Math.min(Math.max(want, MIN_PANEL_H), room))}px`;
  if (!state.userView) fit(b);
}
function fit(b: ViewBox): void {
  const cw = svg.clientWidth || 1;
  const ch = svg.clientHeight || 1;
  const scale = Math.max(Math.min(cw / b.w, ch / b.h, MAX_FIT_SCALE), MIN_FIT_SCALE);
  const w = cw / scale;
  const h = ch / scale;
  // Too big to show whole at a readable size: its left (where the graph starts) and middle.
  const x = w >= b.w ? b.x - (w - b.w) / 2 : b.x;
  const y = h >= b.h ? b.y - (h - b.h) / 2 : b.y;
  setViewBox({ x, y, w, h });
}
function toUser(clientX: number, clientY: number): Point {
  const m = svg.getScreenCTM();
  return m ? new DOMPoint(clientX, clientY).matrixTransform(m.inverse()) : { x: 0, y: 0 };
}
svg.addEventListener("wheel", (e) => {
  const v = state.view;
  if (!v) return;
  e.preventDefault();
  const p = toUser(e.clientX, e.clientY);
  const k = Math.min(4, Math.max(0.25, Math.exp(e.deltaY * 0.0015)));
  state.userView = true;
  setViewBox({ x: p.x - (p.x - v.x) * k, y: p.y - (p.y - v.y) * k, w: v.w * k, h: v.h * k });
}, { passive: false });
let drag: { x: number; y: number; view: ViewBox; moved: boolean; id: number } | null = null;
svg.addEventListener("pointerdown", (e) => {
  if (!state.view || e.button !== 0) return;
  drag = { x: e.clientX, y: e.clientY, view: state.view, moved: false, id: e.pointerId };
});
svg.addEventListener("pointermove", (e) => {
  if (!drag || e.pointerId !== drag.id) return;
  const dx = e.clientX - drag.x;
  const dy = e.clientY - drag.y;
  if (!drag.moved && Math.hypot(dx, dy) < 4) return;
  if (!drag.moved) { drag.moved = true; svg.setPointerCapture(e.pointerId); svg.classList.add("panning"); }
  const m = svg.getScreenCTM();
  const scale = m ? 1 / m.a : 1;
  state.userView = true;
  setViewBox({ ...drag.view, x: drag.view.x - dx * scale, y: drag.view.y - dy * scale });
});
const endDrag = (): void => { svg.classList.remove("panning"); setTimeout(() => { drag = null; }, 0); };
svg.addEventListener("pointerup", endDrag);
svg.addEventListener("pointercancel", endDrag);
$("#fit").addEventListener("click", () => { state.userView = false; fitPanel(); });
new ResizeObserver(() => { if (!state.userView && state.bounds) fit(state.bounds); }).observe(svg);
addEventListener("resize", fitPanel);

// -- selection -----------------------------------------------------------------------------
function itemAt(target: EventTarget | null): Selected | null {
  const g = target instanceof Element ? target.closest<SVGGElement>("g.graph-node, g.graph-topic") : null;
  return g ? { kind: g.classList.contains("graph-node") ? "node" : "topic", name: g.dataset.name ?? "" } : null;
}
svg.addEventListener("click", (e) => {
  if (drag?.moved) return;
  const item = itemAt(e.target);
  if (item) select(item.kind, item.name);
});
svg.addEventListener("keydown", (e) => {
  const item = itemAt(e.target);
  if (item && (e.key === "Enter" || e.key === " ")) { e.preventDefault(); select(item.kind, item.name); }
});

function markSelection(): void {
  const sel = state.selected;
  const is = (kind: Kind, name: string | undefined): boolean => !!sel && sel.kind === kind && sel.name === name;
  for (const g of svg.querySelectorAll<SVGGElement>("g.graph-node, g.graph-topic")) {
    g.classList.toggle("selected", is(g.classList.contains("graph-node") ? "node" : "topic", g.dataset.name));
  }
  for (const g of svg.querySelectorAll<SVGGElement>("g.graph-edge")) {
    g.classList.toggle("active", !!sel && (g.dataset.from === sel.name || g.dataset.to === sel.name));
  }
  for (const tr of document.querySelectorAll<HTMLElement>("#topics-table tbody tr")) tr.classList.toggle("selected", is("topic", tr.dataset.name));
  for (const li of document.querySelectorAll<HTMLElement>("#nodes-list li")) li.classList.toggle("selected", is("node", li.dataset.name));
}

function select(kind: Kind, name: string): void {
  const same = state.selected && state.selected.kind === kind && state.selected.name === name;
  if (!same) {
    closeEcho();
    state.selected = { kind, name };
    $("#details-hint").hidden = true;
    $("#node-info").hidden = kind !== "node";
    $("#topic-info").hidden = kind !== "topic";
    markSelection();
  }
  if (kind === "node") void refreshNode();
  else {
    void refreshTopic();
    void refreshHz();
    if (!state.echo) openEcho(name);
  }
}

// -- node info -----------------------------------------------------------------------------
interface Column { label: string; num?: boolean }
function fillTable(table: Element, headers: Column[], rows: Array<Array<Node | string>>, empty: string): void {
  const head = el("tr", {}, ...headers.map((h) => el("th", { class: h.num ? "num" : "" }, h.label)));
  const body = rows.length
    ? rows.map((cells) => el("tr", {}, ...cells.map((c, i) => el("td", { class: headers[i]?.num ? "num" : "" }, c))))
    : [el("tr", {}, el("td", { class: "empty", colspan: String(headers.length) }, empty))];
  table.replaceChildren(el("thead", {}, head), el("tbody", {}, ...body));
}

function showNode(info: NodeDetailOut): void {
  const box = $("#node-info");
  const part = (sel: string): HTMLElement => box.querySelector<HTMLElement>(sel)!;
  part(".title").textContent = info.name;
  const badge = part(".state");
  badge.textContent = info.state;
  badge.className = `badge state ${info.state}`;
  const reason = part(".crash-reason");
  reason.hidden = !info.crash_reason;
  reason.textContent = info.crash_reason ?? "";
  const origin = info.origin;
  const facts = [["namespace", info.namespace], ["package", origin.package], ["executable", origin.executable],
    ["launch file", origin.launch_file]].filter((f): f is [string, string] => !!f[1]);
  part(".facts").replaceChildren(...facts.flatMap(([k, v]) => [el("dt", {}, k), el("dd", {}, v)]));
  const endpoint = (ep: NodeDetailOut["publishers"][number]): Array<Node | string> => [link("topic", ep.topic), ep.type, String(ep.depth)];
  const cols = [{ label: "topic" }, { label: "type" }, { label: "depth", num: true }];
  fillTable(part(".publishers"), cols, info.publishers.map(endpoint), "none");
  fillTable(part(".subscribers"), cols, info.subscribers.map(endpoint), "none");
  fillTable(part(".timers"),
    [{ label: "period s", num: true }, { label: "calls", num: true }, { label: "late p50 ms", num: true }, { label: "p99 ms", num: true }],
    info.timers.map((t) => [fmt(t.period_s), String(t.calls), fmt(t.lateness_p50_ms, 2), fmt(t.lateness_p99_ms, 2)]), "none");
  fillTable(part(".parameters"), [{ label: "name" }, { label: "value" }],
    Object.entries(info.parameters).map(([k, v]) => [k, el("span", { class: "mono" }, JSON.stringify(v))]), "none");
}

async function refreshNode(): Promise<void> {
  const sel = state.selected;
  if (!sel) return;
  try {
    const info = await getJSON<NodeDetailOut>(`/api/nodes/${path(sel.name)}`);
    if (state.selected === sel) showNode(info);
  } catch (err) {
    if (state.selected !== sel || statusOf(err) !== 404) return;
    $("#node-info .state").textContent = "gone";
    $("#node-info .state").className = "badge state";
  }
}

// -- topic info, rate and echo ---------------------------------------------------------------
async function refreshTopic(): Promise<void> {
  const sel = state.selected;
  if (!sel) return;
  const box = $("#topic-info");
  const part = (s: string): HTMLElement => box.querySelector<HTMLElement>(s)!;
  part(".title").textContent = sel.name;
  let info: TopicDetail;
  try {
    info = await getJSON<TopicDetail>(`/api/topics/${path(sel.name)}`);
  } catch (err) {
    if (state.selected === sel && statusOf(err) === 404) part(".facts").replaceChildren(el("dt", {}, "gone"), el("dd", {}, "no node uses this topic any more"));
    return;
  }
  if (state.selected !== sel) return;
  const shown = (list: string[]): string[] => (state.hideDebug ? list.filter((n) => !isHidden(n)) : list);
  const names = (list: string[], kind: Kind): Array<Node | string> =>
    (list.length ? list.flatMap((n, i) => (i ? [", ", link(kind, n)] : [link(kind, n)])) : ["none"]);
  part(".facts").replaceChildren(
    el("dt", {}, "type"), el("dd", { class: "mono" }, info.type),
    el("dt", {}, "publishers"), el("dd", {}, ...names(shown(info.publishers), "node")),
    el("dt", {}, "subscribers"), el("dd", {}, ...names(shown(info.subscribers), "node")),
    el("dt", {}, "messages"), el("dd", { id: "topic-count" }, String(info.publish_count)),
  );
  if (!state.echoFrames && info.latest) {
    $("#echo").textContent = JSON.stringify(info.latest, null, 2);
    $("#echo-meta").textContent = "last message published before this echo began";
  }
}

async function refreshHz(): Promise<void> {
  const sel = state.selected;
  if (!sel) return;
  try {
    const hz = await getJSON<RateOut>(`/api/hz/${path(sel.name)}`);
    if (state.selected !== sel) return;
    const count = document.getElementById("topic-count");
    if (count) count.textContent = String(hz.count);
    $("#topic-hz").textContent = hz.rate_hz === null
      ? `no rate yet (${hz.count} message${hz.count === 1 ? "" : "s"})`
      : `average rate: ${fmt(hz.rate_hz)} Hz\nmin ${fmt(hz.min_s)} s  max ${fmt(hz.max_s)} s  std dev ${fmt(hz.std_dev_s, 5)} s  window ${hz.window}`;
  } catch (err) {
    if (state.selected === sel) $("#topic-hz").textContent = statusOf(err) === 404 ? "topic gone" : "rate unavailable";
  }
}

function openEcho(topic: string): void {
  const scheme = location.protocol === "https:" ? "wss" : "ws";
  // queue_length=1: with a throttle slower than the topic, show the newest message, not a backlog.
  const ws = new WebSocket(`${scheme}://${location.host}/ws/topics/${path(topic)}?throttle_rate=200&queue_length=1`);
  state.echo = ws;
  state.echoFrames = 0;
  const pre = $("#echo");
  pre.textContent = "";
  pre.dataset.frames = "0";
  $("#echo-meta").textContent = "waiting for a message…";
  ws.onmessage = (ev: MessageEvent<string>) => {
    if (state.echo !== ws) return;
    const frame = JSON.parse(ev.data) as EchoFrame;
    state.echoFrames++;
    if (state.echoPaused) return;
    pre.textContent = JSON.stringify(frame.msg, null, 2);
    pre.dataset.frames = String(state.echoFrames);
    const at = new Date(frame.received * 1000).toLocaleTimeString([], { hour12: false });
    $("#echo-meta").textContent = `${frame.type} · ${state.echoFrames} received · last at ${at}` +
      (frame.dropped ? ` · ${frame.dropped} dropped` : "");
  };
  ws.onclose = (ev) => {
    if (state.echo !== ws) return;
    state.echo = null;
    $("#echo-meta").textContent = `echo closed${ev.reason ? `: ${ev.reason}` : ""}; retrying…`;
    setTimeout(() => {
      const sel = state.selected;
      if (!state.echo && sel && sel.kind === "topic" && sel.name === topic) openEcho(topic);
    }, ECHO_RETRY_MS);
  };
}

function closeEcho(): void {
  const ws = state.echo;
  state.echo = null;
  state.echoFrames = 0;
  if (ws) ws.close(1000);
}

$("#echo-pause").addEventListener("click", () => {
  state.echoPaused = !state.echoPaused;
  $("#echo-pause").textContent = state.echoPaused ? "Resume" : "Pause";
});

// -- lists ---------------------------------------------------------------------------------
async function refreshLists(hidden: boolean): Promise<void> {
  const count = (names: string[]): number => (hidden ? names : names.filter((n) => !isHidden(n))).length;
  const [topics, nodes] = await Promise.all([
    getJSON<TopicSummary[]>(`/api/topics?hidden=${hidden}`), getJSON<NodeSummaryOut[]>(`/api/nodes?hidden=${hidden}`),
  ]);
  $("#topics-table tbody").replaceChildren(...topics.map((t) => el("tr", { "data-name": t.name, onclick: () => select("topic", t.name) },
    el("td", { class: "mono" }, t.name), el("td", { class: "mono" }, t.type),
    el("td", { class: "num" }, String(count(t.publishers))), el("td", { class: "num" }, String(count(t.subscribers))))));
  $("#nodes-list").replaceChildren(...nodes.map((n) => el("li", { "data-name": n.name, onclick: () => select("node", n.name) },
    el("span", { class: "mono" }, n.name), el("span", { class: `badge ${n.state}` }, n.state))));
  markSelection();
}

// -- polling -------------------------------------------------------------------------------
function setStatus(live: boolean, text: string): void {
  const status = $("#status");
  status.textContent = text;
  status.className = `status ${live ? "live" : "offline"}`;
}

let timer: ReturnType<typeof setTimeout> | undefined;
let polling = false;
async function poll(): Promise<void> {
  clearTimeout(timer);
  if (polling) return;
  polling = true;
  try {
    if (!document.hidden) {
      const hidden = !state.hideDebug;
      const graph = await getJSON<GraphOut>(`/api/graph?hidden=${hidden}`);
      setStatus(true, `live · graph v${graph.version}`);
      const key = `${graph.version}:${hidden}`;
      if (key !== state.key) {
        state.key = key;
        state.graph = graph;
        svg.dataset.version = String(graph.version);
        render();
        await refreshLists(hidden);
        if (state.selected?.kind === "topic") void refreshTopic();
      }
      if (state.selected?.kind === "node") void refreshNode();
      if (state.selected?.kind === "topic") void refreshHz();
    }
  } catch {
    setStatus(false, "server unreachable — retrying");
  } finally {
    polling = false;
    timer = setTimeout(() => void poll(), POLL_MS);
  }
}

$<HTMLSelectElement>("#mode").addEventListener("change", (e) => {
  state.mode = (e.target as HTMLSelectElement).value as Mode; state.userView = false; render();
});
$<HTMLInputElement>("#hide-debug").addEventListener("change", (e) => {
  state.hideDebug = (e.target as HTMLInputElement).checked; state.userView = false; void poll();
});
document.addEventListener("visibilitychange", () => { if (!document.hidden) void poll(); });

// For the browser tests and the curious: the page's state, and the layout on its own.
declare global {
  interface Window { __tools?: { state: typeof state; layout: { layout: typeof layout; backEdges: typeof backEdges; assignLayers: typeof assignLayers; crossings: typeof crossings } } }
}
window.__tools = { state, layout: { layout, backEdges, assignLayers, crossings } };
void poll();
