// A report handed in, checked on the instructor's page: the file chosen goes as it is to
// POST /api/checkpoints/verify, and the verdict is shown (valid, edited, signed by another
// server, not a report) with the student it names.
import type { VerifyResult } from "../protocol.gen";
import { CHECKPOINTS_URL, errorOf } from "../guide/contract";

async function check(file: File, out: HTMLElement): Promise<void> {
  out.textContent = `checking ${file.name}…`;
  out.className = "";
  const reply = await fetch(`${CHECKPOINTS_URL}/verify`, {
    method: "POST", headers: { "Content-Type": "application/octet-stream" }, body: await file.arrayBuffer(),
  });
  if (!reply.ok) { out.textContent = `${file.name}: ${await errorOf(reply)}`; out.className = "bad"; return; }
  const v = await reply.json() as VerifyResult;
  out.textContent = `${file.name}: ${v.reason}${v.student ? ` (student: ${v.student})` : ""}`;
  out.className = v.valid ? "good" : "bad";
}

/** Check each report file chosen in ``input``, saying the verdict in ``out``. */
export function startVerify(input: HTMLInputElement, out: HTMLElement): void {
  input.addEventListener("change", () => {
    const file = input.files?.[0];
    if (file) check(file, out).catch((err: unknown) => { out.textContent = String(err); out.className = "bad"; });
  });
}
