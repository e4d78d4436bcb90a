"""demo_nodes_py's and demo_nodes_cpp's talker and listener: their names, topic and lines."""

from __future__ import annotations

from collections.abc import Callable

import pytest

from node_runtime.bus import Bus, Executor
from node_runtime.msgs import Message, String
from server.packages.demo_nodes_cpp.talker import Talker as CppTalker
from server.packages.demo_nodes_py.listener import Listener
from server.packages.demo_nodes_py.talker import Talker

from .conftest import Recorder

Record = Callable[[dict[str, type[Message]]], Recorder]


@pytest.mark.parametrize(
    ("talker", "lines"),
    [
        (Talker, ['Publishing: "Hello World: 0"', 'Publishing: "Hello World: 1"']),
        (CppTalker, ["Publishing: 'Hello World: 1'", "Publishing: 'Hello World: 2'"]),
    ],
)
def test_talker_says_hello_world_on_chatter_once_a_second(
    bus: Bus, executor: Executor, record: Record, talker: type[Talker], lines: list[str]
) -> None:
    rec = record({"/chatter": String})
    with bus.activate():
        node = talker()
    assert node.get_name() == "talker"
    executor.spin_until(2.5)
    assert rec.logs("talker") == lines
    assert rec.data("/chatter") == [line.split(" ", 1)[1].strip("'\"") for line in lines]
    assert rec.times("/chatter") == [1.0, 2.0]


def test_listener_logs_what_the_talker_says(bus: Bus, executor: Executor, record: Record) -> None:
    rec = record({})
    with bus.activate():
        Listener()
        CppTalker()
    executor.spin_until(2.0)
    assert rec.logs("listener") == ["I heard: [Hello World: 1]", "I heard: [Hello World: 2]"]
