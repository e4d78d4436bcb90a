"""Whose a world's progress is: the student who last joined under the world's name, kept beside
the progress as ``student.json``: their name as they typed it and the SHA-256 of the token the
class server gave them.

A world is named after what its student types, and two people can type the same name; a class
server's tokens do not outlive it (server/classroom/tokens.py draws a new secret at each start,
unless the class server is given a class secret). So
after a restart the token a student's browser still holds (the join page's cookie) is what tells
them apart: a join under a name whose progress is on disk takes that progress only when it
presents the token whose hash is recorded here. A hash, not the token: the file grants nothing.
"""

from __future__ import annotations

import hashlib
import hmac
import json
from dataclasses import dataclass
from pathlib import Path

OWNER_FILE = "student.json"
FORMAT = 1
MAX_OWNER_BYTES = 4096


class OwnerFileError(ValueError):
    """An owner record that cannot be read or is not one."""


def token_sha256(token: str) -> str:
    return hashlib.sha256(token.encode()).hexdigest()


@dataclass(frozen=True)
class Owner:
    student: str  # the name as typed at the join
    token_sha256: str

    @classmethod
    def of(cls, student: str, token: str) -> Owner:
        return cls(student, token_sha256(token))

    def proven_by(self, token: str | None) -> bool:
        """Whether ``token`` is the one this student was given."""
        return token is not None and hmac.compare_digest(token_sha256(token), self.token_sha256)

    def encode(self) -> bytes:
        return json.dumps(
            {"format": FORMAT, "student": self.student, "token_sha256": self.token_sha256}
        ).encode()


def read_owner(folder: Path) -> Owner | None:
    """The owner recorded in world folder ``folder``; None when none is; OwnerFileError for a
    record that cannot be read or is not one."""
    path = folder / OWNER_FILE
    try:
        if path.stat().st_size > MAX_OWNER_BYTES:
            raise OwnerFileError(f"{path.name} is larger than {MAX_OWNER_BYTES} bytes")
        raw = path.read_bytes()
    except FileNotFoundError:
        return None
    except OSError as exc:
        raise OwnerFileError(f"{path.name} cannot be read ({exc.strerror or exc})") from None
    try:
        body = json.loads(raw)
    except ValueError:
        raise OwnerFileError(f"{path.name} is not JSON") from None
    student = body.get("student") if isinstance(body, dict) else None
    digest = body.get("token_sha256") if isinstance(body, dict) else None
    if (
        not isinstance(body, dict)
        or body.get("format") != FORMAT
        or not isinstance(student, str)
        or not isinstance(digest, str)
        or len(digest) != 64
    ):
        raise OwnerFileError(f"{path.name} is not an owner record of format {FORMAT}")
    return Owner(student, digest)
