"""tf2_ros.Buffer's lookups: interpolation, chains through the tree, the latest common time and
tf2's exceptions with its messages. Times are stamps the test writes; no clock runs."""

from __future__ import annotations

import math

import pytest
from rclpy.duration import Duration
from rclpy.time import Time
from tf2_ros import (
    Buffer,
    ConnectivityException,
    ExtrapolationException,
    InvalidArgumentException,
    LookupException,
    TransformException,
)

from .frames import quat, stamped, xyz, yaw


def at(t_s: float) -> Time:
    return Time(seconds=t_s)


def test_a_time_between_two_stamps_is_interpolated_linearly_and_by_slerp() -> None:
    buffer = Buffer()
    buffer.set_transform(stamped("world", "robot", 10.0, (0.0, 0.0, 0.0), yaw(0.0)), "test")
    buffer.set_transform(stamped("world", "robot", 12.0, (4.0, 2.0, 0.0), yaw(math.pi / 2)), "test")
    mid = buffer.lookup_transform("world", "robot", at(11.0))
    assert xyz(mid) == pytest.approx((2.0, 1.0, 0.0))
    assert quat(mid) == pytest.approx(yaw(math.pi / 4))
    quarter = buffer.lookup_transform("world", "robot", at(10.5))
    assert xyz(quarter) == pytest.approx((1.0, 0.5, 0.0)) and quat(quarter) == pytest.approx(yaw(math.pi / 8))
    assert (mid.header.frame_id, mid.child_frame_id) == ("world", "robot")
    assert (mid.header.stamp.sec, mid.header.stamp.nanosec) == (11, 0)


def test_a_lookup_and_the_reverse_lookup_compose_to_the_identity() -> None:
    buffer = Buffer()
    buffer.set_transform(stamped("world", "robot", 1.0, (1.0, -2.0, 0.5), yaw(0.7)), "test")
    there = buffer.lookup_transform("world", "robot", at(1.0))
    back = buffer.lookup_transform("robot", "world", at(1.0))
    # back = there⁻¹: rotating there's translation by back's rotation and adding back's gives 0.
    assert quat(back) == pytest.approx((0.0, 0.0, -math.sin(0.35), math.cos(0.35)))
    c, s = math.cos(-0.7), math.sin(-0.7)
    x, y, z = xyz(there)
    assert (c * x - s * y + back.transform.translation.x, s * x + c * y + back.transform.translation.y) == (
        pytest.approx((0.0, 0.0), abs=1e-12)
    )
    assert z + back.transform.translation.z == pytest.approx(0.0)


def test_a_chain_through_a_three_frame_tree_composes_every_link_on_the_way() -> None:
    """world → base (moving, turned a quarter about z) → laser (static, 1 m ahead of base);
    world → dock. The laser seen from the dock goes up through base to world and down to dock."""
    buffer = Buffer()
    buffer.set_transform(stamped("world", "base", 5.0, (2.0, 3.0, 0.0), yaw(math.pi / 2)), "test")
    buffer.set_transform_static(stamped("base", "laser", 0.0, (1.0, 0.0, 0.5)), "test")
    buffer.set_transform_static(stamped("world", "dock", 0.0, (0.0, 10.0, 0.0), yaw(math.pi)), "test")
    laser_in_world = buffer.lookup_transform("world", "laser", Time())
    assert xyz(laser_in_world) == pytest.approx((2.0, 4.0, 0.5))  # base's x axis points along world's y
    laser_in_dock = buffer.lookup_transform("dock", "laser", Time())
    assert xyz(laser_in_dock) == pytest.approx((-2.0, 6.0, 0.5))  # the dock faces -x, 10 m up world's y
    assert quat(laser_in_dock) == pytest.approx(yaw(-math.pi / 2))
    assert laser_in_dock.header.stamp.sec == 5  # the moving link's latest time


