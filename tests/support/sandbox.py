"""For the tests of students' sandboxed nodes: whether this machine can build the sandbox."""

from __future__ import annotations

import os

import pytest

from server.host.processes.sandbox import probe


def require_sandbox() -> None:
    """Skips the test where this machine cannot build the sandbox (no bwrap, namespaces refused);
    fails it in CI, where scripts/test.sh installs bubblewrap and these tests must run."""
    why = probe()
    if why is None:
        return
    message = f"no sandbox on this machine: {why} (scripts/test.sh installs bubblewrap)"
    if os.environ.get("CI") == "true":
        pytest.fail(f"{message}; in CI the sandbox tests must run")
    pytest.skip(message)
