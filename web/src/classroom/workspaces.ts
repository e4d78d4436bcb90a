// A student's workspace as the instructor opens it from the class table: its files (GET
// /api/classroom/worlds/{world}/workspace/files) and one file's text at a time, read-only: the
// instructor reads a student's code here and never edits it. Every workspace in one zip is the
// header's link (GET /api/classroom/workspaces/archive).
import type { ErrorBody, FileText, WorkspaceEntry, WorkspaceTree } from "../protocol.gen";

const $ = <E extends HTMLElement = HTMLElement>(id: string): E => document.getElementById(id) as E;

async function read<T>(url: string): Promise<T> {
  const reply = await fetch(url, { cache: "no-store" });
  const data = await reply.json().catch(() => ({})) as T | Partial<ErrorBody>;
  if (!reply.ok) {
    const detail = (data as Partial<ErrorBody>).detail;
    throw new Error(typeof detail === "string" ? detail : `HTTP ${reply.status}`);
  }
  return data as T;
}

const messageOf = (err: unknown): string => (err instanceof Error ? err.message : String(err));

async function show(base: string, path: string): Promise<void> {
  const text = $("workspace-text");
  text.textContent = "…";
  $("workspace-path").textContent = path;
  try {
    const file = await read<FileText>(`${base}/${path.split("/").map(encodeURIComponent).join("/")}`);
    text.textContent = file.text;
  } catch (err) {
    text.textContent = messageOf(err);
  }
}

/** Open ``world``'s workspace in the dialog: its files listed, the first shown. */
export async function openWorkspace(world: string, student: string): Promise<void> {
  const base = `/api/classroom/worlds/${encodeURIComponent(world)}/workspace/files`;
  const dialog = $<HTMLDialogElement>("workspace");
  const list = $("workspace-files");
  $("workspace-title").textContent = `${student}'s workspace (read-only)`;
  $("workspace-path").textContent = "";
  $("workspace-text").textContent = "";
  list.replaceChildren();
  if (!dialog.open) dialog.showModal();
  let files: WorkspaceEntry[];
  let tree: WorkspaceTree;
  try {
    tree = await read<WorkspaceTree>(base);
    files = tree.entries.filter((e) => e.kind === "file");
  } catch (err) {
    $("workspace-text").textContent = messageOf(err);
    return;
  }
  if (!files.length) $("workspace-text").textContent = "no files yet";
  for (const entry of files) {
    const item = document.createElement("li");
    const b = document.createElement("button");
    b.type = "button";
    b.textContent = entry.path;
    b.addEventListener("click", () => void show(base, entry.path));
    item.append(b);
    list.append(item);
  }
  if (tree.too_deep) {
    const note = document.createElement("li");
    note.textContent = `${tree.too_deep} more deeper than a workspace path may go, not listed ` +
      `(one is ${tree.too_deep_example ?? "?"})`;
    list.append(note);
  }
  const first = files[0];
  if (first) await show(base, first.path);
}

$("workspace-close").addEventListener("click", () => $<HTMLDialogElement>("workspace").close());
