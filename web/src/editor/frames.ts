// The frames of a run's output socket (WS /ws/launches/{id}/output), as the server sends them:
// its lines (the buffered ones first), the count a fast printer lost to the bounded buffer, a
// node waiting for its turn to start (a server that starts a few node processes at a time), each
// node's exit (no code and no signal: stopped before it started) and the group's end.

export interface LineFrame { type: "line"; seq: number; node: string; stream: "stdout" | "stderr"; text: string }
export interface DroppedFrame { type: "dropped"; count: number }
export interface WaitingFrame { type: "waiting"; node: string }
export interface ExitFrame { type: "exit"; node: string; code: number | null; signal: string | null }
export interface EndFrame { type: "end" }
export type OutputFrame = LineFrame | DroppedFrame | WaitingFrame | ExitFrame | EndFrame;

const FRAME_TYPES = new Set(["line", "dropped", "waiting", "exit", "end"]);

/** A frame from the socket's text, or null when it is not one of these. */
export function parseFrame(data: unknown): OutputFrame | null {
  if (typeof data !== "string") return null;
  try {
    const frame = JSON.parse(data) as { type?: unknown };
    return frame && typeof frame.type === "string" && FRAME_TYPES.has(frame.type) ? (frame as OutputFrame) : null;
  } catch {
    return null;
  }
}
