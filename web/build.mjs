// Bundles the page's TypeScript (src/) into ../static/build/, one script per page and one for the
// pose worker, with esbuild. The bundles are IIFEs loaded as classic scripts: the lab page's
// must run in <head>, before viser's own scripts, so its key capture sees keys first.
// The code view's editor (CodeMirror) is an ES module of its own that the lab page imports the
// first time the student opens the code view, so the page's first load does not carry it.
// Unminified and without source maps: what the browser runs reads as the sources do.
import { build } from "esbuild";
import { fileURLToPath } from "node:url";

const here = (path) => fileURLToPath(new URL(path, import.meta.url));

const common = {
  outdir: here("../static/build"),
  bundle: true,
  target: "es2022",
  legalComments: "none",
  logLevel: "warning",
};

await build({
  ...common,
  format: "iife",
  entryPoints: {
    lab: here("src/lab/main.ts"),
    "poses.worker": here("src/lab/poses.worker.ts"),
    tools: here("src/tools/main.ts"),
    instructor: here("src/classroom/instructor.ts"),
    join: here("src/classroom/join.ts"),
  },
});

await build({ ...common, format: "esm", entryPoints: { editor: here("src/editor/main.ts") } });
