// The guide panel's look, light and dark, added to the page with the panel (the lab page is
// viser's own, so its style sheets are the page's to add). layout.ts places the panel.
export const GUIDE_CSS = `
#teleop-guide {
  position: fixed; left: 15px; top: 200px; z-index: 1000; box-sizing: border-box;
  width: min(340px, calc(100vw - 30px)); display: flex; flex-direction: column;
  font: 12px/1.45 system-ui, sans-serif; border-radius: 6px;
  background: rgba(255, 255, 255, 0.94); color: #222; box-shadow: 0 1px 4px rgba(0, 0, 0, 0.2);
}
#teleop-guide > header { display: flex; align-items: center; gap: 6px; padding: 4px 8px; flex: none; }
#teleop-guide > header .summary { flex: 1; opacity: 0.75; white-space: nowrap; overflow: hidden; text-overflow: ellipsis; }
#teleop-guide button {
  font: 12px/1.3 system-ui, sans-serif; padding: 2px 8px; border-radius: 4px; cursor: pointer;
  border: 1px solid #1f5fbf; background: transparent; color: #1f5fbf;
}
#teleop-guide button.fold { font-weight: 600; }
#teleop-guide .body { overflow: auto; padding: 0 8px 8px; min-height: 0; }
#teleop-guide.folded .body, #teleop-guide.squeezed .body { display: none; }
#teleop-guide ol.checkpoints { list-style: none; margin: 0; padding: 0; }
#teleop-guide li.checkpoint { border-top: 1px solid rgba(0, 0, 0, 0.12); padding: 6px 0; }
#teleop-guide .head { display: flex; gap: 6px; align-items: baseline; }
#teleop-guide .head b { flex: 1; }
#teleop-guide .badge { white-space: nowrap; border-radius: 8px; padding: 0 6px; font-size: 11px; background: #e4e4e4; color: #444; }
#teleop-guide [data-state="in_progress"] > .head .badge { background: #ffe1a8; color: #6a4500; }
#teleop-guide [data-state="done"] > .head .badge { background: #c8f0c8; color: #135c13; }
#teleop-guide .progress { margin: 2px 0; font-style: italic; opacity: 0.8; }
#teleop-guide .progress:empty { display: none; }
#teleop-guide ol.steps { margin: 4px 0; padding-left: 18px; }
#teleop-guide ol.steps .page { margin: 1px 0; }
#teleop-guide ol.steps .terminal { font-size: 11px; opacity: 0.8; }
#teleop-guide ol.steps li.already { color: #135c13; }
#teleop-guide code {
  display: inline-block; max-width: 100%; box-sizing: border-box; margin: 1px 0; padding: 0 4px; border-radius: 3px;
  font: 11px/1.4 ui-monospace, monospace; background: rgba(0, 0, 0, 0.07); word-break: break-all; user-select: all;
}
#teleop-guide .guide-question { margin: 6px 0; }
#teleop-guide .guide-question label { display: block; font-weight: 600; margin-bottom: 2px; }
#teleop-guide textarea {
  box-sizing: border-box; width: 100%; resize: vertical; font: 12px/1.4 system-ui, sans-serif;
  border: 1px solid #aaa; border-radius: 4px; padding: 3px 5px; background: #fff; color: #222;
}
#teleop-guide .foot { display: flex; justify-content: space-between; gap: 6px; font-size: 11px; opacity: 0.8; }
#teleop-guide .foot .over, #teleop-guide [data-state="failed"] .saved, #teleop-guide [data-state="too_long"] .saved { color: #b00; opacity: 1; }
#teleop-guide figure.guide-graph { margin: 4px 0; }
#teleop-guide figure.guide-graph svg { display: block; width: 100%; height: 120px; border: 1px solid rgba(0, 0, 0, 0.12); border-radius: 4px; background: #fafafa; }
#teleop-guide figcaption { font-size: 11px; opacity: 0.8; }
#teleop-guide .graph-node ellipse { fill: #dbe8fb; stroke: #1f5fbf; stroke-width: 1.5; }
#teleop-guide .graph-node.crashed ellipse { fill: #fbdada; stroke: #c33; }
#teleop-guide .graph-node text { fill: #222; font-size: 12px; text-anchor: middle; dominant-baseline: central; }
#teleop-guide .graph-edge path { fill: none; stroke: #666; stroke-width: 1.3; }
#teleop-guide .graph-edge text { fill: #666; font-size: 10px; text-anchor: middle; }
#teleop-guide marker path { fill: #666; }
#teleop-guide .report { border-top: 1px solid rgba(0, 0, 0, 0.12); padding-top: 6px; display: flex; flex-wrap: wrap; gap: 6px; align-items: center; }
#teleop-guide .report a { color: #1f5fbf; }
#teleop-guide .error { color: #b00; margin: 4px 0 0; }
#teleop-guide .error:empty { display: none; }
[data-mantine-color-scheme="dark"] #teleop-guide { background: rgba(30, 32, 36, 0.94); color: #eee; }
[data-mantine-color-scheme="dark"] #teleop-guide button, [data-mantine-color-scheme="dark"] #teleop-guide .report a { color: #8ab4f8; border-color: #8ab4f8; }
[data-mantine-color-scheme="dark"] #teleop-guide textarea { background: #1b1c1f; color: #eee; border-color: #555; }
[data-mantine-color-scheme="dark"] #teleop-guide code { background: rgba(255, 255, 255, 0.1); }
[data-mantine-color-scheme="dark"] #teleop-guide figure.guide-graph svg { background: #222; }
[data-mantine-color-scheme="dark"] #teleop-guide .graph-node text { fill: #eee; }
[data-mantine-color-scheme="dark"] #teleop-guide .graph-node ellipse { fill: #24364f; stroke: #8ab4f8; }
@media (max-width: 820px) { #teleop-guide { font-size: 11px; } }
`;