def test_time_zero_is_the_latest_time_every_link_on_the_way_is_known() -> None:
    buffer = Buffer()
    for t_s in (1.0, 2.0, 3.0):
        buffer.set_transform(stamped("world", "arm", t_s, (t_s, 0.0, 0.0)), "test")
    for t_s in (1.5, 2.5):
        buffer.set_transform(stamped("arm", "hand", t_s, (0.0, t_s, 0.0)), "test")
    latest = buffer.lookup_transform("world", "hand", Time())
    assert (latest.header.stamp.sec, latest.header.stamp.nanosec) == (2, 500_000_000)
    assert xyz(latest) == pytest.approx((2.5, 2.5, 0.0))
    assert buffer.get_latest_common_time("world", "hand") == Time(seconds=2.5)


def test_static_links_alone_are_found_at_any_time_and_time_zero_stamps_zero() -> None:
    buffer = Buffer()
    buffer.set_transform_static(stamped("world", "mast", 100.0, (0.0, 0.0, 3.0)), "test")
    assert xyz(buffer.lookup_transform("world", "mast", at(5.0))) == (0.0, 0.0, 3.0)
    assert xyz(buffer.lookup_transform("world", "mast", at(1e6))) == (0.0, 0.0, 3.0)
    stamp = buffer.lookup_transform("world", "mast", Time()).header.stamp
    assert (stamp.sec, stamp.nanosec) == (0, 0)


def test_a_frame_to_itself_is_the_identity_even_unknown() -> None:
    found = Buffer().lookup_transform("nowhere", "nowhere", at(3.0))
    assert xyz(found) == (0.0, 0.0, 0.0) and quat(found) == (0.0, 0.0, 0.0, 1.0)


@pytest.mark.parametrize(
    ("t_s", "message"),
    [
        (
            13.0,
            "Lookup would require extrapolation into the future.  Requested time 13.000000 but the "
            "latest data is at time 12.000000, when looking up transform from frame [robot] to frame [world]",
        ),
        (
            9.5,
            "Lookup would require extrapolation into the past.  Requested time 9.500000 but the "
            "earliest data is at time 10.000000, when looking up transform from frame [robot] to frame [world]",
        ),
    ],
)
def test_outside_the_stored_times_is_an_extrapolation_naming_frames_and_times(
    t_s: float, message: str
) -> None:
    buffer = Buffer()
    buffer.set_transform(stamped("world", "robot", 10.0), "test")
    buffer.set_transform(stamped("world", "robot", 12.0), "test")
    with pytest.raises(ExtrapolationException) as caught:
        buffer.lookup_transform("world", "robot", at(t_s))
    assert str(caught.value) == message
    assert buffer.can_transform("world", "robot", at(t_s)) is False
    assert buffer.can_transform("world", "robot", at(t_s), return_debug_tuple=True) == (False, message)


def test_one_stored_time_is_the_only_time_there_is() -> None:
    buffer = Buffer()
    buffer.set_transform(stamped("world", "robot", 4.0), "test")
    with pytest.raises(
        ExtrapolationException,
        match=(
            r"^Lookup would require extrapolation at time 4\.500000, "
            r"but only time 4\.000000 is in the buffer, when looking up transform from frame "
            r"\[robot\] to frame \[world\]$"
        ),
    ):
        buffer.lookup_transform("world", "robot", at(4.5))


def test_an_unknown_frame_is_a_lookup_exception_in_tf2s_words() -> None:
    buffer = Buffer()
    buffer.set_transform(stamped("world", "turtle2", 1.0), "test")
    with pytest.raises(LookupException) as caught:
        buffer.lookup_transform("turtle2", "turtle1", Time())
    assert str(caught.value) == '"turtle1" passed to lookupTransform argument source_frame does not exist. '
    assert isinstance(caught.value, TransformException)
    assert buffer.can_transform_core("turtle1", "turtle2", Time()) == (
        False,
        'Invalid frame ID "turtle1" passed to canTransform argument target_frame - frame does not exist',
    )


