// A picture of the 3D view as checkpoint 2's evidence ("the drone at the position"): when this
// page sees fly_to_point turn done (or done again), it draws one frame from the drone's follow
// camera and POSTs it as a PNG to /api/checkpoints/fly_to_point/capture, then puts the student's
// own view back. viser's WebGL canvas keeps no drawing buffer (preserveDrawingBuffer is off), so
// the frame is copied right after the scene is drawn into it, in the same task (scene.afterFrame),
// onto a 2D canvas no wider than MAX_WIDTH_PX; that copy is encoded afterwards.
import { scene } from "../lab/scene";
import type { Checkpoints } from "../protocol.gen";
import { CAPTURED_CHECKPOINT, CAPTURE_LIMIT_BYTES, captureUrl, errorOf } from "./contract";
import { progress } from "./progress";

const MAX_WIDTH_PX = 1280;
const FRAME_WAIT_MS = 5000;

export const capture = {
  sent: 0,
  last: null as { checkpoint: string; bytes: number; status: number } | null,
  error: null as string | null,
  /** One frame of the drone's view as a PNG (the student's view is put back after). */
  take: (): Promise<Blob> => take(),
  send: (checkpoint: string): Promise<void> => send(checkpoint),
};

function copyFrame(canvas: HTMLCanvasElement): HTMLCanvasElement {
  const k = Math.min(1, MAX_WIDTH_PX / canvas.width);
  const copy = document.createElement("canvas");
  copy.width = Math.round(canvas.width * k);
  copy.height = Math.round(canvas.height * k);
  copy.getContext("2d")!.drawImage(canvas, 0, 0, copy.width, copy.height);
  return copy;
}

const png = (canvas: HTMLCanvasElement): Promise<Blob> => new Promise((resolve, reject) => {
  canvas.toBlob((blob) => (blob ? resolve(blob) : reject(new Error("the view could not be encoded"))), "image/png");
});

function take(): Promise<Blob> {
  const viser = scene.viser, canvas = viser?.canvas;
  if (!viser || !canvas || !scene.ready) return Promise.reject(new Error("the 3D view is not ready"));
  const before = scene.view ? { name: scene.view.name, follow: scene.follow } : null;
  const drone = scene.views.find((v) => v.follow);
  return new Promise<HTMLCanvasElement>((resolve, reject) => {
    let taken = false;
    const done = (): void => {
      clearTimeout(timer);
      const i = scene.afterFrame.indexOf(grab);
      if (i >= 0) scene.afterFrame.splice(i, 1);
      if (before && drone && (before.name !== drone.name || !before.follow)) scene.setView(before.name, before.follow);
    };
    const grab = (): void => {
      if (taken) return;
      taken = true;
      try { resolve(copyFrame(canvas)); } catch (err) { reject(err instanceof Error ? err : new Error(String(err))); }
      queueMicrotask(done);  // not while the scene is still calling its listeners
    };
    const timer = setTimeout(() => { taken = true; done(); reject(new Error("no frame was drawn")); }, FRAME_WAIT_MS);
    if (drone) scene.setView(drone.name, true);
    scene.afterFrame.push(grab);
    viser.requestRender();
  }).then(png);
}

async function send(checkpoint: string): Promise<void> {
  try {
    const blob = await take();
    if (blob.size > CAPTURE_LIMIT_BYTES) throw new Error(`the picture is ${blob.size} bytes, over the limit`);
    const reply = await fetch(captureUrl(checkpoint), { method: "POST", headers: { "Content-Type": "image/png" }, body: blob });
    capture.last = { checkpoint, bytes: blob.size, status: reply.status };
    if (!reply.ok) throw new Error(await errorOf(reply));
    capture.sent++;
    capture.error = null;
  } catch (err) {
    capture.error = err instanceof Error ? err.message : String(err);
    console.warn("teleop: the view's picture was not sent:", capture.error);
  }
}

const doneAt = (data: Checkpoints | null): string | null =>
  data?.checkpoints.find((c) => c.name === CAPTURED_CHECKPOINT && c.state === "done")?.done_at ?? null;

/** Send a picture each time this page sees checkpoint 2 turn done (a page opened later sends none). */
export function startCapture(): void {
  progress.listeners.push((data, before) => {
    const now = doneAt(data);
    if (before && now && now !== doneAt(before)) void send(CAPTURED_CHECKPOINT);
  });
}
