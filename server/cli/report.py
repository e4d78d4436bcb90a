"""``ros2lab report verify FILE``: whether a checkpoint report (its JSON or its HTML page) is one the
lab's server signed and nobody changed since; the server checks it (``POST /api/checkpoints/verify``),
as only it holds its key. Exit code 0 when valid, 1 when edited, signed by another server or not a
report."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

from server.cli.client import LabClient

MAX_FILE_BYTES = 8 * 1024 * 1024  # the server's limit for a report to verify


def verify(args: argparse.Namespace, client: LabClient) -> int:
    path = Path(args.file)
    try:
        size = path.stat().st_size
        if size > MAX_FILE_BYTES:
            print(
                f"{path}: not a report: {size} bytes, more than a report's {MAX_FILE_BYTES}", file=sys.stderr
            )
            return 1
        data = path.read_bytes()
    except OSError as exc:
        print(f"{path}: {exc.strerror or exc}", file=sys.stderr)
        return 1
    verdict = client.post_file("/api/checkpoints/verify", data)
    student = f" (student: {verdict['student']})" if verdict.get("student") else ""
    print(f"{path}: {verdict['reason']}{student}")
    return 0 if verdict["valid"] else 1


def add_parser(verbs: Any, common: argparse.ArgumentParser) -> None:
    report = verbs.add_parser("report", help="Checkpoint reports (verify one)")
    actions = report.add_subparsers(dest="report_verb", required=True, metavar="ACTION")
    p = actions.add_parser(
        "verify", parents=[common], help="Whether a report file was signed by this lab's server, unchanged"
    )
    p.add_argument("file", help="the report: its .json or its .html")
    p.set_defaults(handler=verify)
