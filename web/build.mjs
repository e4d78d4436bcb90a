// Bundles the page's TypeScript (src/) into ../static/build/, one script per page and one for the
// pose worker, with esbuild. The bundles are IIFEs loaded as classic scripts: the lab page's
// must run in <head>, before viser's own scripts, so its key capture sees keys first.
// Unminified and without source maps: what the browser runs reads as the sources do.
import { build } from "esbuild";
import { fileURLToPath } from "node:url";

const here = (path) => fileURLToPath(new URL(path, import.meta.url));

await build({
  entryPoints: {
    lab: here("src/lab/main.ts"),
    "poses.worker": here("src/lab/poses.worker.ts"),
    tools: here("src/tools/main.ts"),
    instructor: here("src/classroom/instructor.ts"),
    join: here("src/classroom/join.ts"),
  },
  outdir: here("../static/build"),
  bundle: true,
  format: "iife",
  target: "es2022",
  legalComments: "none",
  logLevel: "warning",
});
