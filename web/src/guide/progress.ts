// The world's checkpoints, kept current: GET /api/checkpoints once a second while the page is
// shown, with ?since=<version> so that an unchanged world costs a 204 and nothing else. Each
// change goes to the listeners with what was known before (null the first time), so that the
// guide redraws and the capture sees a checkpoint turn done.
import { notify, type Listeners } from "../lab/listeners";
import type { Checkpoints } from "../protocol.gen";
import { CHECKPOINTS_URL, errorOf } from "./contract";

const POLL_MS = 1000;
const RETRY_MS = 5000;  // after an error: the server restarting, or a lab without checkpoints
const NO_CHANGE = 204;
// Now and then ask in full: a server started again counts its versions from the start, and
// would answer the old, higher ?since= with "no change" until it caught up.
const FULL_EVERY = 30;

export const progress = {
  data: null as Checkpoints | null,
  polls: 0,
  error: null as string | null,
  listeners: [] as Listeners<[Checkpoints, Checkpoints | null]>,
  /** Ask now (after a save), without waiting for the next poll. */
  refresh: (): Promise<void> => poll(),
};

let timer: ReturnType<typeof setTimeout> | undefined;
let asking: Promise<void> | null = null;

async function ask(): Promise<void> {
  const full = !progress.data || progress.polls % FULL_EVERY === 0;
  const since = full ? "" : `?since=${progress.data!.version}`;
  const reply = await fetch(CHECKPOINTS_URL + since, { cache: "no-store" });
  progress.polls++;
  if (reply.status === NO_CHANGE) return;
  if (!reply.ok) throw new Error(await errorOf(reply));
  const data = await reply.json() as Checkpoints;
  const before = progress.data;
  if (before && data.version === before.version) return;
  progress.data = data;
  notify(progress.listeners, data, before);
}

function poll(): Promise<void> {
  if (asking) return asking;
  clearTimeout(timer);
  asking = (async () => {
    let wait = POLL_MS;
    try {
      if (!document.hidden) await ask();
      progress.error = null;
    } catch (err) {
      progress.error = err instanceof Error ? err.message : String(err);
      wait = RETRY_MS;
    } finally {
      asking = null;
      timer = setTimeout(() => void poll(), wait);
    }
  })();
  return asking;
}

/** Start polling; a page shown again asks at once. */
export function startProgress(): void {
  document.addEventListener("visibilitychange", () => { if (!document.hidden) void poll(); });
  void poll();
}
