// The computation graph in SVG, as the tools page draws it (and the lab page's guide beside its
// graph question): what a mode shows of GET /api/graph, then ellipses for nodes, boxes for
// topics and curved arrows between them, placed by layout.ts. Classes (graph-node, graph-topic,
// graph-edge, crashed, debug) are for the page's style sheet.
import type { GraphEdgeOut, GraphOut } from "../protocol.gen";
import { layout, type Box, type Point, type Route } from "./layout";

const FONT = "12px system-ui, -apple-system, 'Segoe UI', sans-serif";
const NODE_H = 30;  // px, ellipse height
const TOPIC_H = 26;  // px, box height
const PAD = 24;  // px around the drawing
const LOOP_ROOM = 44;  // px above the drawing for a self-loop's arc and label
const SVG_NS = "http://www.w3.org/2000/svg";

export type Kind = "node" | "topic";
export type Mode = "nodes" | "all";
export interface Vertex { id: string; kind: Kind; state?: string; type?: string; hidden: boolean }
export interface Edge { from: string; to: string; kind: GraphEdgeOut["kind"] | "flow"; label?: string }
export interface View { vertices: Vertex[]; edges: Edge[] }
export interface ViewBox { x: number; y: number; w: number; h: number }

export function sv<K extends keyof SVGElementTagNameMap>(tag: K, attrs: Record<string, string | number> = {}): SVGElementTagNameMap[K] {
  const node = document.createElementNS(SVG_NS, tag);
  for (const [k, v] of Object.entries(attrs)) node.setAttribute(k, String(v));
  return node;
}
let measure: CanvasRenderingContext2D | null = null;
function textWidth(text: string): number {
  measure ??= document.createElement("canvas").getContext("2d")!;
  measure.font = FONT;
  return measure.measureText(text).width;
}

/** What a graph shows in a mode: nodes and topics, or nodes only with an arrow per publisher → subscriber pair. */
export function viewOf(graph: GraphOut, mode: Mode): View {
  const nodes: Vertex[] = graph.nodes.map((n) => ({ id: n.name, kind: "node", state: n.state, hidden: n.hidden }));
  if (mode === "all") {
    const topics: Vertex[] = graph.topics.map((t) => ({ id: t.name, kind: "topic", type: t.type, hidden: t.hidden }));
    return { vertices: [...nodes, ...topics], edges: graph.edges.map((e) => ({ from: e.from, to: e.to, kind: e.kind })) };
  }
  // Nodes only: publisher → subscriber, one arrow per pair, labelled with the topics it carries.
  const subs = new Map<string, string[]>();
  for (const e of graph.edges) if (e.kind === "subscribe") subs.set(e.from, [...(subs.get(e.from) ?? []), e.to]);
  const pairs = new Map<string, { from: string; to: string; kind: "flow"; topics: string[] }>();
  for (const e of graph.edges) {
    if (e.kind !== "publish") continue;
    for (const to of subs.get(e.to) ?? []) {
      const key = `${e.from}\n${to}`;
      if (!pairs.has(key)) pairs.set(key, { from: e.from, to, kind: "flow", topics: [] });
      pairs.get(key)!.topics.push(e.to);
    }
  }
  const edges = [...pairs.values()].map((p) => ({ ...p, label: p.topics.join(", ") }));
  return { vertices: nodes, edges };
}

function boundary(box: Box, kind: Kind, toward: Point): Point {
  const dx = toward.x - box.x;
  const dy = toward.y - box.y;
  if (!dx && !dy) return { x: box.x, y: box.y };
  const t = kind === "node"
    ? 1 / Math.hypot(dx / (box.w / 2), dy / (box.h / 2))
    : Math.min(dx ? box.w / 2 / Math.abs(dx) : Infinity, dy ? box.h / 2 / Math.abs(dy) : Infinity);
  return { x: box.x + dx * t, y: box.y + dy * t };
}

function curve(points: Point[], bow: number): string {
  let d = `M${points[0]!.x},${points[0]!.y}`;
  for (let i = 1; i < points.length; i++) {
    const a = points[i - 1]!;
    const b = points[i]!;
    const dx = (b.x - a.x) / 2;
    d += ` C${a.x + dx},${a.y + bow} ${b.x - dx},${b.y + bow} ${b.x},${b.y}`;
  }
  return d;
}

