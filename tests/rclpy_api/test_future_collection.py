"""A future the executor is done with is collected without running any code of ours, so a Ctrl-C
that lands as it goes cannot be swallowed there (CPython drops an exception raised inside a
finaliser: "Exception ignored in"); a 10 Hz node drops ten such tasks a second. A future finished
with an exception nobody fetched still says so when it is collected, as rclpy's does, and one
whose exception was fetched says nothing."""

from __future__ import annotations

import gc
import sys
from typing import Any

import pytest
from rclpy.task import Future, Task


def python_calls_while_collected(make: Any) -> list[str]:
    """The Python functions that run while the last reference to ``make()``'s object goes."""
    obj = make()
    calls: list[str] = []

    def profile(frame: Any, event: str, _arg: Any) -> None:
        if event == "call":
            calls.append(frame.f_code.co_name)

    sys.setprofile(profile)
    try:
        del obj
    finally:
        sys.setprofile(None)
    return calls


def finished_task() -> Task:
    task = Task(lambda: 42)
    task()
    assert task.result() == 42
    return task


def test_a_finished_task_or_future_is_collected_with_no_python_code_run() -> None:
    def with_result() -> Future[int]:
        future: Future[int] = Future()
        future.set_result(7)
        return future

    assert python_calls_while_collected(finished_task) == []
    assert python_calls_while_collected(with_result) == []
    assert python_calls_while_collected(Future) == []


def test_an_exception_nobody_fetched_is_reported_when_its_future_goes(
    capsys: pytest.CaptureFixture[str],
) -> None:
    def failed() -> Future[int]:
        future: Future[int] = Future()
        future.set_exception(ValueError("the goal was refused"))
        return future

    assert python_calls_while_collected(failed) != []  # the report runs, as the peer of the above
    gc.collect()
    assert "The following exception was never retrieved: the goal was refused" in capsys.readouterr().err

    fetched = failed()
    assert isinstance(fetched.exception(), ValueError)
    del fetched
    gc.collect()
    assert "never retrieved" not in capsys.readouterr().err
