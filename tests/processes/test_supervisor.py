"""How the supervisor reads a node's output: in chunks, a line at a time, each line cut at
MAX_LINE_CHARS and marked so, and never more held than one line's limit however long a line a node
prints without a newline. The splitter is driven directly, and through a pipe as a node's output
comes; one real process goes through the Supervisor itself (its kept lines, its console echo,
its exit)."""

from __future__ import annotations

import os
import sys
import threading
import tracemalloc
from collections.abc import Iterator

import pytest
from support.wait import wait_until

from node_runtime.bus import Bus, Executor
from server.host.processes.command import NodeCommand
from server.host.processes.output_lines import MAX_LINE_CHARS, LineSplitter, read_lines
from server.host.processes.supervisor import ProcessNode, Supervisor

MARK = f" … [cut: line longer than {MAX_LINE_CHARS} characters]"
MIB = 1 << 20
FLOOD_BYTES = 50 * MIB
PEAK_BYTES = 2 * MIB  # a chunk (64 KiB) and a line's limit (16 KiB), with room for the test's own


def split(*chunks: bytes) -> list[str]:
    lines: list[str] = []
    splitter = LineSplitter(lines.append)
    for chunk in chunks:
        splitter.feed(chunk)
    splitter.close()
    return lines


def in_chunks(data: bytes, size: int) -> Iterator[bytes]:
    return (data[i : i + size] for i in range(0, len(data), size))


def written_from_a_thread(*parts: bytes, repeat_first: int = 1) -> tuple[int, threading.Thread]:
    """The read end of a pipe that a thread fills with ``parts`` (the first ``repeat_first`` times),
    then closes: as a node writes its output, no faster than it is read."""
    read_end, write_end = os.pipe()

    def write() -> None:
        with os.fdopen(write_end, "wb", buffering=0) as out:
            for _ in range(repeat_first):
                out.write(parts[0])
            for part in parts[1:]:
                out.write(part)

    writer = threading.Thread(target=write, name="node-output", daemon=True)
    writer.start()
    return read_end, writer


def test_splitter_line_over_the_limit_is_cut_marked_and_the_next_line_is_whole() -> None:
    assert split(b"y" * (MAX_LINE_CHARS + 1) + b"\nnext line\n") == ["y" * MAX_LINE_CHARS + MARK, "next line"]


def test_splitter_line_at_the_limit_is_whole() -> None:
    assert split(b"y" * MAX_LINE_CHARS + b"\n") == ["y" * MAX_LINE_CHARS]


def test_splitter_long_line_goes_on_before_its_newline_and_its_rest_is_dropped() -> None:
    lines: list[str] = []
    splitter = LineSplitter(lines.append)
    splitter.feed(b"z" * 100_000)
    assert lines == ["z" * MAX_LINE_CHARS + MARK]  # the reader sees it while the node still prints
    splitter.feed(b"z" * 100_000)
    splitter.feed(b"z\ndone\n")
    splitter.close()
    assert lines == ["z" * MAX_LINE_CHARS + MARK, "done"]


@pytest.mark.parametrize("char", ["é", "€", "😀"])
@pytest.mark.parametrize("ascii_before", [0, 1, 2, 3])
def test_splitter_multibyte_characters_at_the_cut_stay_whole(char: str, ascii_before: int) -> None:
    """Each of 1, 2 or 3 ASCII characters first shifts where the byte limit falls inside a
    character; the chunks (an odd size) split characters too."""
    line = "a" * ascii_before + char * 6000
    (cut,) = split(*in_chunks(line.encode() + b"\n", 4093))
    assert cut == line[:MAX_LINE_CHARS] + MARK
    assert "\ufffd" not in cut


def test_splitter_character_split_across_chunks_in_a_short_line_is_whole() -> None:
    assert split(*in_chunks("héllo wörld €😀\n".encode(), 1)) == ["héllo wörld €😀"]


def test_splitter_a_bad_byte_is_a_replacement_character() -> None:
    assert split(b"bad \xff byte\n") == ["bad \ufffd byte"]


def test_splitter_line_ends_as_universal_newlines_read_them() -> None:
    """``\\r\\n`` and a lone ``\\r`` end a line as ``\\n`` does (as the text stream read before),
    also with the ``\\r`` last in one chunk and the ``\\n`` first in the next; empty lines stay."""
    assert split(b"a\r", b"\nb\rc\r\n\n", b"\rd\n") == ["a", "b", "c", "", "", "d"]


def test_splitter_last_line_without_a_newline_is_kept() -> None:
    assert split(b"one\ntw", b"o") == ["one", "two"]
    assert split(b"") == []


def test_read_lines_fifty_mib_line_through_a_pipe_holds_little() -> None:
    read_end, writer = written_from_a_thread(
        b"x" * MIB, b"\nafter the flood\nlast, no newline", repeat_first=50
    )
    lines: list[str] = []
    tracemalloc.start()
    try:
        with os.fdopen(read_end, "rb", buffering=0) as stream:
            read_lines(stream, lines.append)
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    writer.join(timeout=10)
    assert lines == ["x" * MAX_LINE_CHARS + MARK, "after the flood", "last, no newline"]
    assert peak < PEAK_BYTES, f"peak {peak / MIB:.1f} MiB while reading a {FLOOD_BYTES // MIB} MiB line"


PRINTS = """
import sys
sys.stdout.write("x" * 10000 + "\\n")
sys.stdout.write("a line as any\\n")
sys.stdout.write("the last, no newline")
"""


def test_supervisor_keeps_and_echoes_the_cut_line_and_reports_the_exit(
    bus: Bus, executor: Executor, capsys: pytest.CaptureFixture[str]
) -> None:
    exited: list[ProcessNode] = []
    supervisor = Supervisor(bus, exited.append)
    command = NodeCommand([sys.executable, "-c", PRINTS], env=dict(os.environ), zid="1" * 32)
    process = supervisor.start(command, "printer", screen=True, node_name=None)
    wait_until(lambda: process.exit_code is not None, "the printer to end")
    executor.spin_some()  # its exit reaches the supervisor's poller on the executor's thread
    assert exited == [process] and process.state == "died" and process.exit_code == 0
    cut = "x" * MAX_LINE_CHARS + MARK
    assert process.output() == ([cut, "a line as any", "the last, no newline"], 3)
    echoed = capsys.readouterr().out.splitlines()
    assert echoed == [f"[{process.label}] {line}" for line in (cut, "a line as any", "the last, no newline")]