function drawEdge(route: Route<Edge>, boxes: Map<string, Box>, kinds: Map<string, Kind>, marker: string):
  { g: SVGGElement; line: SVGPathElement; labelAt: Point | undefined; label: string | undefined } {
  const e = route.edge;
  const g = sv("g", { class: "graph-edge", "data-from": e.from, "data-to": e.to, "data-kind": e.kind });
  const line = sv("path", { "marker-end": `url(#${marker})` });
  let labelAt: Point | undefined;
  if (route.loop) {
    const b = boxes.get(e.from)!;
    const top = b.y - b.h / 2;
    line.setAttribute("d", `M${b.x - 14},${top + 2} C${b.x - 34},${top - 36} ${b.x + 34},${top - 36} ${b.x + 14},${top + 1}`);
    labelAt = { x: b.x, y: top - 30 };
  } else {
    const pts = route.points.map((p) => ({ ...p }));
    pts[0] = boundary(boxes.get(e.from)!, kinds.get(e.from)!, pts[1]!);
    pts[pts.length - 1] = boundary(boxes.get(e.to)!, kinds.get(e.to)!, pts[pts.length - 2]!);
    line.setAttribute("d", curve(pts, route.reversed ? 16 : 0));  // bowed, to miss its forward twin
  }
  const title = sv("title");
  title.textContent = e.label ? `${e.from} → ${e.to}: ${e.label}` : `${e.from} → ${e.to}`;
  g.append(title, line);
  return { g, line, labelAt, label: e.label };
}

function drawVertex(v: Vertex, box: Box): SVGGElement {
  const down = v.state === "crashed" || v.state === "died";
  const cls = [v.kind === "node" ? "graph-node" : "graph-topic", v.hidden ? "debug" : "", down ? "crashed" : ""];
  const g = sv("g", { class: cls.join(" ").trim(), "data-name": v.id, tabindex: "0", role: "button",
    "aria-label": `${v.kind} ${v.id}${down ? ` (${v.state})` : ""}` });
  if (v.state) g.setAttribute("data-state", v.state);
  const title = sv("title");
  title.textContent = v.kind === "topic" ? `${v.id}\n${v.type}` : `${v.id}${down ? ` (${v.state})` : ""}`;
  const shape = v.kind === "node"
    ? sv("ellipse", { cx: box.x, cy: box.y, rx: box.w / 2, ry: box.h / 2 })
    : sv("rect", { x: box.x - box.w / 2, y: box.y - box.h / 2, width: box.w, height: box.h, rx: 3 });
  const text = sv("text", { x: box.x, y: box.y });
  text.textContent = v.id;
  g.append(title, shape, text);
  return g;
}

/** Draw ``view`` into ``svg`` (replacing what it held); the drawing's bounds, padded, in its units. */
export function drawGraph(svg: SVGSVGElement, view: View, markerId = "arrowhead"): ViewBox {
  const vertices = view.vertices.map((v) => ({
    ...v, w: textWidth(v.id) + (v.kind === "node" ? 36 : 18), h: v.kind === "node" ? NODE_H : TOPIC_H,
  }));
  const { boxes, routes, width, height } = layout(vertices, view.edges);
  const kinds = new Map(vertices.map((v) => [v.id, v.kind]));
  const defs = sv("defs");
  const marker = sv("marker", { id: markerId, viewBox: "0 0 10 10", refX: "10", refY: "5",
    markerWidth: "9", markerHeight: "9", markerUnits: "userSpaceOnUse", orient: "auto" });
  marker.append(sv("path", { d: "M0,0 L10,5 L0,10 z" }));
  defs.append(marker);
  const edgeLayer = sv("g", { class: "edges" });
  const vertexLayer = sv("g", { class: "vertices" });
  svg.replaceChildren(defs, edgeLayer, vertexLayer);
  const hasLoop = routes.some((r) => r.loop);
  for (const route of routes) {
    const { g, line, labelAt, label } = drawEdge(route, boxes, kinds, markerId);
    edgeLayer.append(g);
    if (label) {  // placed once the path is in the document and can be measured
      const at = labelAt ?? line.getPointAtLength(line.getTotalLength() / 2);
      const text = sv("text", { x: at.x, y: at.y - 4 });
      text.textContent = label;
      g.append(text);
    }
  }
  for (const v of vertices) vertexLayer.append(drawVertex(v, boxes.get(v.id)!));
  const top = hasLoop ? LOOP_ROOM : 0;
  return { x: -PAD, y: -PAD - top, w: width + 2 * PAD, h: height + 2 * PAD + top };
}
