"""A node process's output as lines, read in bounded chunks: a node that prints one endless line
holds neither the server's memory nor its time (the supervisor reads it on a thread of its own)."""

from __future__ import annotations

import os
from collections.abc import Callable
from typing import IO

MAX_LINE_CHARS = 4096  # a longer line is kept cut and marked so (on the console too)
READ_CHUNK_BYTES = 64 * 1024  # one read of a node's output (a pipe's buffer on Linux)


class LineSplitter:
    """A node's output, fed in chunks of bytes as they come, handed to ``sink`` line by line: a
    line ends at ``\\n``, ``\\r\\n`` or ``\\r`` (as a text stream's universal newlines read them),
    is decoded as UTF-8 (a bad byte shown as U+FFFD) and keeps at most ``max_chars`` characters.
    A longer line goes on as soon as its limit is reached, with a mark that says it was cut; the
    rest of it is dropped as it comes, up to its end. So what is held is never more than one
    line's limit in bytes, however long a line a node prints without a newline."""

    def __init__(self, sink: Callable[[str], None], max_chars: int = MAX_LINE_CHARS) -> None:
        self._sink = sink
        self._max_chars = max_chars
        self._mark = f" … [cut: line longer than {max_chars} characters]"
        # A character takes at most 4 bytes: these hold max_chars whole characters before the
        # start of one cut off, so the cut line never ends in a needless U+FFFD.
        self._max_bytes = 4 * max_chars + 3
        self._line = bytearray()
        self._dropping = False  # this line's kept part has gone on: the rest waits for its end
        self._after_cr = False  # the last chunk ended with \r: a \n first in this one ends nothing

    def feed(self, chunk: bytes) -> None:
        if self._after_cr and chunk.startswith(b"\n"):
            chunk = chunk[1:]
        self._after_cr = chunk.endswith(b"\r")
        if b"\r" in chunk:
            chunk = chunk.replace(b"\r\n", b"\n").replace(b"\r", b"\n")
        *ended, rest = chunk.split(b"\n")
        for part in ended:
            self._add(part)
            if not self._dropping:
                self._hand_on(cut=False)
            self._dropping = False
        self._add(rest)

    def close(self) -> None:
        """The output's end: a last line with no newline goes on too."""
        if self._line:
            self._hand_on(cut=False)

    def _add(self, part: bytes) -> None:
        if self._dropping or not part:
            return
        room = self._max_bytes - len(self._line)
        self._line += part[:room]
        if len(part) > room:
            self._hand_on(cut=True)
            self._dropping = True

    def _hand_on(self, *, cut: bool) -> None:
        text = self._line.decode(errors="replace")
        self._line.clear()
        if cut or len(text) > self._max_chars:
            text = text[: self._max_chars] + self._mark
        self._sink(text)


def read_lines(stream: IO[bytes], sink: Callable[[str], None]) -> None:
    """Each line of a binary stream to ``sink`` (``LineSplitter``) until the stream ends; read a
    chunk at a time, as it comes, so nothing waits for a line's end to be read."""
    lines = LineSplitter(sink)
    fd = stream.fileno()
    while chunk := os.read(fd, READ_CHUNK_BYTES):
        lines.feed(chunk)
    lines.close()
