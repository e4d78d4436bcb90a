// Run the open file as its package's node (POST /api/run, as `ros2 run`) or, for a launch file,
// launch it (POST /api/launch, as `ros2 launch`); stream its output over the run's socket; Stop
// (DELETE, which is Ctrl-C and then the end after a grace period). One run at a time from here.
// The run is "starting" until each of its node processes has its node in the graph (the socket's
// joined frame) or has ended: on a busy class server a start may wait for its turn, and a node
// process takes a second or more to join.
import type { OutputFrame, WorkspaceEntry } from "../protocol.gen";
import { ApiError, runs, workspace } from "./api";
import { parseFrame } from "./frames";
import type { OutputPane } from "./output";

const LAUNCH_FILE = /(^|\/)launch\/[^/]+$|\.launch(\.(xml|py|yaml))?$/;
const CONSOLE_SCRIPT = /["']\s*([\w.-]+)\s*=\s*([\w.]+)\s*:\s*\w+\s*["']/g;
const PACKAGE_NAME = /<name>\s*([^<\s]+)\s*<\/name>/;
const RECONNECT_MS = 1000;
const NORMAL_CLOSE = 1000;  // the server's close after the group's end
const UNKNOWN_RUN = 4404;  // server/base/close_codes.py's NOT_FOUND: no such launch group

export type RunState = "idle" | "starting" | "running" | "stopping" | "ended";

/** What Run starts for a file: ros2 run PACKAGE EXECUTABLE, or ros2 launch PACKAGE FILE. */
export interface Target { kind: "run" | "launch"; pkg: string; name: string }

const dirOf = (path: string): string => path.slice(0, Math.max(0, path.lastIndexOf("/")));

/** The file's package: the nearest folder above it with a package.xml (its <name>), else the
 * folder right under src/ (a folder without a package.xml, as the lab's simple rule runs it). */
async function packageOf(path: string, entries: WorkspaceEntry[]): Promise<{ name: string; dir: string } | null> {
  const files = new Set(entries.filter((e) => e.kind === "file").map((e) => e.path));
  for (let dir = dirOf(path); dir; dir = dirOf(dir)) {
    if (files.has(`${dir}/package.xml`)) {
      const manifest = await workspace.read(`${dir}/package.xml`);
      return { name: PACKAGE_NAME.exec(manifest.text)?.[1] ?? dir.slice(dir.lastIndexOf("/") + 1), dir };
    }
  }
  const parts = path.split("/");
  return parts[0] === "src" && parts.length > 2 ? { name: parts[1]!, dir: `src/${parts[1]!}` } : null;
}

/** What Run would start for ``path``, or why it cannot (an Error's message). */
export async function targetOf(path: string, entries: WorkspaceEntry[]): Promise<Target> {
  const pkg = await packageOf(path, entries);
  if (pkg === null) throw new Error(`${path} is in no package: put it under src/<package>/`);
  const file = path.slice(path.lastIndexOf("/") + 1);
  if (LAUNCH_FILE.test(path)) return { kind: "launch", pkg: pkg.name, name: file };
  if (!file.endsWith(".py")) return { kind: "run", pkg: pkg.name, name: file };  // an ament_cmake program
  const setup = entries.find((e) => e.path === `${pkg.dir}/setup.py`);
  if (setup) {  // an ament_python package runs its console_scripts: the one whose module is this file
    const module = path.slice(pkg.dir.length + 1, -".py".length).replaceAll("/", ".");
    for (const m of (await workspace.read(setup.path)).text.matchAll(CONSOLE_SCRIPT)) {
      if (m[2] === module) return { kind: "run", pkg: pkg.name, name: m[1]! };
    }
    throw new Error(`no console_scripts entry of ${pkg.dir}/setup.py runs ${module}: add "NAME = ${module}:main"`);
  }
  return { kind: "run", pkg: pkg.name, name: file };
}

export interface RunView { state(state: RunState, label: string): void }

export class Runner {
  state: RunState = "idle";
  id: string | null = null;
  private socket: WebSocket | null = null;
  private lastSeq = -1;
  private nodes = new Set<string>();
  private arriving = new Set<string>();  // node processes not in the graph yet, nor ended
  private told = new Set<string>();  // started and joined frames shown (a new socket sends them again)
  private label = "";

  constructor(private readonly output: OutputPane, private readonly view: RunView) {}

  private set(state: RunState, label = this.label): void {
    this.state = state;
    this.label = label;
    this.view.state(state, label);
  }

  async start(target: Target): Promise<void> {
    if (this.state === "starting" || this.state === "running" || this.state === "stopping") return;
    const command = `ros2 ${target.kind} ${target.pkg} ${target.name}`;
    this.output.clear(`$ ${command}`);
    this.id = null;
    this.set("starting", command);
    try {
      const group = target.kind === "launch" ? await runs.launch(target.pkg, target.name) : await runs.run(target.pkg, target.name);
      this.id = group.id;
      this.lastSeq = -1;
      this.nodes.clear();
      this.told.clear();
      this.arriving = new Set(group.nodes.flatMap((n) => (n.process !== null && n.error === null ? [n.process] : [])));
      this.set(this.arriving.size ? "starting" : "running");
      this.connect(group.id);
    } catch (exc) {
      this.output.note(exc instanceof ApiError ? `refused: ${exc.message}` : String(exc), "error");
      this.set("idle");
    }
  }

  /** Whether Stop applies: a run the server has, starting or running. */
  get stoppable(): boolean {
    return this.id !== null && (this.state === "running" || this.state === "starting");
  }

  async stop(): Promise<void> {
    const id = this.id;
    if (id === null || !this.stoppable) return;
    const was = this.state;
    this.set("stopping");
    try {
      await runs.stop(id);
    } catch (exc) {
      if (exc instanceof ApiError && exc.status === 404) { this.ended(); return; }
      this.output.note(`Stop failed: ${exc instanceof ApiError ? exc.message : String(exc)}`, "error");
      this.set(was);
    }
  }

  private connect(id: string): void {
    const socket = runs.outputSocket(id);
    this.socket = socket;
    socket.onmessage = (ev: MessageEvent) => {
      const frame = parseFrame(ev.data);
      if (frame && id === this.id) this.take(frame);
    };
    socket.onclose = (ev) => {
      if (socket !== this.socket || id !== this.id || this.state === "ended") return;
      if (ev.code === NORMAL_CLOSE || ev.code === UNKNOWN_RUN) {  // the run is over, or gone
        if (ev.code === UNKNOWN_RUN) this.output.note(`the run is gone: ${ev.reason}`, "error");
        this.ended();
        return;
      }
      this.output.note(`the output's connection closed (${ev.code}${ev.reason ? `: ${ev.reason}` : ""}); reconnecting`, "error");
      setTimeout(() => { if (id === this.id && this.state !== "ended") this.connect(id); }, RECONNECT_MS);
    };
  }

  private take(frame: OutputFrame): void {
    switch (frame.type) {
      case "line":
        if (frame.seq <= this.lastSeq) return;  // a new socket sends the buffered lines again
        this.lastSeq = frame.seq;
        this.nodes.add(frame.node);
        this.output.line(frame, this.nodes.size > 1 || this.label.startsWith("ros2 launch"));
        return;
      case "dropped":
        this.output.droppedLines(frame.count);
        return;
      case "waiting":
        this.output.waiting(frame);
        return;
      case "started":
        if (this.tell(frame)) this.output.started(frame);
        return;
      case "joined":
        if (this.tell(frame)) this.output.joined(frame);
        this.arrived(frame.node);
        return;
      case "exit":
        this.output.exit(frame);
        this.arrived(frame.node);
        return;
      case "end":
        this.ended();
    }
  }

  /** Whether this start or arrival is news (not one a reconnected socket sends again). */
  private tell(frame: { type: string; node: string }): boolean {
    const key = `${frame.type} ${frame.node}`;
    if (this.told.has(key)) return false;
    this.told.add(key);
    return true;
  }

  /** A node process joined the graph or ended: the run is running once none is still arriving. */
  private arrived(node: string): void {
    if (this.arriving.delete(node) && !this.arriving.size && this.state === "starting") this.set("running");
  }

  private ended(): void {
    this.set("ended");
    this.socket?.close();
    this.socket = null;
  }
}
