"""What a node process runs: ``python -m node_runtime.process.runner FILE [ARGS]``, ``--entry-point ROOT
MODULE:FUNCTION NAME WHERE [ARGS]`` or ``--builtin MODULE:CLASS [ARGS]``.

For a student's file it does what ``ros2 run`` does with a Python executable, with a clearer word
when the file cannot run at all: a syntax error, a missing import, or a file that would do nothing
(no ``main()`` and no ``if __name__ == '__main__':`` block) is one line naming the file and line,
and a non-zero exit. Otherwise the file runs as ``__main__`` (so its ``main()`` runs, and its own
``time.sleep`` sleeps), and an exception in it prints its traceback and ends the process.

An ament_python package's console script runs as its installed script would: the package's folder
is on ``sys.path`` (so its modules import each other, relative imports included), the module is
imported and its function called, with ``sys.argv`` as ``ros2 run`` gives it. A module or function
that does not exist is one line naming where the script is declared (``setup.py:LINE``).

A lab's built-in node runs with rclpy's usual ``init``/``spin``/``try_shutdown``.

``--launch-description FILE REQUEST`` evaluates a Python launch file instead of running a node
(``launch.lab_evaluation``): its ``generate_launch_description()`` is a student's code, so it runs
where a student's node would, in the sandbox on a server that serves others.

The workspace's interface packages import as their generated modules would
(node_runtime.process.interface_modules), from ``$ROS2LAB_WORKSPACE``.

The parameter files its ``--ros-args`` name (``--params-file FILE``) are read before any of its
code runs: one that cannot be read or does not parse is one line naming the file (and the line
the YAML parser gives), and a non-zero exit.

The process ends when the lab that started it does (Linux's parent-death signal), so no node
outlives a killed app. A sandboxed node (server/host/processes/sandbox.py) takes its limits on first
(node_runtime/process/confinement.py); over its memory limit it ends with one line that says so.
"""

from __future__ import annotations

import ast
import contextlib
import importlib
import os
import runpy
import signal
import sys
import traceback
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING

from node_runtime.process import confinement, lab_packages, node_init

if TYPE_CHECKING:
    from node_runtime.ament.entry_points import EntryPoint

# The lab's heavier modules (the bus, the workspace's packages, YAML) are imported where they are
# used, after a sandboxed node's split (node_runtime/process/node_init.py): the sandbox's pid 1 then
# holds little more than the interpreter, and its pages are not copied into the node as it runs.

EXIT_USAGE = 2
LAUNCH_MODE = "--launch-description"  # a Python launch file evaluated (launch.lab_evaluation)
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


def _exit_code(result: object) -> int:
    """What ``sys.exit(main())`` of an installed console script makes of ``main``'s result."""
    if result is None:
        return 0
    if isinstance(result, int):
        return result
    _say(str(result))
    return EXIT_FAILED


def run_file(path: Path, args: list[str]) -> int:
    checked = check_file(path)
    if isinstance(checked, str):
        _say(checked)
        return EXIT_USAGE
    _tree, has_block, has_main = checked
    sys.argv = [str(path), *args]
    sys.path.insert(0, str(path.parent))
    return _guarded(path, lambda: _run_path(path, has_block, has_main))


def _run_path(path: Path, has_block: bool, has_main: bool) -> int:
    namespace = runpy.run_path(str(path), run_name="__main__" if has_block else "__lab_node__")
    if not has_block and has_main:
        return _exit_code(namespace["main"]())  # as an ament_python entry point calls it
    return 0


def _module_file(root: Path, module: str) -> Path | None:
    base = root.joinpath(*module.split("."))
    for candidate in (base.with_suffix(".py"), base / "__init__.py"):
        if candidate.is_file():
            return candidate
    return None


def run_entry_point(point: EntryPoint, args: list[str]) -> int:
    """Import ``point.module`` with its package importable and call ``point.function()``."""
    script = f"console script '{point.name} = {point.module}:{point.function}'"
    path = _module_file(point.root, point.module)
    if path is None:
        _say(f"{point.declared_at}: {script}: no module '{point.module}' in {point.root}")
        return EXIT_USAGE
    checked = check_file(path) if path.name != "__init__.py" else None
    if isinstance(checked, str) and "SyntaxError" in checked:
        _say(checked)
        return EXIT_USAGE
    sys.argv = [point.name, *args]
    sys.path.insert(0, str(point.root))

    def call() -> int:
        function: object = importlib.import_module(point.module)
        for attr in point.function.split("."):  # ``module:Class.method`` as setuptools allows
            function = getattr(function, attr, None)
        if not callable(function):
            _say(f"{point.declared_at}: {script}: {path} has no function '{point.function}'")
            return EXIT_USAGE
        return _exit_code(function())

    return _guarded(path, call)


