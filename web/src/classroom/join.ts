// The join form of a class server: POST /api/classroom/join sets this browser's HTTP-only token
// cookie, and the page reloads into the student's own world. When the class server is at its
// capacity the join waits in the queue (202 with a ticket): the page shows how many wait ahead
// and asks again (GET /api/classroom/join/{ticket}) until it is admitted or refused.
import type { ErrorBody, JoinRequest, Joined, QueuedJoin } from "../protocol.gen";

const form = document.getElementById("join") as HTMLFormElement;
const status = document.getElementById("status")!;
const field = (id: string): string => (document.getElementById(id) as HTMLInputElement).value.trim();

form.addEventListener("submit", (event) => {
  event.preventDefault();
  void join({ name: field("name"), code: field("code") });
});

async function join(body: JoinRequest): Promise<void> {
  status.textContent = "starting your world…";
  try {
    const reply = await fetch("/api/classroom/join", {
      method: "POST",
      headers: { "Content-Type": "application/json" },
      body: JSON.stringify(body),
    });
    await settle(reply);
  } catch (err) {
    status.textContent = `the class server did not answer: ${String(err)}`;
  }
}

async function settle(reply: Response): Promise<void> {
  const data = await reply.json() as Joined | QueuedJoin | ErrorBody;
  if (reply.status === 202 && "ticket" in data) {
    status.textContent = `waiting, ${data.ahead} ahead (${data.why})…`;
    setTimeout(() => void poll(data.ticket), data.poll_s * 1000);
    return;
  }
  if (!reply.ok || !("world" in data)) {
    const detail = "detail" in data ? data.detail : null;
    status.textContent = typeof detail === "string" ? detail : "the form is not complete";
    return;
  }
  status.textContent = `world ${data.world} is ready`;
  window.location.replace("/");
}

async function poll(ticket: string): Promise<void> {
  try {
    await settle(await fetch(`/api/classroom/join/${encodeURIComponent(ticket)}`));
  } catch (err) {
    status.textContent = `the class server did not answer: ${String(err)}`;
  }
}
