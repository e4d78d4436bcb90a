"""What a node process runs: ``python -m server.processes.runner FILE [ARGS]`` or ``--builtin PKG EXEC``.

For a student's file it does what ``ros2 run`` does with a Python executable, with a clearer word
when the file cannot run at all: a syntax error, a missing import, or a file that would do nothing
(no ``main()`` and no ``if __name__ == '__main__':`` block) is one line naming the file and line,
and a non-zero exit. Otherwise the file runs as ``__main__`` (so its ``main()`` runs, and its own
``time.sleep`` sleeps), and an exception in it prints its traceback and ends the process.

A lab's built-in node runs with rclpy's usual ``init``/``spin``/``try_shutdown``.

The process ends when the lab that started it does (Linux's parent-death signal), so no node
outlives a killed app.
"""

from __future__ import annotations

import ast
import importlib
import os
import runpy
import signal
import sys
import traceback
from pathlib import Path

EXIT_USAGE = 2
EXIT_FAILED = 1
PARENT_ENV = "ROS2LAB_PARENT_PID"


def _die_with_parent() -> None:
    parent = os.environ.get(PARENT_ENV)
    if not parent or not sys.platform.startswith("linux"):
        return
    import ctypes

    pr_set_pdeathsig = 1
    libc = ctypes.CDLL(None, use_errno=True)
    libc.prctl(pr_set_pdeathsig, signal.SIGTERM, 0, 0, 0)
    if os.getppid() != int(parent):  # the parent died before the request took hold
        sys.exit(EXIT_FAILED)


def _say(text: str) -> None:
    print(text, file=sys.stderr, flush=True)


def check_file(path: Path) -> tuple[ast.Module, bool, bool] | str:
    """The parsed file with (has a ``__main__`` block, defines ``main``), or the one-line problem."""
    try:
        source = path.read_text(encoding="utf-8")
    except OSError as exc:
        return f"{path}: cannot read it: {exc.strerror}"
    try:
        tree = ast.parse(source, filename=str(path))
    except SyntaxError as exc:
        return f"{path}:{exc.lineno}: SyntaxError: {exc.msg}"
    has_block = any(
        isinstance(node, ast.If)
        and isinstance(node.test, ast.Compare)
        and isinstance(node.test.left, ast.Name)
        and node.test.left.id == "__name__"
        for node in tree.body
    )
    has_main = any(isinstance(node, ast.FunctionDef) and node.name == "main" for node in tree.body)
    if not has_block and not has_main:
        return (
            f"{path}: nothing would run: it has no main() and no `if __name__ == '__main__':` block "
            "(end it as the handout does: rclpy.init(), then rclpy.spin(YourNode()))"
        )
    return tree, has_block, has_main


def _import_problem(path: Path, exc: ImportError) -> str:
    frames = [f for f in traceback.extract_tb(exc.__traceback__) if Path(f.filename) == path]
    where = f"{path}:{frames[-1].lineno}" if frames else str(path)
    return f"{where}: {type(exc).__name__}: {exc}"


def run_file(path: Path, args: list[str]) -> int:
    checked = check_file(path)
    if isinstance(checked, str):
        _say(checked)
        return EXIT_USAGE
    _tree, has_block, has_main = checked
    sys.argv = [str(path), *args]
    sys.path.insert(0, str(path.parent))
    try:
        namespace = runpy.run_path(str(path), run_name="__main__" if has_block else "__lab_node__")
        if not has_block and has_main:
            result = namespace["main"]()  # as an ament_python entry point calls it
            return result if isinstance(result, int) else 0
    except ImportError as exc:
        if any(Path(f.filename) == path for f in traceback.extract_tb(exc.__traceback__)):
            _say(_import_problem(path, exc))
            return EXIT_FAILED
        raise
    except KeyboardInterrupt:
        return 130  # Ctrl-C the file did not handle itself (the handout's nodes do)
    return 0


def run_builtin(target: str, args: list[str]) -> int:
    import rclpy

    module, _, attr = target.partition(":")
    node_class = getattr(importlib.import_module(module), attr)
    rclpy.init(args=[target, *args])
    try:
        rclpy.spin(node_class())
    except KeyboardInterrupt:
        pass
    finally:
        rclpy.try_shutdown()
    return 0


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    _die_with_parent()
    if len(argv) >= 2 and argv[0] == "--builtin":
        return run_builtin(argv[1], argv[2:])
    if not argv:
        _say("usage: python -m server.processes.runner FILE [ARGS] | --builtin MODULE:CLASS [ARGS]")
        return EXIT_USAGE
    return run_file(Path(argv[0]).resolve(), argv[1:])


if __name__ == "__main__":
    sys.exit(main())