def _guarded(path: Path, body: Callable[[], int]) -> int:
    """Run a student's code as Python would, with one line for an import it cannot make."""
    try:
        return body()
    except ImportError as exc:
        if any(Path(f.filename) == path for f in traceback.extract_tb(exc.__traceback__)):
            _say(_import_problem(path, exc))
            return EXIT_FAILED
        traceback.print_exc()
        return EXIT_FAILED
    except KeyboardInterrupt:
        return 130  # Ctrl-C the file did not handle itself (the handout's nodes do)
    except MemoryError:
        limits = confinement.from_env()
        if limits is None:
            traceback.print_exc()
            return EXIT_FAILED
        _say(limits.memory_line())  # the sandbox's limit, not a bug in the node
        return confinement.EXIT_MEMORY
    except SystemExit as exc:
        return exc.code if isinstance(exc.code, int) else (0 if exc.code is None else EXIT_FAILED)
    except BaseException:
        traceback.print_exc()  # as Python prints an uncaught exception, and ends with 1
        return EXIT_FAILED


def run_builtin(target: str, args: list[str]) -> int:
    import rclpy

    module, _, attr = target.partition(":")
    node_class = getattr(importlib.import_module(module), attr)
    rclpy.init(args=[target, *args])
    try:
        node = node_class()
        from node_runtime.bus.parameter_service import serve_parameters

        serve_parameters(node)  # a lab node is the bus's, not rclpy's: it serves them as the app's do
        rclpy.spin(node)
    except KeyboardInterrupt:
        pass
    finally:
        rclpy.try_shutdown()
    return 0


def params_files_problem(args: list[str]) -> str | None:
    """The first ``--params-file`` among the ROS arguments that does not parse, in one line."""
    from node_runtime.params_file import ParamsFileError, read_params_file

    inside = False
    for i, arg in enumerate(args):
        if arg == "--ros-args":
            inside = True
        elif arg == "--":
            inside = False
        elif inside and arg == "--params-file" and i + 1 < len(args):
            try:
                read_params_file(args[i + 1])
            except ParamsFileError as exc:
                return str(exc)
    return None


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    limits = confinement.from_env()
    if limits is not None:  # a sandboxed node: its limits before any of its code
        limits.apply()
        node_init.split()  # pid 1 stays the lab's, holding the lifeline; the node runs in the child
    _die_with_parent()
    problem = params_files_problem(argv)
    if problem is not None:
        _say(problem)
        return EXIT_USAGE
    if len(argv) == 3 and argv[0] == LAUNCH_MODE:  # before the heavier imports a node needs
        lab_packages.pin()
        from launch.lab_evaluation import main as evaluate_launch_file

        return evaluate_launch_file(argv[1], argv[2])
    from node_runtime.ament.entry_points import EntryPoint
    from node_runtime.process import interface_modules

    interface_modules.install()
    lab_packages.pin()  # before any student's folder is on sys.path
    if len(argv) >= 2 and argv[0] == "--builtin":
        return run_builtin(argv[1], argv[2:])
    if len(argv) >= 5 and argv[0] == "--entry-point":
        module, _, function = argv[2].partition(":")
        return run_entry_point(EntryPoint(Path(argv[1]), module, function, argv[3], argv[4]), argv[5:])
    if not argv:
        _say(
            "usage: python -m node_runtime.process.runner FILE [ARGS] | --builtin MODULE:CLASS [ARGS] "
            "| --entry-point ROOT MODULE:FUNCTION NAME WHERE [ARGS] | --launch-description FILE REQUEST"
        )
        return EXIT_USAGE
    return run_file(Path(argv[0]).resolve(), argv[1:])


def end(code: int) -> None:
    """Leave with ``code``, the node's own exit code. Python's normal exit would turn a Ctrl-C that a
    library call saw (and the node then handled) into death by SIGINT; so the graph is left and the
    output flushed here, then the process ends at once."""
    rclpy = sys.modules.get("rclpy")
    if rclpy is not None:
        try:
            rclpy.try_shutdown()
        except Exception:  # the node's own shutdown already failed; the exit code says the rest
            traceback.print_exc()
    for stream in (sys.stdout, sys.stderr):
        with contextlib.suppress(OSError, ValueError):
            stream.flush()
    os._exit(code)


if __name__ == "__main__":
    end(main())
