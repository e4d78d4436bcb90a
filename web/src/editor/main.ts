// The code view (its own bundle, loaded when the lab page's Code tab first opens): the workspace's
// tree, the editor with its save state, Run/Stop for the open file and the run's live output. The
// tree follows the workspace: it is listed again every POLL_MS while the view is shown, and a file
// changed on disk reloads in the editor when nothing here is unsaved.
import Split from "split.js";
import * as actions from "./actions";
import type { WorkspaceEntry } from "../protocol.gen";
import { ApiError, workspace } from "./api";
import { OpenFile, type SaveState } from "./autosave";
import { CodeEditor } from "./editor";
import { OutputPane } from "./output";
import { Runner, targetOf, type RunState } from "./runner";
import { CSS } from "./style";
import { FileTree } from "./tree";

const POLL_MS = 1500;
const STORE_OUTPUT_SPLIT = "teleop.workbench.output";
const OUTPUT_SPLIT = [70, 30];  // % of the code pane's height: the editor, the output
const SAVE_WORDS: Record<SaveState, string> = {
  none: "", saved: "\u2713 saved", unsaved: "\u25CF unsaved", saving: "saving \u2026", failed: "\u26A0 not saved", conflict: "\u26A0 changed elsewhere",
};

export interface CodeViewHost { close(): void }
export interface CodeViewHandle { shown(open: boolean): void }

const el = <K extends keyof HTMLElementTagNameMap>(tag: K, cls = "", text = ""): HTMLElementTagNameMap[K] => {
  const e = document.createElement(tag);
  if (cls) e.className = cls;
  if (text) e.textContent = text;
  return e;
};
const button = (label: string, title: string, cls = ""): HTMLButtonElement => {
  const b = el("button", cls, label);
  b.type = "button";
  b.title = title;
  return b;
};
const message = (exc: unknown): string => (exc instanceof ApiError ? exc.message : exc instanceof Error ? exc.message : String(exc));

/** The editor above, the run's output below, with a gutter between them; the student's split
 * is kept in the browser. */
function splitOutput(top: HTMLElement, output: HTMLElement): void {
  let sizes = OUTPUT_SPLIT;
  try {
    const saved = JSON.parse(localStorage.getItem(STORE_OUTPUT_SPLIT) ?? "null") as unknown;
    if (Array.isArray(saved) && saved.length === 2 && saved.every((v) => typeof v === "number")) sizes = saved;
  } catch { /* the defaults */ }
  Split([top, output], {
    direction: "vertical", sizes, minSize: [160, 48], gutterSize: 6, snapOffset: 0,
    gutter: () => { const g = el("div", "teleop-gutter gutter-vertical"); g.title = "Drag to size the output"; return g; },
    onDragEnd: (s) => localStorage.setItem(STORE_OUTPUT_SPLIT, JSON.stringify(s)),
  });
}

