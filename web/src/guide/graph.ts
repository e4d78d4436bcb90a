// The student's computation graph beside the guide's graph question, drawn as the tools page
// draws it (tools/drawing.ts: nodes only, an arrow per publisher → subscriber labelled with its
// topics, debug nodes hidden). It asks GET /api/graph every two seconds while it is on screen
// and redraws only when the graph's version changed.
import type { GraphOut } from "../protocol.gen";
import { drawGraph, sv, viewOf } from "../tools/drawing";

const REFRESH_MS = 2000;
const MIN_H_PX = 90, MAX_H_PX = 240;  // the drawing's height follows its shape, within these
const MARKER_ID = "guide-graph-arrow";

export interface GraphFigure { el: HTMLElement; version: () => number | null; refresh: () => Promise<void> }

export function graphFigure(): GraphFigure {
  const el = document.createElement("figure");
  el.className = "guide-graph";
  const svg = sv("svg", { role: "img", "aria-label": "Your computation graph, nodes only" });
  const caption = document.createElement("figcaption");
  const tools = document.createElement("a");
  tools.href = "/tools"; tools.target = "_blank"; tools.rel = "noopener"; tools.tabIndex = -1;
  tools.textContent = "Graph & topics \u2197";
  caption.append("Your graph now (nodes only) · ", tools);
  el.append(svg, caption);

  let version: number | null = null, asking = false;
  const refresh = async (): Promise<void> => {
    if (asking || document.hidden || !el.isConnected || el.getClientRects().length === 0) return;
    asking = true;
    try {
      const reply = await fetch("/api/graph?hidden=false", { cache: "no-store" });
      if (!reply.ok) return;
      const graph = await reply.json() as GraphOut;
      if (graph.version === version) return;
      const box = drawGraph(svg, viewOf(graph, "nodes"), MARKER_ID);
      svg.setAttribute("viewBox", `${box.x} ${box.y} ${box.w} ${box.h}`);
      const tall = (el.clientWidth * box.h) / Math.max(box.w, 1);
      svg.style.height = `${Math.round(Math.min(MAX_H_PX, Math.max(MIN_H_PX, tall)))}px`;
      version = graph.version;
      svg.dataset.version = String(version);
    } catch { /* the next refresh tries again */ } finally {
      asking = false;
    }
  };
  setInterval(() => void refresh(), REFRESH_MS);
  requestAnimationFrame(() => void refresh());
  return { el, version: () => version, refresh };
}
