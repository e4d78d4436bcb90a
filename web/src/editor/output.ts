// A run's output as the page shows it: each line as the node printed it (stderr in red, a ROS 2
// log line coloured by its level), a traceback's `File "...", line N` as a link that opens the
// file at that line when it is in the workspace, what a fast printer lost, and each exit. In a
// traceback the student's frames show and the lab's own frames (rclpy, the launcher: files outside
// the workspace) fold behind a toggle right after its first line, so the student's line is not
// buried under them. The page keeps the last MAX_LINES lines; older ones scroll away (what a
// fast printer lost is said again at its exit if its note went with them).
import type { ExitFrame, JoinedFrame, LineFrame, StartedFrame, WaitingFrame } from "../protocol.gen";

const MAX_LINES = 2000;
const LOG_LEVEL = /^\[(DEBUG|INFO|WARN|ERROR|FATAL)\]/;
const TRACEBACK_FILE = /File "([^"]+)", line (\d+)/;
const TRACEBACK_START = /^Traceback \(most recent call last\):/;
const INDENTED = /^\s/;

/** A traceback being printed by one node: the fold that holds the lab's frames. */
interface Traceback { fold: HTMLDetailsElement; label: HTMLElement; frames: number; inLab: boolean }

/** Where a path a node printed is in the workspace (a workspace path), or null. */
export type Resolve = (printed: string) => string | null;
export type OpenAt = (path: string, line: number) => void;

export class OutputPane {
  readonly element = document.createElement("div");
  /** Lines a fast printer lost (the server's count, summed over this run). */
  dropped = 0;
  lines = 0;
  private droppedNote: HTMLElement | null = null;
  private readonly tracebacks = new Map<string, Traceback>();

  constructor(private readonly resolve: Resolve, private readonly openAt: OpenAt) {
    this.element.className = "output";
    this.element.setAttribute("role", "log");
    this.element.setAttribute("aria-label", "Output");
  }

  clear(heading: string): void {
    this.dropped = 0;
    this.lines = 0;
    this.droppedNote = null;
    this.tracebacks.clear();
    this.element.replaceChildren();
    this.note(heading, "heading");
  }

  private append(row: HTMLElement): void {
    const follow = this.element.scrollTop + this.element.clientHeight >= this.element.scrollHeight - 4;
    this.element.append(row);
    while (this.element.childElementCount > MAX_LINES) this.element.firstElementChild?.remove();
    if (follow) this.element.scrollTop = this.element.scrollHeight;
  }

  note(text: string, kind: string): HTMLElement {
    const row = document.createElement("div");
    row.className = `note ${kind}`;
    row.textContent = text;
    this.append(row);
    return row;
  }

  line(frame: LineFrame, labelled: boolean): void {
    const row = document.createElement("div");
    row.className = `line ${frame.stream}`;
    const level = LOG_LEVEL.exec(frame.text);
    if (level) row.classList.add(`log-${level[1]!.toLowerCase()}`);
    if (labelled) {
      const who = document.createElement("span");
      who.className = "node";
      who.textContent = `[${frame.node}] `;
      row.append(who);
    }
    const file = TRACEBACK_FILE.exec(frame.text);
    const path = file ? this.resolve(file[1]!) : null;
    if (file && path !== null) {
      const lineNo = Number(file[2]);
      const link = document.createElement("a");
      link.href = "#";
      link.className = "traceback";
      link.dataset.path = path;
      link.dataset.line = String(lineNo);
      link.textContent = file[0];
      link.title = `Open ${path} at line ${lineNo}`;
      link.addEventListener("click", (e) => { e.preventDefault(); this.openAt(path, lineNo); });
      row.append(frame.text.slice(0, file.index), link, frame.text.slice(file.index + file[0].length));
    } else {
      row.append(frame.text);
    }
    this.lines++;
    this.place(frame, row, file !== null && path === null);
  }

  /** A line where it goes: in its node's traceback, the lab's frames into the fold. */
  private place(frame: LineFrame, row: HTMLElement, labFile: boolean): void {
    const text = frame.text;
    const open = this.tracebacks.get(frame.node);
    if (TRACEBACK_START.test(text)) {
      this.append(row);
      const fold = document.createElement("details");
      fold.className = "lab-frames";
      fold.hidden = true;
      const label = document.createElement("summary");
      fold.append(label);
      this.append(fold);
      this.tracebacks.set(frame.node, { fold, label, frames: 0, inLab: false });
      return;
    }
    if (!open || !INDENTED.test(text)) {
      this.tracebacks.delete(frame.node);  // the exception's own line ends the traceback
      this.append(row);
      return;
    }
    if (TRACEBACK_FILE.test(text)) open.inLab = labFile;
    if (!open.inLab) { this.append(row); return; }
    if (TRACEBACK_FILE.test(text)) {
      open.frames++;
      open.label.textContent = `${open.frames} frame${open.frames === 1 ? "" : "s"} of the lab's own code (rclpy, the launcher)`;
      open.fold.hidden = false;
    }
    open.fold.append(row);
  }

  droppedLines(count: number): void {
    this.dropped += count;
    const text = `\u2026 ${this.dropped} line${this.dropped === 1 ? "" : "s"} dropped: the node printed faster than the page shows`;
    if (this.droppedNote?.isConnected) this.droppedNote.textContent = text;
    else this.droppedNote = this.note(text, "dropped");
    this.element.dataset.dropped = String(this.dropped);
  }

  waiting(frame: WaitingFrame): void {
    this.note(`[${frame.node}] waiting for its turn to start: this server starts a few node processes at a time`, "waiting");
  }

  /** As ros2 launch logs it. */
  started(frame: StartedFrame): void {
    this.note(`[INFO] [${frame.node}]: process started with pid [${frame.pid}]`, "started");
  }

  joined(frame: JoinedFrame): void {
    this.note(`[${frame.node}] in the graph: ${frame.names.join(", ")}`, "joined");
  }

  exit(frame: ExitFrame): void {
    const how = frame.signal ? `ended by ${frame.signal}`
      : frame.code === null ? "stopped before it started" : `exited with code ${frame.code}`;
    // The drops' note may have scrolled away under the lines after it: said again at the end.
    if (this.dropped > 0 && !this.droppedNote?.isConnected) this.droppedLines(0);
    this.note(`[${frame.node}] ${how}`, frame.code === 0 || frame.signal === "SIGINT" ? "exit" : "exit failed");
  }
}
