"""Signed tokens: who is calling (a student and their world, or the instructor).

A token is ``<payload>.<signature>``: the payload is URL-safe base64 of a small JSON object, the
signature an HMAC-SHA256 of it with the class server's secret. Nothing in a token is secret; it
cannot be forged or changed.

The secret is new at every start, so tokens from an earlier run stop working, unless the class
server is given a class secret (``--class-secret-file``, read by :func:`read_class_secret`): then
its tokens outlive a restart, and the instructor's token is derived from the secret alone
(:func:`instructor_token`), so its world workers derive the same one from the same file.
"""

from __future__ import annotations

import base64
import binascii
import hashlib
import hmac
import json
import secrets
import stat
from dataclasses import dataclass
from pathlib import Path
from typing import Literal

Role = Literal["student", "instructor"]
MAX_TOKEN_CHARS = 512
MIN_SECRET_BYTES = 32  # a class secret's, after surrounding whitespace
MAX_SECRET_FILE_BYTES = 4096
MAKE_SECRET = (
    'openssl rand -hex 32 > FILE, or python -c "import secrets; print(secrets.token_hex(32))" > FILE'
)
# What the instructor's token id is an HMAC of, under the secret: the same token at every start.
_INSTRUCTOR_LABEL = b"teleop-lab: the instructor's token id"


class ClassSecretError(ValueError):
    """A class secret file that cannot be used: one line saying why."""


def read_class_secret(path: Path) -> bytes:
    """The class secret in file ``path``: its content without surrounding whitespace, at least
    ``MIN_SECRET_BYTES`` of it. ClassSecretError for a file that is missing, unreadable, not a
    regular file, too large or too short."""
    try:
        info = path.stat()
    except FileNotFoundError:
        raise ClassSecretError(
            f"the class secret file {path} does not exist: make one with {MAKE_SECRET}"
        ) from None
    except OSError as exc:
        raise ClassSecretError(f"the class secret file {path} cannot be read: {exc.strerror}") from None
    if not stat.S_ISREG(info.st_mode):
        raise ClassSecretError(f"the class secret file {path} is not a regular file")
    if info.st_size > MAX_SECRET_FILE_BYTES:
        raise ClassSecretError(
            f"the class secret file {path} is larger than {MAX_SECRET_FILE_BYTES} bytes: is it the right file?"
        )
    try:
        secret = path.read_bytes().strip()
    except OSError as exc:
        raise ClassSecretError(f"the class secret file {path} cannot be read: {exc.strerror}") from None
    if len(secret) < MIN_SECRET_BYTES:
        raise ClassSecretError(
            f"the class secret file {path} holds {len(secret)} bytes of secret, fewer than {MIN_SECRET_BYTES}: "
            f"make one with {MAKE_SECRET}"
        )
    return secret


@dataclass(frozen=True)
class Grant:
    """What a token lets its bearer do: a student acts in ``world`` only; the instructor in all."""

    role: Role
    world: str | None  # None for the instructor
    name: str
    token_id: str

    @property
    def is_instructor(self) -> bool:
        return self.role == "instructor"


def _b64(data: bytes) -> str:
    return base64.urlsafe_b64encode(data).rstrip(b"=").decode("ascii")


def _unb64(text: str) -> bytes:
    return base64.urlsafe_b64decode(text + "=" * (-len(text) % 4))


class TokenSigner:
    def __init__(self, secret: bytes | None = None) -> None:
        self._secret = secret or secrets.token_bytes(32)

    def _sign(self, payload: str) -> str:
        return _b64(hmac.new(self._secret, payload.encode("ascii"), hashlib.sha256).digest())

    def issue(
        self, role: Role, world: str | None, name: str, token_id: str | None = None
    ) -> tuple[str, Grant]:
        grant = Grant(role, world, name, token_id or secrets.token_hex(8))
        body = {"r": role, "w": world, "n": name, "i": grant.token_id}
        payload = _b64(json.dumps(body, separators=(",", ":")).encode())
        return f"{payload}.{self._sign(payload)}", grant

    def issue_instructor(self) -> tuple[str, Grant]:
        """The instructor's token: its id an HMAC of the secret, so the same secret gives the same
        token (a random secret, a token of its own)."""
        token_id = hmac.new(self._secret, _INSTRUCTOR_LABEL, hashlib.sha256).hexdigest()[:16]
        return self.issue("instructor", None, "instructor", token_id)

    def verify(self, token: str) -> Grant | None:
        """The grant a genuine token carries; None for anything else (never an exception)."""
        if len(token) > MAX_TOKEN_CHARS or not token.isascii() or token.count(".") != 1:
            return None
        payload, signature = token.split(".")
        if not hmac.compare_digest(self._sign(payload), signature):
            return None
        try:
            body = json.loads(_unb64(payload))
        except (binascii.Error, ValueError):
            return None
        role, world, name, token_id = body.get("r"), body.get("w"), body.get("n"), body.get("i")
        if (
            role not in ("student", "instructor")
            or not isinstance(name, str)
            or not isinstance(token_id, str)
        ):
            return None
        if (role == "student") != isinstance(world, str):
            return None
        return Grant(role, world, name, token_id)


def instructor_token(secret: bytes) -> str:
    """The instructor's token of the class whose secret is ``secret``: what its class server issues
    (grants.py) and what a world worker given the same secret file derives for itself."""
    return TokenSigner(secret).issue_instructor()[0]
