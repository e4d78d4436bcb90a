"""The comparer cannot pass by accident: a different line, order, exit code or measured rate is
a difference; a missing oracle fails with what to run; and the two sides really are two rclpys."""

from __future__ import annotations

from pathlib import Path

import pytest

from .harness import (
    DOMAINS,
    MissingOracle,
    Run,
    compare,
    normalise,
    oracle_python,
    run_lab,
    run_oracle,
    worker_domains,
    worker_share,
)

LOGGED = '[INFO] [1795929059.433280785] [talker]: I heard: "Hello World: 1"\nheard 1\n'


def test_runs_that_differ_only_in_log_stamps_are_the_same() -> None:
    other = LOGGED.replace("1795929059.433280785", "1795929060.000000001")
    assert compare(Run(LOGGED, 0), Run(other, 0)) is None
    assert normalise(Run(LOGGED, 0))[0] == '[INFO] [<stamp>] [talker]: I heard: "Hello World: 1"'


@pytest.mark.parametrize(
    ("ours", "shown"),
    [
        (
            Run(LOGGED.replace("World: 1", "World: 2"), 0),
            '+[INFO] [<stamp>] [talker]: I heard: "Hello World: 2"',
        ),
        (Run("heard 1\n" + LOGGED.splitlines()[0] + "\n", 0), "-heard 1"),  # the same lines, another order
        (Run(LOGGED, 1), "+(exit code 1)"),
        (Run(LOGGED, None), "+(exit code killed)"),
        (Run(LOGGED.replace("[INFO]", "[WARN]"), 0), "+[WARN] [<stamp>]"),
        (Run(LOGGED + "one more\n", 0), "+one more"),
    ],
    ids=["another-message", "another-order", "another-exit", "killed", "another-severity", "a-line-more"],
)
def test_any_other_output_is_a_difference_shown_as_a_diff(ours: Run, shown: str) -> None:
    problem = compare(Run(LOGGED, 0), ours)
    assert problem is not None
    assert "--- ROS 2's rclpy" in problem and "+++ the lab's rclpy" in problem
    assert shown in problem


def test_tracebacks_compare_by_their_exception_not_by_their_frames() -> None:
    theirs = 'Traceback (most recent call last):\n  File "/a/rclpy/node.py", line 3, in f\n    x()\nValueError: bad\n'
    ours = 'Traceback (most recent call last):\n  File "/runner.py", line 9\n  File "/b/rclpy/node.py", line 7\nValueError: bad\n'
    assert normalise(Run(theirs, 1)) == [
        "Traceback (most recent call last):",
        "  ...",
        "ValueError: bad",
        "(exit code 1)",
    ]
    assert compare(Run(theirs, 1), Run(ours, 1)) is None
    problem = compare(Run(theirs, 1), Run(ours.replace("ValueError", "TypeError"), 1))
    assert problem is not None and "+TypeError: bad" in problem


def test_an_exception_a_destructor_raised_and_python_ignored_is_no_difference() -> None:
    """Seen from ROS 2's rclpy under load: an executor collected after rclpy.shutdown(); its
    peer, the same exception printed by the program itself, still differs."""
    said = "MultiThreadedExecutor spin raised: tick 3\n"
    ignored = (
        "Exception ignored in: <function Executor.__del__ at 0x7f14c1f03c40>\n"
        "Traceback (most recent call last):\n"
        '  File "/a/rclpy/executors.py", line 302, in __del__\n'
        "rclpy._rclpy_pybind11.InvalidHandle: cannot use Destroyable because destruction was requested\n"
    )
    assert normalise(Run(said + ignored + "done\n", 0)) == [said.strip(), "done", "(exit code 0)"]
    assert compare(Run(said + ignored + "done\n", 0), Run(said + "done\n", 0)) is None
    raised = ignored.split("\n", 1)[1]  # the traceback without the interpreter's header
    assert compare(Run(said + raised + "done\n", 0), Run(said + "done\n", 0)) is not None


def test_measured_numbers_agree_within_the_tolerance_only() -> None:
    theirs = Run("measured rate: 10.00 Hz\n", 0)
    assert compare(theirs, Run("measured rate: 9.1 Hz\n", 0), tolerance=0.2) is None
    problem = compare(theirs, Run("measured rate: 7.5 Hz\n", 0), tolerance=0.2)
    assert problem == "measured rate: 7.5 Hz on the lab's rclpy, 10.0 Hz on ROS 2's (more than 20% apart)"
    assert compare(theirs, Run("measured period: 10.00 Hz\n", 0)) is not None  # another label


def test_a_missing_oracle_is_an_error_that_says_to_run_the_set_up(tmp_path: Path) -> None:
    with pytest.raises(MissingOracle, match=r"run scripts/test\.sh"):
        oracle_python(tmp_path)
    (tmp_path / "oracle" / "bin").mkdir(parents=True)
    (tmp_path / "oracle" / "bin" / "python").touch()
    with pytest.raises(MissingOracle):  # an install that never finished (no stamp) is missing too
        oracle_python(tmp_path)


def test_the_two_sides_run_two_different_rclpys(oracle: Path, router: str, tmp_path: Path) -> None:
    """A program that prints where its rclpy comes from differs, so the suite compares ROS 2's
    rclpy with the lab's, not one with itself."""
    program = tmp_path / "where.py"
    program.write_text(
        "import rclpy\n\n\ndef main():\n    rclpy.init()\n"
        "    print('rclpy from', rclpy.__file__.split('/')[-3])\n    rclpy.shutdown()\n\n\n"
        "if __name__ == '__main__':\n    main()\n"
    )
    domain = DOMAINS.start - 1  # below the programs' own
    theirs, ours = run_oracle(oracle, program, domain), run_lab(program, domain, router)
    assert normalise(theirs) == ["rclpy from site-packages", "(exit code 0)"]
    assert normalise(ours) == ["rclpy from client", "(exit code 0)"]
    problem = compare(theirs, ours)
    assert problem is not None and "-rclpy from site-packages" in problem and "+rclpy from client" in problem


def test_each_xdist_worker_gets_domains_no_other_worker_gets() -> None:
    assert worker_share(None, 1) == (0, 1) and worker_share("gw3", 5) == (3, 5)
    for workers in (1, 2, 5, 13):
        slices = [set(worker_domains(i, workers)) for i in range(workers)]
        assert all(len(s) >= 3 and s <= set(DOMAINS) for s in slices), workers
        assert sum(len(s) for s in slices) == len(set().union(*slices)), workers  # none shared
