"""What the app prints: one lab shows its nodes' lines as ``ros2 launch`` does; a class server
and its world workers show their own events and each world's warnings, not 30 worlds' chatter.

A class world's nodes log under ``world.<world>`` (``node_runtime.bus.node.node_logger_name``), so
``--world-log-level`` sets them all at once; their every line still goes to the world's own
``/rosout``, where its student reads them (``ros2lab topic echo /rosout``, the tools page).
"""

from __future__ import annotations

import logging
import unicodedata

WORLD_LOGGER = "world"  # the parent logger of every class world's nodes
LEVELS = ("debug", "info", "warning", "error")
# Libraries whose routine lines say nothing to a user: the class server's calls to its workers
# (httpx), and each viser server's own loopback socket opening (websockets).
_CHATTY = ("httpx", "websockets.server", "websockets.client")
_BREAKING = frozenset({"Cc", "Cf", "Zl", "Zp"})  # control, format (bidi overrides), line separators


def one_line(text: str) -> str:
    """``text`` with every control or line-breaking character escaped (``\\n``, ``\\x1b``): a
    client's value or a student node's message in a log line can never start a line of its own."""
    if text.isprintable():
        return text
    return "".join(
        c if c == "\t" or unicodedata.category(c) not in _BREAKING else repr(c)[1:-1] for c in text
    )


class OneLineFormatter(logging.Formatter):
    """A record's message on one line (its traceback, the formatter's own, still below it)."""

    def formatMessage(self, record: logging.LogRecord) -> str:
        record.message = one_line(record.message)
        return super().formatMessage(record)


def world_logger(world: str) -> str:
    """The logger a class world's node lines go under (its nodes' loggers are its children)."""
    return f"{WORLD_LOGGER}.{world}"


def setup_logging(
    level: str, *, classroom: bool = False, world_level: str = "warning", who: str = ""
) -> None:
    """The process's logging: ``level`` for the app, ``world_level`` for a class's worlds' nodes,
    and ``who`` (a world worker's id) in front of every line when several processes share a console."""
    prefix = f"[{who}] " if who else ""
    handler = logging.StreamHandler()
    handler.setFormatter(
        OneLineFormatter(f"%(asctime)s {prefix}%(levelname)s %(name)s: %(message)s", "%H:%M:%S")
    )
    logging.basicConfig(level=level.upper(), handlers=[handler])
    if level != "debug":
        for name in _CHATTY:
            logging.getLogger(name).setLevel(logging.WARNING)
    if classroom:
        logging.getLogger(WORLD_LOGGER).setLevel(world_level.upper())


def access_log(level: str, *, classroom: bool) -> bool:
    """Whether uvicorn logs every request: for one lab yes; a class's pages poll, so only at debug."""
    return not classroom or level == "debug"


def quiet_uvicorn(level: str, *, classroom: bool) -> None:
    """In a class, uvicorn's own info lines are four per page opened ("WebSocket ... [accepted]",
    "connection open"): keep its warnings only, below debug. Call it after ``uvicorn.Config``,
    which sets uvicorn's levels."""
    if classroom and level != "debug":
        logging.getLogger("uvicorn.error").setLevel(logging.WARNING)
