"""Reports signed by the server (HMAC-SHA256), so an instructor can tell one was not edited.

The key is 32 random bytes in the server's state folder, made on first use and kept, so a restart
still verifies the reports it signed. A report names its key by an id (a hash of the key, which
tells nothing of it), so a report of another server is named as such rather than as edited.

- The JSON file is the report in canonical form (sorted keys, no spaces) with ``signature``: the
  MAC of the canonical report without it. Any changed byte, layout included, fails.
- The HTML page carries ``<meta name="report-signature" content="KEY_ID:MAC">``: the MAC of the
  page's bytes with that content left empty.
"""

from __future__ import annotations

import hashlib
import hmac
import json
import os
import re
import secrets
from dataclasses import dataclass
from pathlib import Path
from typing import Any

KIND = "teleop-lab checkpoint report"
KEY_FILE = "report-key"
ALGORITHM = "HMAC-SHA256"
META = re.compile(rb'<meta name="report-signature" content="([0-9a-f]*):([0-9a-f]*)">')
META_EMPTY = b'<meta name="report-signature" content="">'
EMBEDDED = re.compile(rb'<script type="application/json" id="report">(.*?)</script>', re.S)


def canonical(value: Any) -> bytes:
    return json.dumps(value, sort_keys=True, separators=(",", ":"), ensure_ascii=False).encode()


@dataclass(frozen=True)
class Verdict:
    valid: bool
    reason: str
    student: str | None = None


class ReportSigner:
    def __init__(self, key: bytes) -> None:
        self._key = key
        self.key_id = hashlib.sha256(b"teleop-lab report key id\0" + key).hexdigest()[:16]

    @classmethod
    def in_folder(cls, folder: Path) -> ReportSigner:
        """The server's key in ``folder`` (made, readable by this user alone, if there is none)."""
        path = folder / KEY_FILE
        if not path.exists():
            folder.mkdir(parents=True, exist_ok=True, mode=0o700)
            fd = os.open(path, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600)
            with os.fdopen(fd, "w") as out:
                out.write(secrets.token_hex(32))
        return cls(bytes.fromhex(path.read_text().strip()))

    def _mac(self, data: bytes) -> str:
        return hmac.new(self._key, data, hashlib.sha256).hexdigest()

    # -- signing -------------------------------------------------------------------------------
    def sign(self, report: dict[str, Any]) -> dict[str, Any]:
        unsigned = {k: v for k, v in report.items() if k != "signature"}
        return {
            **unsigned,
            "signature": {
                "algorithm": ALGORITHM,
                "key_id": self.key_id,
                "mac": self._mac(canonical(unsigned)),
            },
        }

    def json_file(self, report: dict[str, Any]) -> bytes:
        return canonical(self.sign(report))

    def sign_html(self, page: bytes) -> bytes:
        """``page`` must hold META_EMPTY once: it gets this server's signature of the page."""
        if page.count(META_EMPTY) != 1:
            raise ValueError("a report page holds exactly one empty report-signature meta tag")
        mark = f'<meta name="report-signature" content="{self.key_id}:{self._mac(page)}">'.encode()
        return page.replace(META_EMPTY, mark)

    # -- verifying -----------------------------------------------------------------------------
    def verify(self, data: bytes) -> Verdict:
        stripped = data.strip()
        if stripped.startswith(b"{"):
            return self._verify_json(stripped)
        if META.search(data) is not None or EMBEDDED.search(data) is not None:
            return self._verify_html(data)
        return Verdict(False, "not a report: neither a report's JSON nor its page")

    def _verify_json(self, data: bytes) -> Verdict:
        try:
            report = json.loads(data)
        except (UnicodeDecodeError, json.JSONDecodeError):
            return Verdict(False, "not a report: the file is not JSON")
        if not isinstance(report, dict) or report.get("kind") != KIND:
            return Verdict(False, f"not a report: the JSON is not a {KIND}")
        student = report.get("student") if isinstance(report.get("student"), str) else None
        signature = report.get("signature")
        if not isinstance(signature, dict) or not isinstance(signature.get("mac"), str):
            return Verdict(False, "not a report: it carries no signature", student)
        if signature.get("key_id") != self.key_id:
            return Verdict(False, "signed by another server (its key is not this server's)", student)
        expected = self.sign(report)
        if (
            not hmac.compare_digest(signature["mac"], expected["signature"]["mac"])
            or canonical(expected) != data
        ):
            return Verdict(False, "edited: the report differs from what this server signed", student)
        return Verdict(True, "valid: signed by this server and unchanged", student)

    def _verify_html(self, page: bytes) -> Verdict:
        student = _embedded_student(page)
        marks = META.findall(page)
        if len(marks) != 1:
            return Verdict(False, "not a report: the page carries no single signature", student)
        key_id, mac = marks[0]
        if key_id.decode() != self.key_id:
            return Verdict(False, "signed by another server (its key is not this server's)", student)
        blank = META.sub(META_EMPTY, page, count=1)
        if not hmac.compare_digest(mac.decode(), self._mac(blank)):
            return Verdict(False, "edited: the page differs from what this server signed", student)
        return Verdict(True, "valid: signed by this server and unchanged", student)


def _embedded_student(page: bytes) -> str | None:
    found = EMBEDDED.search(page)
    if found is None:
        return None
    try:
        report = json.loads(found.group(1))
    except (UnicodeDecodeError, json.JSONDecodeError):
        return None
    student = report.get("student") if isinstance(report, dict) else None
    return student if isinstance(student, str) else None
