"""A node's ``sys.exit()`` or a KeyboardInterrupt raised by node code (not a real Ctrl-C) crashes
that node only: the executor and the launcher keep the server up."""

from __future__ import annotations

import signal
import sys
from collections.abc import Iterator

import pytest

from node_runtime.bus import Bus, Executor, Node
from node_runtime.bus.faults import is_node_fault


@pytest.fixture
def server_sigint_handler() -> Iterator[None]:
    """SIGINT handled as a server (uvicorn) handles it: Ctrl-C no longer raises KeyboardInterrupt."""
    previous = signal.signal(signal.SIGINT, lambda *_: None)
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous)


def _ticking(bus: Bus, name: str, fail: BaseException | None) -> Node:
    node = Node(name, context=bus)
    node.ticks = 0  # type: ignore[attr-defined]

    def tick() -> None:
        node.ticks += 1  # type: ignore[attr-defined]
        if fail is not None:
            raise fail

    node.create_timer(1.0, tick)
    return node


@pytest.mark.parametrize("fault", [SystemExit(0), SystemExit("bye"), ValueError("bad")])
def test_node_exiting_in_a_callback_crashes_only_that_node(
    bus: Bus, executor: Executor, fault: BaseException
) -> None:
    quitter = _ticking(bus, "quitter", fault)
    steady = _ticking(bus, "steady", None)
    executor.spin_until(5.0)
    assert quitter.state == "crashed" and type(fault).__name__ in (quitter.crash_reason or "")
    assert quitter.ticks == 1  # type: ignore[attr-defined]
    assert steady.state == "active" and steady.ticks == 5  # type: ignore[attr-defined]


def test_keyboard_interrupt_from_node_code_under_a_server_crashes_the_node(
    bus: Bus, executor: Executor, server_sigint_handler: None
) -> None:
    node = _ticking(bus, "interrupter", KeyboardInterrupt())
    executor.spin_until(2.0)
    assert node.state == "crashed"


def test_keyboard_interrupt_with_pythons_own_sigint_handler_still_stops(bus: Bus, executor: Executor) -> None:
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler
    _ticking(bus, "interrupter", KeyboardInterrupt())
    with pytest.raises(KeyboardInterrupt):
        executor.spin_until(2.0)


def test_generator_exit_is_not_a_node_fault() -> None:
    assert not is_node_fault(GeneratorExit())
    assert is_node_fault(SystemExit(sys.maxsize))
