"""schemathesis with ``--checks all`` against a class server's own routes, with the instructor's
token, on a live server (schemathesis_run.py: the server and the run's bounds)."""

from __future__ import annotations

import re

import pytest
from schemathesis_run import live_server, schemathesis
from support.app import instructor_token

CLASS_CODE = "K7PX2M"  # the join example's code, so schemathesis' first join gets a world


def test_a_class_servers_own_routes_pass_checks_all_with_the_instructors_token(
    tmp_path_factory: pytest.TempPathFactory,
) -> None:
    """Joins (the first with the right code), the instructor's table, resets, kicks and
    broadcasts, fuzzed; ``ignored_auth`` also calls each secured route without the token."""
    workdir = tmp_path_factory.mktemp("schemathesis_class_server")
    with live_server(
        workdir,
        "--classroom",
        "--class-code",
        CLASS_CODE,
        "--max-worlds",
        "3",
        "--launch",
        "rocket",
        "start_delay:=3600",
    ) as (url, log_path):
        token = instructor_token(log_path.read_text())
        done = schemathesis(
            url,
            "schemathesis_classroom.toml",
            "--include-path-regex",
            "^/api/classroom/",
            "--header",
            f"Authorization: Bearer {token}",
        )
        assert done.returncode == 0, done.stdout[-6000:] + done.stderr[-2000:]
        # The run covered every route of the class server's own (the document lists 21: the
        # checkpoints' four, the workspaces' three, and the load and join queue's three among them).
        assert re.search(r"Selected:\s+21/\d+", done.stdout) and re.search(r"Tested:\s+21\b", done.stdout), (
            done.stdout
        )
