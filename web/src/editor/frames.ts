// The frames of a run's output socket (WS /ws/launches/{id}/output), as the server sends them:
// its lines (the buffered ones first), the count a fast printer lost to the bounded buffer, a
// node waiting for its turn to start (a server that starts a few node processes at a time), a
// node process started (its pid) and its node arrived in the graph (joined), each node's exit (no code and no signal: stopped before it started) and the group's end. Their
// shapes are the protocol's (server/services/launch/output.py declares them).
import type { OutputFrame } from "../protocol.gen";

// Every frame type, checked against the protocol's: a type added there fails the type check here.
const TYPES: Record<OutputFrame["type"], true> = {
  line: true, dropped: true, waiting: true, started: true, joined: true, exit: true, end: true,
};
const FRAME_TYPES = new Set(Object.keys(TYPES));

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
