// The checkpoints routes as the page uses them (docs/checkpoints.md): the world's checks and
// questions (GET /api/checkpoints, polled with ?since=<version>), an answer saved
// (PUT /api/checkpoints/answers/{id}), the 3D view's capture (POST .../{name}/capture), the
// report to hand in, and the instructor's class table. The token is the page's cookie: every
// request here is same-origin. The shapes are the protocol's (protocol.gen.ts).
import type { ErrorBody } from "../protocol.gen";

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
  const body = await reply.json().catch(() => null) as Partial<ErrorBody> | null;
  const detail = body?.detail;
  if (typeof detail === "string") return detail;
  if (Array.isArray(detail) && detail.length) return JSON.stringify(detail[0]);
  return `HTTP ${reply.status}`;
}