/** Build the code view inside ``host`` (the lab page's panel). */
export function mountCodeView(host: HTMLElement, lab: CodeViewHost): CodeViewHandle {
  const style = el("style");
  style.textContent = CSS;
  document.head.append(style);

  const body = el("div", "code-body");
  const bar = el("div", "bar");
  const [newPkg, newFile, renameB, deleteB, download, uploadB, close] = [
    button("New package", "Make a package, as ros2 pkg create does"),
    button("New file", "An empty file, or one of the lab's starting files"),
    button("Rename", "Rename or move the selected file or folder"),
    button("Delete", "Delete the selected file or folder"),
    el("a", "button", "Download zip"),
    button("Upload", "Upload a zip of a workspace, or files into the selected folder"),
    button("\u2715", "Close the code view (the 3D view takes its room)"),
  ] as const;
  download.href = workspace.archiveUrl;
  download.setAttribute("download", "workspace.zip");
  const picker = el("input");
  picker.type = "file";
  picker.multiple = true;
  picker.hidden = true;
  bar.append(el("span", "title", "Code"), newPkg, newFile, renameB, deleteB, download, uploadB, picker, el("span", "spacer"), close);

  const problem = el("div", "problem");
  problem.hidden = true;
  problem.setAttribute("role", "alert");
  const split = el("div", "split");
  const pane = el("div", "pane");
  const fileBar = el("div", "file-bar");
  const pathLabel = el("span", "path", "no file open");
  const saveState = el("span", "save-state");
  saveState.setAttribute("aria-live", "polite");
  fileBar.append(pathLabel, saveState);
  const conflict = el("div", "problem conflict");
  conflict.hidden = true;
  const cmHost = el("div", "cm-host");
  pane.append(fileBar, conflict, cmHost);

  const runBar = el("div", "bar run-bar");
  const runB = button("\u25B6 Run", "Run the open file: its package's node (ros2 run) or launch file (ros2 launch)", "primary");
  const stopB = button("\u25A0 Stop", "Ctrl-C, then the end after a grace period", "stop");
  const runState = el("span", "run-state");
  runBar.append(runB, stopB, runState);

  const showProblem = (text: string): void => { problem.textContent = text; problem.hidden = !text; };
  const editor = new CodeEditor(cmHost, () => file.edited(), () => void file.flush());
  const file = new OpenFile(editor, {
    show(state, path, detail) {
      saveState.dataset.state = state;
      saveState.textContent = SAVE_WORDS[state];
      saveState.title = detail;
      pathLabel.textContent = path ?? "no file open";
      if (state === "failed") showProblem(`Not saved: ${detail}. Your text is kept here; it saves again with your next edit.`);
      else if (state !== "conflict") showProblem("");
      showConflict(state === "conflict" ? detail : null);
      runB.disabled = path === null || runner.state === "running" || runner.state === "starting" || runner.state === "stopping";
    },
  });
  const tree = new FileTree({
    open: (path) => void openFile(path),
    select: () => undefined,
  });
  split.append(tree.element, pane);

  const resolvePrinted = (printed: string): string | null => {
    const hits = tree.paths.filter((e) => e.kind === "file" && (printed === e.path || printed.endsWith(`/${e.path}`)));
    return hits.sort((a, b) => b.path.length - a.path.length)[0]?.path ?? null;
  };
  const output = new OutputPane(resolvePrinted, (path, line) => void openFile(path, line));
  const runner = new Runner(output, {
    state(state: RunState, label: string) {
      runState.dataset.state = state;
      runState.textContent = state === "idle" ? "" : `${label} \u2014 ${state}`;
      runB.disabled = file.path === null || state === "running" || state === "starting" || state === "stopping";
      stopB.disabled = !runner.stoppable;
    },
  });
  stopB.disabled = true;
  runB.disabled = true;
  const top = el("div", "code-top");
  top.append(bar, problem, split, runBar);
  body.append(top, output.element);
  host.append(body);
  splitOutput(top, output.element);

  function showConflict(detail: string | null): void {
    conflict.hidden = detail === null;
    if (detail === null) return;
    const theirs = button("Reload theirs", "Drop your changes here and take the version saved elsewhere");
    const mine = button("Overwrite with mine", "Save your text over the version saved elsewhere");
    theirs.addEventListener("click", () => void file.takeTheirs());
    mine.addEventListener("click", () => void file.keepMine());
    conflict.replaceChildren(`This file was changed elsewhere (${detail}). Autosave has stopped until you choose:`, theirs, mine);
  }

  async function openFile(path: string, line?: number): Promise<void> {
    try {
      if (await file.open(path, line)) tree.markOpen(path);
      else showProblem(`Not switching to ${path}: ${file.path ?? "this file"} is not saved yet.`);
    } catch (exc) {
      showProblem(`Could not open ${path}: ${message(exc)}`);
    }
  }

  let version = "";
  let polling = false;
  async function refresh(force = false): Promise<WorkspaceEntry[]> {
    if (polling && !force) return tree.paths;
    polling = true;
    try {
      const listedAt = file.generation;
      const listing = await workspace.tree();
      if (force || listing.version !== version) {
        version = listing.version;
        tree.show(listing.entries);
        if (listing.too_deep) {
          showProblem(`${listing.too_deep} file(s) or folder(s) lie deeper than a workspace path may go and are not ` +
            `listed, zipped or run from here (one is ${listing.too_deep_example ?? "?"}).`);
        }
        if (file.path !== null) {
          const mine = listing.entries.find((e) => e.path === file.path);
          await file.changedElsewhere(mine?.etag ?? null, listedAt);
        }
      }
      return listing.entries;
    } catch (exc) {
      showProblem(`Could not list the workspace: ${message(exc)}`);
      return tree.paths;
    } finally {
      polling = false;
    }
  }

  const act = (b: HTMLButtonElement, work: () => Promise<void>): void => {
    b.addEventListener("click", () => {
      showProblem("");
      work().catch((exc: unknown) => showProblem(message(exc))).finally(() => void refresh(true));
    });
  };
  act(newPkg, async () => {
    const next = await actions.newPackage(host);
    await refresh(true);
    if (next) await openFile(next);
  });
  act(newFile, async () => {
    const next = await actions.newFile(host, tree.selected, tree.paths);
    await refresh(true);
    if (next) await openFile(next);
  });
  act(renameB, async () => {
    const from = tree.selected;
    if (from === null) { showProblem("Select a file or folder in the tree to rename it."); return; }
    if (!(await file.flush())) return;
    const to = await actions.rename(host, from);
    if (to === null) return;
    if (file.path === from) file.closed(to);
    else if (file.path?.startsWith(`${from}/`)) file.closed(to + file.path.slice(from.length));
    tree.markOpen(file.path);
  });
  act(deleteB, async () => {
    const path = tree.selected;
    if (path === null) { showProblem("Select a file or folder in the tree to delete it."); return; }
    if (!(await actions.remove(host, path, tree.paths))) return;
    if (file.path === path || file.path?.startsWith(`${path}/`)) { file.closed(); tree.markOpen(null); }
  });
  uploadB.addEventListener("click", () => picker.click());
  picker.addEventListener("change", () => {
    const files = picker.files;
    if (!files?.length) return;
    actions.upload(files, tree.selected, tree.paths)
      .then((written) => showProblem(written.length ? "" : "The upload wrote nothing."))
      .catch((exc: unknown) => showProblem(`Upload refused: ${message(exc)}`))
      .finally(() => { picker.value = ""; void refresh(true); });
  });
  close.addEventListener("click", () => lab.close());
  runB.addEventListener("click", () => {
    const path = file.path;
    if (path === null) return;
    void (async () => {
      if (!(await file.flush())) { showProblem("Not running: the file is not saved."); return; }
      try {
        await runner.start(await targetOf(path, await refresh(true)));
      } catch (exc) {
        output.clear(`Cannot run ${path}`);
        output.note(message(exc), "error");
      }
    })();
  });
  stopB.addEventListener("click", () => void runner.stop());
  addEventListener("beforeunload", (e) => {
    if (file.state === "unsaved" || file.state === "saving" || file.state === "failed" || file.state === "conflict") {
      void file.flush();
      e.preventDefault();
    }
  });

  let timer: ReturnType<typeof setInterval> | null = null;
  const handle: CodeViewHandle = {
    shown(open: boolean) {
      if (timer !== null) clearInterval(timer);
      timer = open ? setInterval(() => void refresh(), POLL_MS) : null;
      if (open) void refresh();
    },
  };
  handle.shown(true);
  return handle;
}
