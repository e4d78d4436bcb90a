// Layered left-to-right graph layout for the tools page, as rqt_graph's dot draws it, in brief:
// cycles broken by reversing DFS back edges; longest-path layers, then vertices with no more
// inputs than outputs pulled up to their successors; long edges split by invisible dummy
// vertices; barycenter ordering sweeps, keeping the order with the fewest crossings; then y
// pulled toward the neighbours without overlap.
// Pure: sizes in, coordinates out.
const LAYER_GAP = 44;  // px between the widest boxes of two layers, room for arrowheads
const ROW_GAP = 18;  // px between boxes in one layer
const DUMMY_H = 6;  // px a long edge takes where it crosses a layer
const SWEEPS = 16;

export interface Sized { id: string; w: number; h: number }
export interface Link { from: string; to: string }
export interface Box { x: number; y: number; w: number; h: number }  // x, y: the centre
export interface Point { x: number; y: number }
/** An edge's path through the layers, from edge.from to edge.to; or a self-loop. */
export interface Route<E extends Link> { edge: E; loop: boolean; points: Point[]; reversed?: boolean }
export interface Layout<E extends Link> { boxes: Map<string, Box>; routes: Route<E>[]; width: number; height: number }
type Adjacent = Map<string, string[]>;

const at = <K, V>(map: Map<K, V>, key: K): V => map.get(key)!;

/** Indices of the edges to reverse so that the graph has no cycle (DFS back edges). */
export function backEdges(ids: string[], edges: Link[]): Set<number> {
  const out = new Map<string, number[]>(ids.map((id) => [id, []]));
  const indeg = new Map<string, number>(ids.map((id) => [id, 0]));
  edges.forEach((e, i) => { at(out, e.from).push(i); indeg.set(e.to, at(indeg, e.to) + 1); });
  const seen = new Map<string, 1 | 2>();  // 1: on the DFS stack, 2: finished
  const back = new Set<number>();
  const visit = (v: string): void => {
    seen.set(v, 1);
    for (const i of at(out, v)) {
      const w = edges[i]!.to;
      if (seen.get(w) === 1) back.add(i);
      else if (!seen.has(w)) visit(w);
    }
    seen.set(v, 2);
  };
  const starts = [...ids].sort((a, b) => at(indeg, a) - at(indeg, b));
  for (const v of starts) if (!seen.has(v)) visit(v);
  return back;
}

export function assignLayers(ids: string[], dag: Array<[string, string]>): Map<string, number> {
  const preds = new Map<string, string[]>(ids.map((id) => [id, []]));
  const succs = new Map<string, string[]>(ids.map((id) => [id, []]));
  for (const [u, v] of dag) { at(succs, u).push(v); at(preds, v).push(u); }
  const layer = new Map<string, number>();
  const waiting = new Map<string, number>(ids.map((id) => [id, at(preds, id).length]));
  const queue = ids.filter((id) => waiting.get(id) === 0);
  for (let k = 0; k < queue.length; k++) {
    const v = queue[k]!;
    layer.set(v, Math.max(0, ...at(preds, v).map((p) => at(layer, p) + 1)));
    for (const w of at(succs, v)) {
      waiting.set(w, at(waiting, w) - 1);
      if (waiting.get(w) === 0) queue.push(w);
    }
  }
  // Longest path packs everything to the left. Moving a vertex right by one shortens its
  // outgoing edges and lengthens its incoming ones, so, sinks first, move each vertex with no
  // more inputs than outputs up against its nearest successor (a source always qualifies).
  for (let k = queue.length - 1; k >= 0; k--) {
    const v = queue[k]!;
    if (at(succs, v).length && at(preds, v).length <= at(succs, v).length) {
      layer.set(v, Math.min(...at(succs, v).map((s) => at(layer, s))) - 1);
    }
  }
  return layer;
}

export function crossings(upper: string[], lower: string[], down: Adjacent): number {
  const pos = new Map(lower.map((v, i) => [v, i]));
  const segs: Array<[number, number]> = [];
  upper.forEach((u, i) => { for (const w of down.get(u) ?? []) segs.push([i, at(pos, w)]); });
  let n = 0;
  for (let a = 0; a < segs.length; a++) {
    for (let b = a + 1; b < segs.length; b++) {
      const [a0, a1] = segs[a]!, [b0, b1] = segs[b]!;
      if ((a0 - b0) * (a1 - b1) < 0) n++;
    }
  }
  return n;
}

function totalCrossings(layers: string[][], down: Adjacent): number {
  let n = 0;
  for (let l = 0; l + 1 < layers.length; l++) n += crossings(layers[l]!, layers[l + 1]!, down);
  return n;
}

function reorder(layer: string[], fixed: string[], neighbours: Adjacent): string[] {
  const pos = new Map(fixed.map((v, i) => [v, i]));
  const key = new Map(layer.map((v, i) => {
    const ns = (neighbours.get(v) ?? []).filter((w) => pos.has(w));
    return [v, ns.length ? ns.reduce((s, w) => s + at(pos, w), 0) / ns.length : i * fixed.length / Math.max(1, layer.length)];
  }));
  return layer.map((v, i): [string, number] => [v, i])
    .sort((a, b) => at(key, a[0]) - at(key, b[0]) || a[1] - b[1]).map((a) => a[0]);
}

