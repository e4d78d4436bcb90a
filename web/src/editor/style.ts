// The code view's looks: a toolbar, the tree beside the editor, the run bar and the output below.
export const CSS = `
  #teleop-code .code-body { flex: 1; display: flex; flex-direction: column; min-height: 0; }
  #teleop-code .code-top { display: flex; flex-direction: column; min-height: 0; overflow: hidden; }
  #teleop-code .bar {
    display: flex; flex-wrap: wrap; align-items: center; gap: 4px; padding: 5px 8px;
    border-bottom: 1px solid #ddd; background: #f6f7f9;
  }
  #teleop-code .bar .title { font-weight: 600; margin-right: 6px; }
  #teleop-code .bar .spacer { flex: 1; }
  #teleop-code button, #teleop-code .button {
    font: 12px/1.3 system-ui, sans-serif; padding: 3px 8px; border-radius: 4px; cursor: pointer;
    border: 1px solid #b8bec8; background: #fff; color: #222; text-decoration: none;
  }
  #teleop-code button:disabled { opacity: 0.45; cursor: default; }
  #teleop-code button.primary { background: #1f5fbf; border-color: #1f5fbf; color: #fff; }
  #teleop-code button.stop { background: #c33; border-color: #c33; color: #fff; }
  #teleop-code .split { flex: 1; display: flex; min-height: 0; }
  #teleop-code .tree {
    width: 30%; min-width: 120px; max-width: 280px; overflow: auto; border-right: 1px solid #ddd; padding: 4px 0;
  }
  #teleop-code .tree ul { list-style: none; margin: 0; padding: 0; }
  #teleop-code .tree .row {
    display: block; width: 100%; text-align: left; border: 0; border-radius: 0; background: none;
    padding: 2px 6px; white-space: nowrap; overflow: hidden; text-overflow: ellipsis;
  }
  #teleop-code .tree .row.selected { background: #e3ecfa; }
  #teleop-code .tree .row[aria-current="true"] { font-weight: 600; }
  #teleop-code .tree .empty { padding: 8px; color: #666; }
  #teleop-code .pane { flex: 1; display: flex; flex-direction: column; min-width: 0; }
  #teleop-code .file-bar { display: flex; gap: 8px; align-items: center; padding: 3px 8px; border-bottom: 1px solid #eee; }
  #teleop-code .file-bar .path { flex: 1; font-family: ui-monospace, monospace; font-size: 12px; overflow: hidden; text-overflow: ellipsis; white-space: nowrap; }
  #teleop-code .save-state { font-size: 12px; white-space: nowrap; }
  #teleop-code .save-state[data-state="saved"] { color: #2a7a2a; }
  #teleop-code .save-state[data-state="unsaved"], #teleop-code .save-state[data-state="saving"] { color: #a66a00; }
  #teleop-code .save-state[data-state="failed"], #teleop-code .save-state[data-state="conflict"] { color: #c33; font-weight: 600; }
  #teleop-code .problem { padding: 5px 8px; background: #fdecea; border-bottom: 1px solid #f3b4ae; }
  #teleop-code .problem[hidden] { display: none; }
  #teleop-code .problem button { margin-left: 6px; }
  #teleop-code .cm-host { flex: 1; min-height: 0; overflow: hidden; }
  #teleop-code .cm-editor { height: 100%; font-size: 13px; }
  #teleop-code .run-bar { border-top: 1px solid #ddd; border-bottom: 1px solid #ddd; }
  #teleop-code .run-state { font-family: ui-monospace, monospace; font-size: 12px; }
  #teleop-code .output {
    min-height: 0; overflow: auto; padding: 4px 8px; box-sizing: border-box; background: #1e1f22;
    color: #ddd; font: 12px/1.4 ui-monospace, monospace; white-space: pre-wrap; word-break: break-word;
  }
  #teleop-code .output .stderr { color: #ff8a80; }
  #teleop-code .output .log-warn { color: #ffd166; }
  #teleop-code .output .log-error, #teleop-code .output .log-fatal { color: #ff6b6b; }
  #teleop-code .output .log-debug { color: #9aa; }
  #teleop-code .output .node { color: #8ab4f8; }
  #teleop-code .output .note { color: #aaa; font-style: italic; }
  #teleop-code .output .note.heading { color: #8ab4f8; font-style: normal; }
  #teleop-code .output .note.error, #teleop-code .output .note.failed { color: #ff8a80; }
  #teleop-code .output .note.dropped { color: #ffd166; }
  #teleop-code .output .note.waiting { color: #9ecbff; }
  #teleop-code .output .note.started { font-style: normal; }
  #teleop-code .output .note.joined { color: #a5d6a7; }
  #teleop-code .run-state[data-state="starting"] { color: #9ecbff; }
  #teleop-code .output a.traceback { color: #8ab4f8; }
  #teleop-code .output details.lab-frames { color: #999; margin-left: 2ch; }
  #teleop-code .output details.lab-frames > summary { cursor: pointer; font-style: italic; }
  #teleop-code .code-dialog { border: 1px solid #bbb; border-radius: 8px; padding: 14px 18px; min-width: 300px; }
  #teleop-code .code-dialog h3 { margin: 0 0 8px; font-size: 15px; }
  #teleop-code .code-dialog label { display: block; margin: 6px 0; }
  #teleop-code .code-dialog input, #teleop-code .code-dialog select { display: block; width: 100%; box-sizing: border-box; font: 13px system-ui, sans-serif; padding: 3px; }
  #teleop-code .code-dialog small { color: #666; }
  #teleop-code .code-dialog .buttons { display: flex; justify-content: flex-end; gap: 6px; margin-top: 10px; }
`;
