// The open file and its saves. An edit marks it unsaved and saves it a moment later (over the
// version this page last read, If-Match); a save that fails says why and keeps the text, and the
// next edit or Retry saves again. A save the server refuses because the file changed elsewhere
// (412: another tab, or an editor on disk) stops autosave and offers the choice: their version
// (reload) or mine (overwrite theirs). Nothing is ever overwritten silently.
import type { StaleSave } from "../protocol.gen";
import { ApiError, workspace } from "./api";
import type { CodeEditor } from "./editor";

export type SaveState = "none" | "saved" | "unsaved" | "saving" | "failed" | "conflict";
const SAVE_AFTER_MS = 600;

export interface SaveView {
  /** The state changed: show it (``detail`` says why a save failed or was refused). */
  show(state: SaveState, path: string | null, detail: string): void;
}

export class OpenFile {
  path: string | null = null;
  state: SaveState = "none";
  private etag: string | null = null;
  private savedText = "";
  private timer: ReturnType<typeof setTimeout> | null = null;
  private saving: Promise<void> | null = null;
  /** The etag the server named in its 412 (null: the file is gone there). */
  private theirs: string | null = null;
  /** Counts opens and saves: a tree listed before the latest of them may show an older etag. */
  generation = 0;

  constructor(private readonly editor: CodeEditor, private readonly ui: SaveView) {}

  private set(state: SaveState, detail = ""): void {
    this.state = state;
    this.ui.show(state, this.path, detail);
  }

  /** Open ``path`` (saving the file open now first); false if that save failed. */
  async open(path: string, line?: number): Promise<boolean> {
    if (path !== this.path && !(await this.flush())) return false;
    if (path !== this.path) {
      const file = await workspace.read(path);
      this.path = file.path;
      this.etag = file.etag;
      this.savedText = file.text;
      this.editor.open(file.path, file.text);
      this.generation++;
      this.set("saved");
    }
    if (line !== undefined) this.editor.goToLine(line);
    return true;
  }

  /** Forget the open file (it was deleted), or follow it to its new name. */
  closed(newPath: string | null = null): void {
    if (newPath !== null) { this.path = newPath; this.set(this.state); return; }
    this.cancel();
    this.path = null; this.etag = null; this.savedText = "";
    this.editor.open("", "");
    this.set("none");
  }

  edited(): void {
    if (this.path === null || this.state === "conflict") return;
    this.set(this.editor.text === this.savedText ? "saved" : "unsaved");
    this.cancel();
    if (this.state === "unsaved") this.timer = setTimeout(() => void this.save(), SAVE_AFTER_MS);
  }

  private cancel(): void {
    if (this.timer !== null) clearTimeout(this.timer);
    this.timer = null;
  }

  /** Save now if there is anything to save; true when the file is saved afterwards. */
  async flush(): Promise<boolean> {
    this.cancel();
    if (this.saving) await this.saving;
    if (this.state === "unsaved" || this.state === "failed") await this.save();
    return this.state === "saved" || this.state === "none";
  }

  private save(): Promise<void> {
    if (this.saving) return this.saving;
    this.saving = this.put(this.etag).finally(() => { this.saving = null; });
    return this.saving;
  }

  private async put(etag: string | null): Promise<void> {
    const path = this.path;
    if (path === null) return;
    this.cancel();
    const text = this.editor.text;
    this.set("saving");
    try {
      const saved = await workspace.write(path, text, etag);
      if (path !== this.path) return;
      this.etag = saved.etag;
      this.savedText = text;
      this.generation++;
      this.set("saved");
      this.edited();  // typed on while it saved: that is unsaved again
    } catch (exc) {
      if (path !== this.path) return;
      if (exc instanceof ApiError && exc.status === 412) {
        const body = exc.body as Partial<StaleSave> | null;
        this.theirs = typeof body?.etag === "string" ? body.etag : null;
        this.set("conflict", exc.detail);
      } else {
        this.set("failed", exc instanceof ApiError ? exc.detail : String(exc));
      }
    }
  }

  /** The conflict's choice: their version replaces the text here. */
  async takeTheirs(): Promise<void> {
    if (this.path === null) return;
    try {
      const file = await workspace.read(this.path);
      this.etag = file.etag;
      this.savedText = file.text;
      this.generation++;
      this.editor.replace(file.text);
      this.set("saved");
    } catch (exc) {
      this.set("conflict", exc instanceof ApiError ? exc.detail : String(exc));
    }
  }

  /** The conflict's other choice: this text overwrites theirs (or re-creates a file deleted there). */
  async keepMine(): Promise<void> {
    if (this.state !== "conflict") return;
    await this.put(this.theirs);
  }

  /** The file changed on disk (the tree's etag is not ours): take it when nothing here is unsaved. */
  async changedElsewhere(etag: string | null, listedAt: number): Promise<void> {
    if (this.path === null || etag === this.etag || this.saving || listedAt !== this.generation) return;
    if (this.state === "saved") {
      if (etag === null) { this.set("conflict", "the file was deleted elsewhere"); this.theirs = null; return; }
      await this.takeTheirs();
    } else if (this.state === "unsaved" || this.state === "failed") {
      this.theirs = etag;
      this.cancel();
      this.set("conflict", "the file changed elsewhere (another tab, or an editor on disk) while you edited it here");
    }
  }
}
