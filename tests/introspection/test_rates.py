"""``rate_stats`` and ``percentile``: ros2 topic hz's numbers, checked against hand-computed values."""

from __future__ import annotations

import math

import pytest

from node_runtime.bus import Bus, Executor, Node
from node_runtime.msgs import Int64
from server.host.introspection import RateStats, percentile, rate_stats


def test_rate_stats_uneven_periods_match_hand_computed_values() -> None:
    # Periods 1, 2, 1: mean 4/3 s, so 0.75 Hz; population std sqrt(((1/3)²·2 + (2/3)²)/3) = sqrt(2)/3.
    stats = rate_stats([0.0, 1.0, 3.0, 4.0], window=100)
    assert stats.window == 3
    assert stats.rate_hz == pytest.approx(0.75)
    assert (stats.min_s, stats.max_s) == (1.0, 2.0)
    assert stats.std_dev_s == pytest.approx(math.sqrt(2) / 3)


def test_rate_stats_window_2_uses_only_the_last_three_times() -> None:
    # Last three times 1, 3, 4: periods 2 and 1, mean 1.5 s, std 0.5 s.
    stats = rate_stats([0.0, 1.0, 3.0, 4.0], window=2)
    assert stats.rate_hz == pytest.approx(2 / 3)
    assert (stats.window, stats.min_s, stats.max_s, stats.std_dev_s) == (2, 1.0, 2.0, 0.5)


@pytest.mark.parametrize("times", [[], [5.0]])
def test_rate_stats_fewer_than_two_messages_gives_no_rate(times: list[float]) -> None:
    assert rate_stats(times, window=100) == RateStats(window=0)


def test_rate_stats_all_messages_at_one_instant_gives_no_rate_but_zero_spread() -> None:
    stats = rate_stats([2.0, 2.0, 2.0], window=10)
    assert stats == RateStats(window=2, rate_hz=None, min_s=0.0, max_s=0.0, std_dev_s=0.0)


def test_rate_stats_window_below_one_raises() -> None:
    with pytest.raises(ValueError):
        rate_stats([0.0, 1.0], window=0)


def test_rate_stats_publisher_with_0_1s_timer_on_manual_clock_is_exactly_10_hz(
    bus: Bus, executor: Executor
) -> None:
    node = Node("talker", context=bus)
    pub = node.create_publisher(Int64, "/ticks", 10)
    node.create_timer(0.1, lambda: pub.publish(Int64(data=1)))
    executor.spin_until(5.0)
    topic = bus.get_topic("/ticks")
    stats = rate_stats(topic.publish_times_s, window=100)
    assert topic.publish_count == 50
    assert stats.window == 49
    assert stats.rate_hz == pytest.approx(10.0, abs=1e-6)
    assert stats.std_dev_s == pytest.approx(0.0, abs=1e-9)
    assert stats.min_s == pytest.approx(0.1) and stats.max_s == pytest.approx(0.1)


def test_percentile_four_values_interpolates_linearly() -> None:
    values = [4.0, 1.0, 3.0, 2.0]
    assert percentile(values, 50) == pytest.approx(2.5)
    assert percentile(values, 99) == pytest.approx(3.97)
    assert (percentile(values, 0), percentile(values, 100)) == (1.0, 4.0)


def test_percentile_no_values_is_none() -> None:
    assert percentile([], 50) is None
