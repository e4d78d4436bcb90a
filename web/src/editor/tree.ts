// The workspace's packages and files as a tree: folders fold, a click on a file opens it, the
// open file is marked. The tree is drawn again from each listing the server gives (the poll in
// main.ts asks for one whenever the workspace's version may have changed).
import type { WorkspaceEntry } from "../protocol.gen";

export interface TreeActions {
  open(path: string): void;
  select(path: string): void;
}

interface Node { entry: WorkspaceEntry; children: Node[] }

const nest = (entries: WorkspaceEntry[]): Node[] => {
  const roots: Node[] = [];
  const dirs = new Map<string, Node>();
  for (const entry of [...entries].sort((a, b) => a.path.localeCompare(b.path))) {
    const node: Node = { entry, children: [] };
    const slash = entry.path.lastIndexOf("/");
    const parent = slash < 0 ? undefined : dirs.get(entry.path.slice(0, slash));
    (parent ? parent.children : roots).push(node);
    if (entry.kind === "dir") dirs.set(entry.path, node);
  }
  const order = (nodes: Node[]): Node[] => {
    nodes.sort((a, b) => (a.entry.kind === b.entry.kind ? a.entry.path.localeCompare(b.entry.path) : a.entry.kind === "dir" ? -1 : 1));
    for (const n of nodes) order(n.children);
    return nodes;
  };
  return order(roots);
};

const baseName = (path: string): string => path.slice(path.lastIndexOf("/") + 1);

export class FileTree {
  readonly element = document.createElement("div");
  /** The file or folder the student picked last (new files go in it; rename and delete act on it). */
  selected: string | null = null;
  private opened: string | null = null;
  private readonly folded = new Set<string>();
  private entries: WorkspaceEntry[] = [];

  constructor(private readonly actions: TreeActions) {
    this.element.className = "tree";
    this.element.setAttribute("role", "tree");
    this.element.setAttribute("aria-label", "Workspace files");
  }

  get paths(): WorkspaceEntry[] {
    return this.entries;
  }

  show(entries: WorkspaceEntry[]): void {
    this.entries = entries;
    if (this.selected !== null && !entries.some((e) => e.path === this.selected)) this.selected = null;
    this.draw();
  }

  markOpen(path: string | null): void {
    this.opened = path;
    if (path !== null) {
      this.selected = path;
      for (let i = path.indexOf("/"); i > 0; i = path.indexOf("/", i + 1)) this.folded.delete(path.slice(0, i));
    }
    this.draw();
  }

  private draw(): void {
    const list = document.createElement("ul");
    const add = (nodes: Node[], into: HTMLUListElement, depth: number): void => {
      for (const node of nodes) {
        const { path, kind } = node.entry;
        const item = document.createElement("li");
        const row = document.createElement("button");
        row.type = "button";
        row.className = `row ${kind}`;
        row.dataset.path = path;
        row.style.paddingLeft = `${6 + depth * 14}px`;
        const folded = this.folded.has(path);
        row.textContent = (kind === "dir" ? (folded ? "\u25B8 " : "\u25BE ") : "") + baseName(path);
        row.title = path;
        if (path === this.opened) row.setAttribute("aria-current", "true");
        if (path === this.selected) row.classList.add("selected");
        row.addEventListener("click", () => {
          this.selected = path;
          if (kind === "dir") {
            if (folded) this.folded.delete(path); else this.folded.add(path);
            this.actions.select(path);
            this.draw();
          } else {
            this.actions.open(path);
          }
        });
        item.append(row);
        if (kind === "dir" && !folded && node.children.length) {
          const sub = document.createElement("ul");
          add(node.children, sub, depth + 1);
          item.append(sub);
        }
        into.append(item);
      }
    };
    add(nest(this.entries), list, 0);
    if (!this.entries.length) {
      const empty = document.createElement("p");
      empty.className = "empty";
      empty.textContent = "The workspace is empty: make a package with \u201CNew package\u201D.";
      this.element.replaceChildren(empty);
      return;
    }
    this.element.replaceChildren(list);
  }
}