def test_two_trees_without_a_link_are_a_connectivity_exception() -> None:
    buffer = Buffer()
    buffer.set_transform(stamped("map", "robot", 1.0), "test")
    buffer.set_transform(stamped("odom", "wheel", 1.0), "test")
    with pytest.raises(ConnectivityException) as caught:
        buffer.lookup_transform("robot", "wheel", Time())
    assert str(caught.value) == (
        "Could not find a connection between 'robot' and 'wheel' because they are not part of the same "
        "tree.Tf has two or more unconnected trees."
    )


@pytest.mark.parametrize(("frame", "why"), [("", "cannot be empty"), ("/world", "cannot start with a '/'")])
def test_a_frame_name_tf2_does_not_take_is_an_invalid_argument(frame: str, why: str) -> None:
    buffer = Buffer()
    buffer.set_transform(stamped("world", "robot", 1.0), "test")
    with pytest.raises(
        InvalidArgumentException,
        match=f"passed to lookupTransform argument target_frame - in tf2 frame_ids {why}",
    ):
        buffer.lookup_transform(frame, "robot", Time())


def test_data_older_than_the_cache_time_goes_and_is_then_refused() -> None:
    buffer = Buffer(cache_time=Duration(seconds=2.0))
    for t_s in (1.0, 2.0, 3.0, 4.0):
        assert buffer.set_transform(stamped("world", "robot", t_s, (t_s, 0.0, 0.0)), "test")
    assert buffer.set_transform(stamped("world", "robot", 5.0, (5.0, 0.0, 0.0)), "test")
    with pytest.raises(ExtrapolationException, match=r"earliest data is at time 2\.000000"):
        buffer.lookup_transform("world", "robot", at(1.5))
    assert xyz(buffer.lookup_transform("world", "robot", at(2.5))) == pytest.approx((2.5, 0.0, 0.0))
    assert not buffer.set_transform(stamped("world", "robot", 2.5), "test")  # behind 5 s - 2 s
    with pytest.raises(ExtrapolationException, match=r"earliest data is at time 3\.000000"):
        buffer.lookup_transform("world", "robot", at(2.5))  # that insert pruned up to 3 s


@pytest.mark.parametrize(
    ("transform", "reason"),
    [
        (stamped("robot", "robot", 1.0), "TF_SELF_TRANSFORM"),
        (stamped("world", "", 1.0), "TF_NO_CHILD_FRAME_ID"),
        (stamped("", "robot", 1.0), "TF_NO_FRAME_ID"),
        (stamped("world", "robot", 1.0, (math.nan, 0.0, 0.0)), "TF_NAN_INPUT"),
        (stamped("world", "robot", 1.0, q=(0.0, 0.0, 0.0, 2.0)), "TF_DENORMALIZED_QUATERNION"),
    ],
)
def test_a_transform_tf2_would_ignore_is_refused_and_logged_saying_why(
    transform: object, reason: str
) -> None:
    buffer = Buffer()
    logged: list[str] = []
    buffer.log_error = logged.append
    assert buffer.set_transform(transform, "the test") is False  # type: ignore[arg-type]
    assert len(logged) == 1 and logged[0].startswith(f"{reason}: Ignoring transform")
    assert "robot" not in buffer.all_frames_as_string()


def test_frames_describe_themselves_as_tf2s_yaml() -> None:
    buffer = Buffer()
    buffer.set_transform(stamped("world", "robot", 1.0), "tb3")
    buffer.set_transform(stamped("world", "robot", 3.0), "tb3")
    assert buffer.all_frames_as_yaml() == (
        "robot: \n  parent: 'world'\n  broadcaster: 'tb3'\n  rate: 1.000\n"
        "  most_recent_transform: 3.000000\n  oldest_transform: 1.000000\n  buffer_length: 2.000\n"
    )
    assert Buffer().all_frames_as_yaml() == "[]"


def test_clear_forgets_moving_frames_but_not_static_ones() -> None:
    buffer = Buffer()
    buffer.set_transform(stamped("world", "robot", 1.0), "test")
    buffer.set_transform_static(stamped("world", "mast", 0.0), "test")
    buffer.clear()
    assert not buffer.can_transform("world", "robot", Time())
    assert buffer.can_transform("world", "mast", Time())
