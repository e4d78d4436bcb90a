// The workspace's file operations as the toolbar offers them: a new package (the choices of
// `ros2lab pkg create`), a new file (empty or from one of the lab's templates), rename, delete
// (after a confirmation naming how much goes), and upload (a zip, or text files into the selected
// folder). Each answers with what to open next, or throws an ApiError the toolbar shows.
import type { Template, WorkspaceEntry } from "../protocol.gen";
import { workspace } from "./api";
import { ask, confirmed } from "./dialogs";

const LICENSES: [string, string][] = [
  ["", "none (TODO: License declaration)"], ["Apache-2.0", "Apache-2.0"], ["MIT", "MIT"],
  ["BSD-3-Clause", "BSD-3-Clause"], ["GPL-3.0-only", "GPL-3.0-only"],
];

const folderOf = (selected: string | null, entries: WorkspaceEntry[]): string => {
  if (selected === null) return "";
  const entry = entries.find((e) => e.path === selected);
  return entry?.kind === "dir" ? selected : selected.slice(0, Math.max(0, selected.lastIndexOf("/")));
};

/** The package a folder is in (src/<package>/...), for a template's {package}. */
const packageIn = (folder: string): string => (folder.startsWith("src/") ? folder.split("/")[1] ?? "" : "");

export async function newPackage(host: HTMLElement): Promise<string | null> {
  const a = await ask(host, "New package", [
    { name: "name", label: "Package name", required: true, placeholder: "simple_control" },
    { name: "build_type", label: "Build type", value: "ament_python",
      options: [["ament_python", "ament_python"], ["ament_cmake", "ament_cmake"]] },
    { name: "node_name", label: "Node name (optional)", placeholder: "keyboard_manager",
      hint: "an executable of that name, as ros2 pkg create --node-name writes it" },
    { name: "dependencies", label: "Dependencies (optional)", placeholder: "rclpy std_msgs geometry_msgs" },
    { name: "description", label: "Description (optional)" },
    { name: "license", label: "License", value: "", options: LICENSES },
  ], "Create");
  if (a === null) return null;
  const created = await workspace.createPackage({
    name: a.name ?? "",
    build_type: a.build_type === "ament_cmake" ? "ament_cmake" : "ament_python",
    node_name: a.node_name || null,
    dependencies: (a.dependencies ?? "").split(/[\s,]+/).filter(Boolean),
    description: a.description || null,
    license: a.license || null,
  });
  // The node's file when there is one (what the student edits next), else the manifest.
  const node = a.node_name ? created.files.find((f) => f.endsWith(`/${a.node_name}.py`) || f.endsWith(`/${a.node_name}.cpp`)) : undefined;
  return node ?? created.files.find((f) => f.endsWith("package.xml")) ?? null;
}

export async function newFile(host: HTMLElement, selected: string | null, entries: WorkspaceEntry[]): Promise<string | null> {
  const folder = folderOf(selected, entries);
  let templates: Template[] = [];
  try { templates = await workspace.templates(); } catch { /* an empty file is still offered */ }
  const pathFor = (name: string): string => {
    const t = templates.find((x) => x.name === name);
    const pkg = packageIn(folder);
    return t ? t.path.replaceAll("{package}", pkg || "my_package") : folder ? `${folder}/` : "src/";
  };
  const a = await ask(host, "New file", [
    { name: "template", label: "Start from", value: "",
      options: [["", "an empty file"], ...templates.map((t): [string, string] => [t.name, t.title])],
      hint: templates.length ? "the lab's starting files, with their # TODOs" : "",
      onChange: (value, form) => { (form.elements.namedItem("path") as HTMLInputElement).value = pathFor(value); } },
    { name: "path", label: "Path in the workspace", value: pathFor(""), required: true },
  ], "Create");
  if (a === null || !a.path) return null;
  const text = templates.find((t) => t.name === a.template)?.text ?? "";
  await workspace.write(a.path, text, null);
  return a.path;
}

export async function rename(host: HTMLElement, path: string): Promise<string | null> {
  const a = await ask(host, "Rename", [{ name: "target", label: "New path", value: path, required: true }], "Rename");
  if (a === null || !a.target || a.target === path) return null;
  return (await workspace.rename(path, a.target)).path;
}

export async function remove(host: HTMLElement, path: string, entries: WorkspaceEntry[]): Promise<boolean> {
  const files = entries.filter((e) => e.kind === "file" && (e.path === path || e.path.startsWith(`${path}/`))).length;
  const what = entries.find((e) => e.path === path)?.kind === "dir" ? `the folder ${path} and its ${files} file${files === 1 ? "" : "s"}` : path;
  if (!(await confirmed(host, "Delete", `Delete ${what}? This cannot be undone (download the workspace first to keep a copy).`, "Delete"))) return false;
  await workspace.remove(path);
  return true;
}

/** Upload the chosen files: a zip into the workspace, other files as text into ``folder``. */
export async function upload(files: FileList, selected: string | null, entries: WorkspaceEntry[]): Promise<string[]> {
  const folder = folderOf(selected, entries);
  const written: string[] = [];
  for (const file of Array.from(files)) {
    if (file.name.toLowerCase().endsWith(".zip")) {
      written.push(...(await workspace.upload(file)).written);
    } else {
      const path = folder ? `${folder}/${file.name}` : file.name;
      await workspace.write(path, await file.text(), null);
      written.push(path);
    }
  }
  return written;
}
