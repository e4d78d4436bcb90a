"""Worlds in other processes: world workers on the class's Zenoh router.

A world worker (``ros2lab world-worker --connect tcp/HOST:7447``) is a class server of its own
that hosts worlds it is asked to host and lets no student join it directly. It answers a *hello*
on the class's router (``ros2lab/classroom/worker/<id>``) with where its HTTP API listens and how
full it is and how busy its CPU is (``load.py``). The class server asks before placing a new
world, puts it where the load is lowest, and then serves the student's page itself while every
call for that world goes to the worker (``api/middleware/world_proxy.py``).

The class server also says hello every ``WATCH_PERIOD_S``: a worker silent for its
``--worker-timeout`` is taken as gone, and its worlds start again elsewhere; a worker that hears
no hello for its ``--orphan-timeout`` (shorter) frees its worlds, as nobody can reach them.

Trust comes from the instructor's token, which both sides know and which never crosses the wire:
the class server seals its hellos with it and a worker seals its replies (so a stranger on the
router can neither pose as a worker nor learn what one hosts), and the class server calls the
worker's API with a token derived from it and the worker's id: as the instructor for its own
calls and the instructor's, and with a credential for the one world a student's call is for
(``world_call_token``), which the worker answers as that world's student and nothing more.
"""

from __future__ import annotations

import hashlib
import hmac
import json
import secrets
from dataclasses import dataclass
from typing import Any

import httpx

from server.classroom.errors import WorkerFailedError, WorkerRefusedError
from server.classroom.load import CpuLoad
from server.classroom.worker_connections import WorkerConnections
from server.services.workspace.class_mark import MAX_MARK_CHARS

CONTROL_PREFIX = "ros2lab/classroom/worker"
MAX_REPLY_BYTES = 16 * 1024
HELLO_TIMEOUT_S = 3.0  # an upper bound: a get ends once every worker has answered
WATCH_PERIOD_S = 2.0  # how often the class server says hello to its workers
WORKER_CALL_TIMEOUT_S = 30.0  # starting a world with the whole lab takes a few seconds
WORLD_CALL_PREFIX = "world:"
MAX_WORLD_CALL_TOKEN_CHARS = 256


def control_key(worker_id: str) -> str:
    return f"{CONTROL_PREFIX}/{worker_id}"


def _mac(secret: str, body: dict[str, Any]) -> str:
    canonical = json.dumps(body, sort_keys=True, separators=(",", ":")).encode()
    return hmac.new(secret.encode(), canonical, hashlib.sha256).hexdigest()


def seal(secret: str, body: dict[str, Any]) -> bytes:
    """``body`` as JSON with a MAC under ``secret``."""
    return json.dumps({**body, "mac": _mac(secret, body)}).encode()


def unseal(secret: str, raw: bytes) -> dict[str, Any] | None:
    """The body of a genuine sealed message; None for anything else (never an exception)."""
    if len(raw) > MAX_REPLY_BYTES:
        return None
    try:
        body = json.loads(raw)
    except ValueError:
        return None
    if not isinstance(body, dict) or not isinstance(mac := body.pop("mac", None), str):
        return None
    return body if hmac.compare_digest(_mac(secret, body), mac) else None


def hello_request(class_token: str, nonce: str) -> bytes:
    """The class server's hello, sealed: only a worker of this class answers it."""
    return seal(class_token, {"op": "hello", "nonce": nonce})


def genuine_hello(class_token: str, raw: bytes) -> str | None:
    """The nonce of a hello sealed with this class's token; None for anything else."""
    body = unseal(class_token, raw)
    if body is None or body.get("op") != "hello":
        return None
    nonce = body.get("nonce")
    return nonce if isinstance(nonce, str) and 0 < len(nonce) <= 64 else None


class Silence:
    """When each peer was last heard, on the caller's clock: who has been silent too long.

    A peer is first heard when it is first asked about, so a new one gets the whole timeout.
    """

    def __init__(self, timeout_s: float) -> None:
        self.timeout_s = timeout_s
        self._heard: dict[str, float] = {}

    def heard(self, peer: str, now: float) -> None:
        self._heard[peer] = now

    def silent(self, peers: set[str], now: float) -> set[str]:
        """Those of ``peers`` not heard for ``timeout_s``; the rest are forgotten."""
        self._heard = {p: self._heard.get(p, now) for p in peers}
        return {p for p, at in self._heard.items() if now - at >= self.timeout_s}


def worker_api_token(class_token: str, worker_id: str) -> str:
    """The token the class server calls a worker's API with as its instructor: derived, never sent
    in a hello, and used for the class server's own calls and the instructor's, never a student's."""
    return hmac.new(class_token.encode(), f"world-worker:{worker_id}".encode(), hashlib.sha256).hexdigest()


def world_call_token(class_token: str, worker_id: str, world: str) -> str:
    """The credential a student's call to their world on a worker is forwarded with: it names that
    one world (``world:<name>:<mac>``), and the worker answers it as that world's student only."""
    mac = hmac.new(class_token.encode(), f"world-worker:{worker_id}:world:{world}".encode(), hashlib.sha256)
    return f"{WORLD_CALL_PREFIX}{world}:{mac.hexdigest()}"


def world_of_call_token(class_token: str, worker_id: str, token: str) -> str | None:
    """The world a genuine ``world_call_token`` for this worker is for; None for anything else."""
    if not token.startswith(WORLD_CALL_PREFIX) or len(token) > MAX_WORLD_CALL_TOKEN_CHARS:
        return None
    world, _, _mac = token[len(WORLD_CALL_PREFIX) :].rpartition(":")
    if not world:
        return None
    expected = world_call_token(class_token, worker_id, world)
    return world if hmac.compare_digest(token.encode(), expected.encode()) else None


