"""Signed tokens: who is calling (a student and their world, or the instructor).

A token is ``<payload>.<signature>``: the payload is URL-safe base64 of a small JSON object, the
signature an HMAC-SHA256 of it with the class server's secret (new at every start, so tokens
from an earlier run stop working). Nothing in a token is secret; it cannot be forged or changed.
"""

from __future__ import annotations

import base64
import binascii
import hashlib
import hmac
import json
import secrets
from dataclasses import dataclass
from typing import Literal

Role = Literal["student", "instructor"]
MAX_TOKEN_CHARS = 512


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

    def issue(self, role: Role, world: str | None, name: str) -> tuple[str, Grant]:
        grant = Grant(role, world, name, secrets.token_hex(8))
        body = {"r": role, "w": world, "n": name, "i": grant.token_id}
        payload = _b64(json.dumps(body, separators=(",", ":")).encode())
        return f"{payload}.{self._sign(payload)}", grant

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
