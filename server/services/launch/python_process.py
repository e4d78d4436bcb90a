"""A Python launch file's ``generate_launch_description()`` is run in a process of its own, never
in the server: it is a student's code, so on a server that serves others it runs where a
student's node runs, in the sandbox (server/host/processes/sandbox.py), with the same limits.

The process (node_runtime/process/runner.py's ``--launch-description``, client/launch/lab_evaluation.py)
prints what the file launches as JSON; what the file prints itself comes back as lines to show.
"""

from __future__ import annotations

import contextlib
import itertools
import json
import os
import signal
import subprocess
import tempfile
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import IO, Any

from server.host.processes.command import PreparedStart, launch_command
from server.host.processes.sandbox import CLIENT_CODE, PROJECT, Sandbox, StudentCodeRefusedError
from server.services.launch.description import LaunchFileError

EVALUATION_TIMEOUT_S = 30.0
MAX_ANSWER_BYTES = 8 * 1024 * 1024
MAX_PRINTED_LINES = 100  # of what the file itself printed, shown with the launch
_labels = itertools.count(1)
OUTSIDE_SANDBOX = (
    "a Python launch file runs in the students' sandbox on this server, which sees only the lab's "
    "packages and the workspace: put it in a package there, or write it in XML or YAML"
)


@dataclass(frozen=True)
class Evaluation:
    """What the process answered: the JSON object, and the lines the launch file printed."""

    answer: Mapping[str, Any]
    printed: tuple[str, ...]


@dataclass(frozen=True)
class PythonLaunchProcess:
    """Runs Python launch files for one lab: its workspace, its sandbox (None: as the server's
    user), whether the launch is confined (no variable of the server's environment) and its ROS
    domain (a sandboxed world's uid follows it)."""

    workspace: Path | None
    sandbox: Sandbox | None = None
    confined: bool = False
    domain_id: int = 0
    timeout_s: float = EVALUATION_TIMEOUT_S
    refused: StudentCodeRefusedError | None = None  # a server that serves others but cannot sandbox

    def __call__(self, path: Path, args: Mapping[str, str], namespace: str | None) -> Evaluation:
        if self.refused is not None:
            raise self.refused
        if self.sandbox is not None and not sandbox_sees(path, self.workspace):
            raise LaunchFileError(str(path), 0, OUTSIDE_SANDBOX)
        request = json.dumps({"args": dict(args), "namespace": namespace})
        clean = self.sandbox is not None or self.confined
        command = launch_command(
            path, request, domain_id=self.domain_id, env={} if clean else None, workspace=self.workspace
        )
        if self.sandbox is not None:
            command = self.sandbox.wrap(command, self.workspace)
        label = f"launch-evaluation-{os.getpid()}-{next(_labels)}"
        prepared = command.prepare(command.argv, label) if command.prepare else PreparedStart(command.argv)
        with tempfile.TemporaryFile() as out, tempfile.TemporaryFile() as err:
            code = self._run(path, prepared, command.env, out, err)
            answer, printed = _read(out), _read(err).decode("utf-8", "replace").splitlines()
        return Evaluation(_parse(path, answer, code, printed), tuple(printed[-MAX_PRINTED_LINES:]))

    def _run(
        self, path: Path, prepared: PreparedStart, env: Mapping[str, str], out: IO[bytes], err: IO[bytes]
    ) -> int:
        try:
            process = subprocess.Popen(
                prepared.argv,
                env=dict(env),
                stdin=subprocess.DEVNULL,
                stdout=out,
                stderr=err,
                pass_fds=prepared.pass_fds,
                cwd=path.parent if self.sandbox is None else None,
                start_new_session=True,
            )
        finally:
            for fd in prepared.pass_fds:
                with contextlib.suppress(OSError):
                    os.close(fd)
        try:
            code = process.wait(timeout=self.timeout_s)
        except subprocess.TimeoutExpired:
            with contextlib.suppress(ProcessLookupError):
                os.killpg(process.pid, signal.SIGKILL)
            process.wait()
            prepared.finish(-signal.SIGKILL)
            raise LaunchFileError(
                str(path), 0, f"generate_launch_description() did not finish within {self.timeout_s:.0f} s"
            ) from None
        memory = prepared.finish(code)
        if memory is not None:
            raise LaunchFileError(str(path), 0, f"evaluating it ended: {memory}")
        return code


def sandbox_sees(path: Path, workspace: Path | None) -> bool:
    """Whether the sandbox shows ``path``: a file of the workspace or of the lab's own code."""
    roots = [PROJECT / name for name in CLIENT_CODE] + ([workspace] if workspace is not None else [])
    try:
        resolved = path.resolve()
        return any(resolved.is_relative_to(root.resolve()) for root in roots)
    except (OSError, RuntimeError):
        return False


def _read(stream: IO[bytes]) -> bytes:
    stream.seek(0)
    return stream.read(MAX_ANSWER_BYTES + 1)


def _parse(path: Path, answer: bytes, code: int, printed: list[str]) -> Mapping[str, Any]:
    try:
        parsed = json.loads(answer) if len(answer) <= MAX_ANSWER_BYTES else None
    except ValueError:
        parsed = None
    if not isinstance(parsed, dict):
        last = next((line for line in reversed(printed) if line.strip()), "")
        why = f": {last.strip()[:300]}" if last else ""
        raise LaunchFileError(str(path), 0, f"evaluating it failed (exit code {code}){why}")
    error = parsed.get("error")
    if error is not None:
        raise _as_error(str(error), str(path))
    return parsed


def _as_error(text: str, path: str) -> LaunchFileError:
    """``FILE:LINE: problem`` (the process's one line) as the launcher's error."""
    file, _, rest = text.partition(":")
    line, _, problem = rest.partition(": ")
    if file and line.isdigit() and problem:
        return LaunchFileError(file, int(line), problem)
    return LaunchFileError(path, 0, text)