@dataclass(frozen=True)
class WorkerRef:
    """A world worker as its last hello described it."""

    id: str
    url: str  # its HTTP API, e.g. http://127.0.0.1:41234
    worlds: int
    max_worlds: int
    token: str  # worker_api_token(...): what the class server calls it with
    hosted: frozenset[str] | None = None  # the worlds it said it hosts (None: it did not say)
    load: CpuLoad | None = None  # its CPU over its last window (None: it did not say)
    late: int | None = None  # its worlds that are late (lateness.py; None: it did not say)
    # The mark in its workspaces folder (server/services/workspace/class_mark.py; None: it has none).
    workspaces_mark: str | None = None
    progress_mark: str | None = None  # and in its progress folder (progress_copies.py)

    def describe(self) -> dict[str, Any]:
        cpu = self.load.describe() if self.load is not None else None
        return {
            "id": self.id,
            "url": self.url,
            "worlds": self.worlds,
            "max_worlds": self.max_worlds,
            "cpu": cpu,
            "late": self.late,
        }


def _worker_ref(body: dict[str, Any], class_token: str) -> WorkerRef | None:
    wid, url, worlds, most = body.get("id"), body.get("url"), body.get("worlds"), body.get("max_worlds")
    if not (isinstance(wid, str) and isinstance(url, str) and url.startswith(("http://", "https://"))):
        return None
    if not (isinstance(worlds, int) and isinstance(most, int)):
        return None
    listed = body.get("hosted")
    hosted = (
        frozenset(listed) if isinstance(listed, list) and all(isinstance(n, str) for n in listed) else None
    )
    load = CpuLoad.parse(body.get("cpu"))
    late = body.get("late")
    late = late if isinstance(late, int) and not isinstance(late, bool) and 0 <= late <= most else None
    mark, progress_mark = (_mark(body.get("workspaces")), _mark(body.get("progress")))
    token = worker_api_token(class_token, wid)
    return WorkerRef(wid, url.rstrip("/"), worlds, most, token, hosted, load, late, mark, progress_mark)


def _mark(value: Any) -> str | None:
    return value if isinstance(value, str) and 0 < len(value) <= MAX_MARK_CHARS else None


class WorkerDirectory:
    """The class server's side: find workers on the router, and call their API."""

    def __init__(self, session: Any, class_token: str, hello_timeout_s: float = HELLO_TIMEOUT_S) -> None:
        self.session: Any = session  # the class's Zenoh router session (None while it opens again)
        self.last_found: set[str] = set()  # the workers the last hello found
        self.class_token = class_token
        self.hello_timeout_s = hello_timeout_s
        self.http = httpx.AsyncClient(timeout=WORKER_CALL_TIMEOUT_S, trust_env=False)
        # The students' calls passed on to the worlds the workers host (api/middleware/world_proxy.py).
        self.connections = WorkerConnections(WORKER_CALL_TIMEOUT_S)

    def use_session(self, session: Any) -> None:
        """The router's session once it opened again (None: while it opens again, nobody is asked)."""
        self.session = session

    def discover(self) -> list[WorkerRef]:
        """Every worker that answers a fresh hello in time (blocking: call it in a thread)."""
        if self.session is None:  # the router is opening again (class_router.py): nobody to ask
            return []
        nonce = secrets.token_hex(16)
        found: dict[str, WorkerRef] = {}
        replies = self.session.get(
            f"{CONTROL_PREFIX}/*",
            payload=hello_request(self.class_token, nonce),
            timeout=self.hello_timeout_s,
        )
        for reply in replies:
            if reply.ok is None:
                continue
            body = unseal(self.class_token, reply.ok.payload.to_bytes())
            if body is None or body.get("nonce") != nonce:
                continue  # not sealed with this class's token, or an old reply: not our worker
            ref = _worker_ref(body, self.class_token)
            if ref is not None:
                found[ref.id] = ref
        self.last_found = set(found)
        return sorted(found.values(), key=lambda r: r.id)

    async def call(
        self,
        ref: WorkerRef,
        method: str,
        path: str,
        *,
        world: str | None = None,
        body: Any = None,
        content: bytes | None = None,
    ) -> httpx.Response:
        """One call to a worker's API as its instructor, with a JSON ``body`` or raw ``content``;
        WorkerFailedError if it cannot answer."""
        headers = {"Authorization": f"Bearer {ref.token}"}
        if world is not None:
            headers["X-Lab-World"] = world
        if content is not None:
            headers["Content-Type"] = "application/octet-stream"
        try:
            return await self.http.request(
                method, ref.url + path, headers=headers, json=body, content=content
            )
        except httpx.HTTPError as exc:
            raise WorkerFailedError(
                f"world worker {ref.id!r} did not answer: {str(exc) or type(exc).__name__}"
            ) from None

    async def checked(
        self, ref: WorkerRef, method: str, path: str, *, world: str | None = None, body: Any = None
    ) -> Any:
        """``call``, and its JSON; a refusal keeps the worker's status and reason."""
        reply = await self.call(ref, method, path, world=world, body=body)
        if reply.status_code >= 400:
            try:
                detail = reply.json().get("detail")
            except ValueError:
                detail = reply.text[:200]
            raise WorkerRefusedError(f"world worker {ref.id!r}: {detail}", reply.status_code)
        return reply.json()

    async def close(self) -> None:
        self.connections.close()
        await self.http.aclose()
