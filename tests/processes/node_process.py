"""A node file run as ``python FILE`` against a live lab's router, its console lines collected as
they come so a test can wait for one and read what the process printed, as ROS 2 prints it."""

from __future__ import annotations

import os
import re
import signal
import subprocess
import sys
import threading
from pathlib import Path

import pytest
from support.app import WAIT_S, App


class NodeProcess:
    def __init__(self, app: App, file: Path, *args: str, command: list[str] | None = None) -> None:
        """``python FILE ARGS``, or ``command`` (``ros2lab run ...``) in ``file``'s folder."""
        env = {**os.environ, "ZENOH_CONFIG_OVERRIDE": f'connect/endpoints=["tcp/{app.router}"]'}
        self.name = file.name
        self.proc = subprocess.Popen(
            command or [sys.executable, "-u", str(file), *args],
            env=env,
            text=True,
            cwd=file.parent if command else None,
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
        )
        self.lines: list[str] = []
        self._changed = threading.Condition()
        self._reader = threading.Thread(target=self._pump, daemon=True)
        self._reader.start()

    def _pump(self) -> None:
        assert self.proc.stdout is not None
        for line in self.proc.stdout:
            with self._changed:
                self.lines.append(line.rstrip("\n"))
                self._changed.notify_all()
        with self._changed:
            self._changed.notify_all()

    @property
    def text(self) -> str:
        with self._changed:
            return "\n".join(self.lines)

    def wait_for(self, pattern: str, count: int = 1, timeout_s: float = WAIT_S) -> list[re.Match[str]]:
        """The first ``count`` matches of ``pattern`` (multi-line) in what the process printed."""
        regex = re.compile(pattern, re.MULTILINE)
        with self._changed:
            found = self._changed.wait_for(
                lambda: len(regex.findall("\n".join(self.lines))) >= count or self.proc.poll() is not None,
                timeout_s,
            )
            matches = list(regex.finditer("\n".join(self.lines)))
        if not found or len(matches) < count:
            pytest.fail(
                f"{self.name} printed {len(matches)} of {count} lines like {pattern!r}:\n{self.text[-3000:]}"
            )
        return matches[:count]

    def finish(self, timeout_s: float = WAIT_S) -> int:
        """Its exit code once it ends by itself."""
        try:
            code = self.proc.wait(timeout_s)
        except subprocess.TimeoutExpired:
            self.kill()
            pytest.fail(f"{self.name} did not end within {timeout_s} s:\n{self.text[-3000:]}")
        self._close()
        return code

    def _close(self) -> None:
        self._reader.join(5.0)
        if self.proc.stdout is not None:
            self.proc.stdout.close()

    def interrupt(self, timeout_s: float = WAIT_S) -> int:
        """Ctrl-C, as a student stops a node; its exit code."""
        if self.proc.poll() is None:
            self.proc.send_signal(signal.SIGINT)
        return self.finish(timeout_s)

    def kill(self) -> None:
        if self.proc.poll() is None:
            self.proc.kill()
            self.proc.wait(10.0)
        self._close()