function order(layers: string[][], up: Adjacent, down: Adjacent): string[][] {
  let best = layers.map((l) => [...l]);
  let bestCount = totalCrossings(best, down);
  const cur = best.map((l) => [...l]);
  for (let s = 0; s < SWEEPS && bestCount > 0; s++) {
    if (s % 2 === 0) for (let l = 1; l < cur.length; l++) cur[l] = reorder(cur[l]!, cur[l - 1]!, up);
    else for (let l = cur.length - 2; l >= 0; l--) cur[l] = reorder(cur[l]!, cur[l + 1]!, down);
    const count = totalCrossings(cur, down);
    if (count < bestCount) { best = cur.map((l) => [...l]); bestCount = count; }
  }
  return best;
}

// y of each box: centred layers first, then pulled toward the mean y of their neighbours.
function placeY(layers: string[][], size: Map<string, { w: number; h: number }>, up: Adjacent, down: Adjacent): Map<string, number> {
  const y = new Map<string, number>();
  const h = (v: string): number => at(size, v).h;
  const heights = layers.map((l) => l.reduce((s, v) => s + h(v), 0) + ROW_GAP * (l.length - 1));
  const tallest = Math.max(0, ...heights);
  layers.forEach((l, i) => {
    let top = (tallest - heights[i]!) / 2;
    for (const v of l) { y.set(v, top + h(v) / 2); top += h(v) + ROW_GAP; }
  });
  for (let pass = 0; pass < 6; pass++) {
    for (const l of layers) {
      const want = l.map((v) => {
        const ns = [...(up.get(v) ?? []), ...(down.get(v) ?? [])];
        return ns.length ? ns.reduce((s, w) => s + at(y, w), 0) / ns.length : at(y, v);
      });
      // Push down from the top, push up from the bottom, and take the mean: both keep the
      // spacing, so their mean does too, and neither side is favoured.
      const gap = (i: number): number => h(l[i]!) / 2 + ROW_GAP + h(l[i + 1]!) / 2;
      const pushed = [...want];
      for (let i = 1; i < l.length; i++) pushed[i] = Math.max(want[i]!, pushed[i - 1]! + gap(i - 1));
      const pulled = [...want];
      for (let i = l.length - 2; i >= 0; i--) pulled[i] = Math.min(want[i]!, pulled[i + 1]! - gap(i));
      const placed = pushed.map((d, i) => (d + pulled[i]!) / 2);
      l.forEach((v, i) => y.set(v, placed[i]!));
    }
  }
  const top = Math.min(...[...y].map(([v, c]) => c - h(v) / 2));
  for (const [v, c] of y) y.set(v, c - top);
  return y;
}

/** Boxes (centres) for the vertices, and a route for each edge, in a width × height drawing (px). */
export function layout<E extends Link>(vertices: Sized[], edges: E[]): Layout<E> {
  const ids = vertices.map((v) => v.id);
  const size = new Map(vertices.map((v) => [v.id, { w: v.w, h: v.h }]));
  const plain = edges.map((e, i): [E, number] => [e, i])
    .filter(([e]) => e.from !== e.to && size.has(e.from) && size.has(e.to));
  const back = backEdges(ids, plain.map(([e]) => e));
  const dag = plain.map(([e], k): [string, string] => (back.has(k) ? [e.to, e.from] : [e.from, e.to]));
  const layer = assignLayers(ids, dag);
  const up: Adjacent = new Map();
  const down: Adjacent = new Map();
  const link = (a: string, b: string): void => {
    if (!down.has(a)) down.set(a, []);
    if (!up.has(b)) up.set(b, []);
    at(down, a).push(b);
    at(up, b).push(a);
  };
  const chains = dag.map(([u, v], k) => {
    const chain = [u];
    for (let l = at(layer, u) + 1; l < at(layer, v); l++) {
      const d = `\u0000dummy${k}:${l}`;
      layer.set(d, l);
      size.set(d, { w: 0, h: DUMMY_H });
      chain.push(d);
    }
    chain.push(v);
    for (let i = 0; i + 1 < chain.length; i++) link(chain[i]!, chain[i + 1]!);
    return chain;
  });
  const count = Math.max(0, ...[...layer.values()]) + 1;
  const layers = Array.from({ length: ids.length ? count : 0 }, (): string[] => []);
  for (const [v, l] of layer) layers[l]!.push(v);
  const ordered = order(layers, up, down);
  const y = placeY(ordered, size, up, down);
  const boxes = new Map<string, Box>();
  let left = 0;
  for (const l of ordered) {
    const w = Math.max(0, ...l.map((v) => at(size, v).w));
    for (const v of l) boxes.set(v, { x: left + w / 2, y: at(y, v), ...at(size, v) });
    left += w + LAYER_GAP;
  }
  const routes: Route<E>[] = edges.map((e) => ({ edge: e, loop: e.from === e.to, points: [] }));
  plain.forEach(([, i], k) => {
    const pts = chains[k]!.map((v) => ({ x: at(boxes, v).x, y: at(boxes, v).y }));
    routes[i]!.points = back.has(k) ? pts.reverse() : pts;
    routes[i]!.reversed = back.has(k);
  });
  const height = Math.max(0, ...[...boxes.values()].map((b) => b.y + b.h / 2));  // dummies too
  for (const id of [...boxes.keys()]) if (id.startsWith("\u0000")) boxes.delete(id);
  return { boxes, routes, width: Math.max(0, left - LAYER_GAP), height };
}
