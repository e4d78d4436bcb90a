// A question's answer box in the guide: a text box saved as the student types (a second after
// the last change, and when the box loses focus) with PUT /api/checkpoints/answers/{id}, its
// size against the server's limit, and a line that says what is saved: "saved at 14:02:11",
// "saving…", "not saved: ..." (the server's words; the text stays in the box). An answer saved
// elsewhere (another tab) replaces the box's text only while the box has no unsaved change.
import type { AnswerBody, Question } from "../protocol.gen";
import { ANSWER_LIMIT_BYTES, answerUrl, errorOf } from "./contract";

const SAVE_AFTER_MS = 1000;
const utf8 = new TextEncoder();

export type SaveState = "saved" | "unsaved" | "saving" | "failed" | "too_long";

/** One question's box; `update` takes the server's newest copy of the question. */
export interface AnswerBox {
  el: HTMLElement;
  state: () => SaveState;
  update: (q: Question) => void;
}

const clock = (iso: string): string => new Date(iso).toLocaleTimeString([], { hour12: false });
const bytes = (text: string): number => utf8.encode(text).length;

export function answerBox(question: Question, onSaved: (q: Question) => void): AnswerBox {
  const el = document.createElement("div");
  el.className = "guide-question";
  el.dataset.question = question.id;
  const label = document.createElement("label");
  label.htmlFor = `guide-answer-${question.id}`;
  label.textContent = question.text;
  const box = document.createElement("textarea");
  box.id = label.htmlFor;
  box.rows = 3;
  box.value = question.answer;
  box.spellcheck = true;
  const size = document.createElement("span");
  size.className = "size";
  const status = document.createElement("span");
  status.className = "saved";
  status.setAttribute("role", "status");
  const foot = document.createElement("div");
  foot.className = "foot";
  foot.append(status, size);
  el.append(label, box, foot);

  let saved = question.answer, savedAt = question.saved_at, state: SaveState = "saved";
  let timer: ReturnType<typeof setTimeout> | undefined;
  let saving: Promise<void> | null = null;

  const show = (next: SaveState, detail = ""): void => {
    state = next;
    el.dataset.state = next;
    const n = bytes(box.value);
    size.textContent = `${n.toLocaleString()} / ${ANSWER_LIMIT_BYTES.toLocaleString()} bytes`;
    size.classList.toggle("over", n > ANSWER_LIMIT_BYTES);
    status.textContent = {
      saved: savedAt ? `saved at ${clock(savedAt)}` : "not answered yet",
      unsaved: "editing…",
      saving: "saving…",
      failed: `not saved: ${detail}`,
      too_long: `too long to save: at most ${ANSWER_LIMIT_BYTES.toLocaleString()} bytes`,
    }[next];
  };

  const save = async (): Promise<void> => {
    clearTimeout(timer);
    if (saving) { await saving; if (box.value === saved) return; }
    const text = box.value;
    if (text === saved && state !== "failed") { show("saved"); return; }
    if (bytes(text) > ANSWER_LIMIT_BYTES) { show("too_long"); return; }
    show("saving");
    saving = (async () => {
      try {
        const reply = await fetch(answerUrl(question.id), {
          method: "PUT", headers: { "Content-Type": "application/json" }, body: JSON.stringify({ text } satisfies AnswerBody),
        });
        if (!reply.ok) { show("failed", await errorOf(reply)); return; }
        const q = await reply.json() as Question;
        saved = text; savedAt = q.saved_at;
        if (box.value === text) show("saved"); else schedule();
        onSaved(q);
      } catch (err) {
        show("failed", err instanceof Error ? err.message : String(err));
      } finally {
        saving = null;
      }
    })();
    await saving;
  };
  const schedule = (): void => {
    clearTimeout(timer);
    if (bytes(box.value) > ANSWER_LIMIT_BYTES) { show("too_long"); return; }
    show(box.value === saved ? "saved" : "unsaved");
    timer = setTimeout(() => void save(), SAVE_AFTER_MS);
  };
  box.addEventListener("input", schedule);
  box.addEventListener("blur", () => { if (box.value !== saved || state === "failed") void save(); });
  show("saved");

  const update = (q: Question): void => {
    if (q.answer === saved && q.saved_at === savedAt) return;
    const clean = box.value === saved && state === "saved";
    saved = q.answer; savedAt = q.saved_at;
    if (clean && document.activeElement !== box) { box.value = q.answer; show("saved"); }
  };
  return { el, state: () => state, update };
}
