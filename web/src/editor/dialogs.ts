// Small modal forms (a native <dialog>) for the code view's questions: a new package's choices, a
// new file's path and template, a new name, and "are you sure" before a delete. Each resolves to
// the answers, or null when the student cancels. A form's submit is refused while an answer the
// server would refuse anyway is empty.

export interface Field {
  name: string;
  label: string;
  value?: string;
  placeholder?: string;
  required?: boolean;
  /** A select of these (value, label) instead of a text field. */
  options?: [string, string][];
  hint?: string;
  /** A field whose value changed: the form's other fields may follow (a template's path). */
  onChange?: (value: string, form: HTMLFormElement) => void;
}

/** Ask, in a modal dialog inside ``host``; resolves to the fields' values or null (cancelled). */
export function ask(host: HTMLElement, title: string, fields: Field[], submitLabel: string, message = ""):
Promise<Record<string, string> | null> {
  const dialog = document.createElement("dialog");
  dialog.className = "code-dialog";
  const form = document.createElement("form");
  form.method = "dialog";
  const heading = document.createElement("h3");
  heading.textContent = title;
  form.append(heading);
  if (message) {
    const p = document.createElement("p");
    p.textContent = message;
    form.append(p);
  }
  for (const field of fields) {
    const label = document.createElement("label");
    label.textContent = field.label;
    let input: HTMLInputElement | HTMLSelectElement;
    if (field.options) {
      input = document.createElement("select");
      for (const [value, text] of field.options) input.append(new Option(text, value, false, value === field.value));
    } else {
      input = document.createElement("input");
      input.type = "text";
      input.spellcheck = false;
      input.autocomplete = "off";
      input.value = field.value ?? "";
      input.placeholder = field.placeholder ?? "";
      input.required = field.required ?? false;
    }
    input.name = field.name;
    const onChange = field.onChange;
    if (onChange) input.addEventListener("change", () => onChange(input.value, form));
    label.append(input);
    if (field.hint) {
      const hint = document.createElement("small");
      hint.textContent = field.hint;
      label.append(hint);
    }
    form.append(label);
  }
  const buttons = document.createElement("div");
  buttons.className = "buttons";
  const cancel = document.createElement("button");
  cancel.type = "button";
  cancel.textContent = "Cancel";
  const submit = document.createElement("button");
  submit.type = "submit";
  submit.className = "primary";
  submit.textContent = submitLabel;
  buttons.append(cancel, submit);
  form.append(buttons);
  dialog.append(form);
  host.append(dialog);
  return new Promise((resolve) => {
    let answer: Record<string, string> | null = null;
    cancel.addEventListener("click", () => dialog.close());
    form.addEventListener("submit", () => {
      const data = new FormData(form);
      answer = Object.fromEntries(fields.map((f) => {
        const value = data.get(f.name);
        return [f.name, typeof value === "string" ? value.trim() : ""];
      }));
    });
    dialog.addEventListener("close", () => { dialog.remove(); resolve(answer); });
    dialog.showModal();
  });
}

/** "Are you sure?" with the action named on its button; true when confirmed. */
export async function confirmed(host: HTMLElement, title: string, message: string, action: string): Promise<boolean> {
  return (await ask(host, title, [], action, message)) !== null;
}
