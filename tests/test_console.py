"""What a process prints (node_runtime/console.py): each check runs in a fresh interpreter, since
logging's set-up is once per process."""

from __future__ import annotations

import subprocess
import sys
import textwrap

from node_runtime.console import access_log


def console_of(setup: str) -> list[str]:
    """The lines a fresh process prints after ``setup`` and the same five log calls."""
    script = textwrap.dedent(f"""
        import logging
        from node_runtime.console import setup_logging
        {setup}
        logging.getLogger("world.ada.MainControllerNode").info("[MainControllerNode] Countdown: 3s")
        logging.getLogger("world.bob.PositionController").warning("[PositionController] setpoint clamped")
        logging.getLogger("node.talker").info("[talker] hello")
        logging.getLogger("classroom").info("Ada joined: world ada")
        logging.getLogger("httpx").info("HTTP Request: GET http://127.0.0.1:1/api/nodes")
    """)
    done = subprocess.run(
        [sys.executable, "-c", script], capture_output=True, text=True, timeout=60, check=True
    )
    return done.stderr.splitlines()


def test_a_class_console_shows_its_own_events_and_the_worlds_warnings_by_name() -> None:
    lines = console_of("setup_logging('info', classroom=True)")
    assert [line.split(" ", 1)[1] for line in lines] == [
        "WARNING world.bob.PositionController: [PositionController] setpoint clamped",
        "INFO node.talker: [talker] hello",
        "INFO classroom: Ada joined: world ada",
    ]


def test_a_class_console_can_show_every_worlds_info_lines_and_a_worker_names_itself() -> None:
    lines = console_of("setup_logging('info', classroom=True, world_level='info', who='local-2')")
    assert all(line.split(" ")[1] == "[local-2]" for line in lines), lines
    assert any(
        line.endswith("world.ada.MainControllerNode: [MainControllerNode] Countdown: 3s") for line in lines
    )
    assert not any("httpx" in line for line in lines)


def test_debug_shows_everything_and_one_lab_logs_every_request() -> None:
    lines = console_of("setup_logging('debug', classroom=True, world_level='debug')")
    assert len(lines) == 5 and "HTTP Request" in lines[-1]
    assert access_log("info", classroom=False) and access_log("debug", classroom=True)
    assert not access_log("info", classroom=True)  # a class's pages poll: 30 students would flood it


def test_a_message_with_line_breaks_or_escapes_stays_on_its_one_line() -> None:
    script = textwrap.dedent("""
        import logging
        from node_runtime.console import setup_logging
        setup_logging('info', classroom=True, world_level='info')
        logging.getLogger("classroom").info("%s joined", "Eve\\r\\n12:00:00 INFO classroom: Mallory joined")
        logging.getLogger("world.ada.talker").warning("[talker] a\\nb\\x1b[2J\\u2028c\\u202ed\\tе")
        logging.getLogger("classroom").info("Ada joined: world ada")
        try:
            raise ValueError("boom")
        except ValueError:
            logging.getLogger("classroom").exception("it failed")
    """)
    done = subprocess.run(
        [sys.executable, "-c", script], capture_output=True, text=True, timeout=60, check=True
    )
    lines = done.stderr.splitlines()
    assert lines[0].endswith("INFO classroom: Eve\\r\\n12:00:00 INFO classroom: Mallory joined joined")
    assert lines[1].endswith("WARNING world.ada.talker: [talker] a\\nb\\x1b[2J\\u2028c\\u202ed\tе")
    assert lines[2].endswith("INFO classroom: Ada joined: world ada")  # a clean line as it was
    assert (
        lines[3].endswith("ERROR classroom: it failed") and lines[4] == "Traceback (most recent call last):"
    )
    assert lines[-1] == "ValueError: boom"  # a traceback keeps its own lines
