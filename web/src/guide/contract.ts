// The checkpoints routes as the page uses them (docs/checkpoints.md): the world's checks and
// questions (GET /api/checkpoints, polled with ?since=<version>), an answer saved
// (PUT /api/checkpoints/answers/{id}), the 3D view's capture (POST .../{name}/capture), the
// report to hand in, and the instructor's class table. The token is the page's cookie: every
// request here is same-origin.

export type CheckState = "not_started" | "in_progress" | "done";

/** One thing to do: what (`text`), how in the page (`page`: its buttons, panels, starting files),
 * and the same in a terminal (`commands`, the alternative). `already`: what runs already, when
 * the step's nodes run (the lab's launch started them); the Guide shows it instead of asking. */
export interface Step { text: string; page: string; commands: string[]; already: string | null }

export interface Checkpoint {
  name: string;
  title: string;
  state: CheckState;
  done_at: string | null;  // ISO 8601, UTC
  steps: Step[];
  progress: string;  // one short live line
  evidence: Record<string, unknown> | null;
  times_done?: number;
  has_capture?: boolean;  // the server keeps a picture the page sent
}

export interface Question {
  id: string;
  checkpoint: string;
  text: string;
  answer: string;
  saved_at: string | null;
  shows_graph?: boolean;  // the page shows the student's graph beside the box
}

export interface Checkpoints { checkpoints: Checkpoint[]; questions: Question[]; version: number }

export interface Verdict { valid: boolean; reason: string; student: string | null }

/** "unreachable": the world's world worker did not answer the class server in time. */
export interface ClassCell { state: CheckState | "unreachable"; done_at: string | null }
export interface ClassStudent {
  name: string;
  world?: string;
  cells: Record<string, ClassCell | undefined>;
  answers: Record<string, string | undefined>;
  unreachable?: string; // why its world worker did not answer
  joined?: boolean; // false: not joined since the class server started (listed from its saved progress)
}
export interface ClassCheckpoints { checkpoints: string[]; students: ClassStudent[] }

/** The server refuses a longer answer (413), counted in UTF-8 bytes. */
export const ANSWER_LIMIT_BYTES = 8 * 1024;
/** The largest capture the server takes (bytes of PNG). */
export const CAPTURE_LIMIT_BYTES = 2 * 1024 * 1024;
/** Checkpoint 2, whose done state asks the page for a picture of its 3D view. */
export const CAPTURED_CHECKPOINT = "fly_to_point";

export const CHECKPOINTS_URL = "/api/checkpoints";
export const answerUrl = (question: string): string => `${CHECKPOINTS_URL}/answers/${encodeURIComponent(question)}`;
export const captureUrl = (checkpoint: string): string => `${CHECKPOINTS_URL}/${encodeURIComponent(checkpoint)}/capture`;
export const reportUrl = (format: "html" | "json"): string => `${CHECKPOINTS_URL}/report?format=${format}`;

/** A reply's error, as the server words it (its `detail`), or its status. */
export async function errorOf(reply: Response): Promise<string> {
  const body = await reply.json().catch(() => null) as { detail?: unknown } | null;
  const detail = body?.detail;
  if (typeof detail === "string") return detail;
  if (Array.isArray(detail) && detail.length) return JSON.stringify(detail[0]);
  return `HTTP ${reply.status}`;
}
