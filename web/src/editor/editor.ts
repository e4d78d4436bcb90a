// The code editor: CodeMirror 6 with its basic set-up (line numbers, indentation, search, undo
// history, bracket matching), Python or XML highlighting by the file's name, and a 4-space indent
// as PEP 8 and the handout write Python. One editor view; opening a file swaps its document.
// Ctrl-S (Cmd-S) saves at once instead of offering to save the page.
import { python } from "@codemirror/lang-python";
import { xml } from "@codemirror/lang-xml";
import { indentUnit } from "@codemirror/language";
import { EditorState, type Extension } from "@codemirror/state";
import { EditorView, keymap } from "@codemirror/view";
import { indentWithTab } from "@codemirror/commands";
import { basicSetup } from "codemirror";

const XML_FILE = /\.(xml|launch|urdf|xacro|sdf|srdf)$/i;
const PY_FILE = /\.py$/i;

const languageOf = (path: string): Extension =>
  PY_FILE.test(path) ? python() : XML_FILE.test(path) ? xml() : [];

/** The editor view, and what it reports: every change of its text, by the student. */
export class CodeEditor {
  readonly view: EditorView;
  private quiet = false;

  constructor(parent: HTMLElement, onEdit: () => void, private readonly onSave: () => void) {
    this.view = new EditorView({
      parent,
      state: this.stateFor("", ""),
      dispatch: (tr, view) => {
        view.update([tr]);
        if (tr.docChanged && !this.quiet) onEdit();
      },
    });
  }

  private stateFor(path: string, text: string): EditorState {
    return EditorState.create({
      doc: text,
      extensions: [
        basicSetup,
        keymap.of([indentWithTab, { key: "Mod-s", preventDefault: true, run: () => { this.onSave(); return true; } }]),
        indentUnit.of("    "),
        EditorState.tabSize.of(4),
        languageOf(path),
        EditorState.readOnly.of(path === ""),
        EditorView.theme({ "&": { height: "100%" }, ".cm-scroller": { overflow: "auto" } }),
        EditorView.lineWrapping,  // a long line wraps in a narrow pane rather than hiding its end
      ],
    });
  }

  /** Show ``text`` as ``path``'s, with a fresh undo history (an open is not an edit). */
  open(path: string, text: string): void {
    this.view.setState(this.stateFor(path, text));
  }

  /** Replace the text (the file changed elsewhere), keeping the cursor where it can be. */
  replace(text: string): void {
    const head = Math.min(this.view.state.selection.main.head, text.length);
    this.quiet = true;
    try {
      this.view.dispatch({ changes: { from: 0, to: this.view.state.doc.length, insert: text }, selection: { anchor: head } });
    } finally {
      this.quiet = false;
    }
  }

  get text(): string {
    return this.view.state.doc.toString();
  }

  /** Put the cursor at the start of ``line`` (1-based, clamped), scroll to it and take focus. */
  goToLine(line: number): void {
    const doc = this.view.state.doc;
    const at = doc.line(Math.max(1, Math.min(line, doc.lines)));
    this.view.dispatch({ selection: { anchor: at.from, head: at.to }, scrollIntoView: true });
    this.view.focus();
  }
}
