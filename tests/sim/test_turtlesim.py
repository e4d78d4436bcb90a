"""sim/turtlesim: turtlesim's kinematics, its window's edges, teleports, pens and the canvas."""

from __future__ import annotations

import math

import pytest

from sim.turtlesim import (
    CENTER_M,
    COMMAND_TIMEOUT_S,
    SIZE_M,
    UPDATE_PERIOD_S,
    Rgb,
    Teleport,
    TurtleWorld,
    normalize_angle,
)

PEN = Rgb(0xB3, 0xB8, 0xFF)
WHITE = Rgb(255, 255, 255)


def steps(world: TurtleWorld, count: int, start_s: float = 0.0) -> float:
    """``count`` frames from ``start_s``; the time after the last."""
    now = start_s
    for _ in range(count):
        now += UPDATE_PERIOD_S
        world.step(now)
    return now


def test_turtlesim_first_turtle_is_turtle1_in_the_middle_of_an_11_m_window() -> None:
    world = TurtleWorld()
    assert world.spawn("", CENTER_M, CENTER_M, 0.0, 0.0) == "turtle1"
    assert round(SIZE_M, 6) == 11.088889
    reading = world.step(UPDATE_PERIOD_S)["turtle1"]
    assert (reading.x_m, reading.y_m, reading.theta_rad) == pytest.approx((5.544444, 5.544444, 0.0), abs=1e-6)
    assert reading.color == WHITE  # nothing drawn where it stands


def test_turtlesim_velocity_integrates_along_the_heading_at_the_frame_period() -> None:
    world = TurtleWorld()
    world.spawn("t", 2.0, 2.0, math.pi / 2, 0.0)
    world.turtles["t"].command(1.0, 0.0, 0.0, 0.0)
    steps(world, 50)  # 0.8 s of frames
    turtle = world.turtles["t"]
    assert (turtle.x_m, turtle.y_m) == pytest.approx((2.0, 2.8), abs=1e-6)  # pi/2 as a float32
    reading = world.step(51 * UPDATE_PERIOD_S)["t"]
    assert reading.linear_velocity_mps == 1.0 and reading.angular_velocity_radps == 0.0


def test_turtlesim_a_command_older_than_a_second_stops_the_turtle() -> None:
    world = TurtleWorld()
    world.spawn("t", 5.0, 5.0, 0.0, 0.0)
    world.turtles["t"].command(2.0, 0.0, 1.0, 0.0)
    now = steps(world, int(COMMAND_TIMEOUT_S / UPDATE_PERIOD_S))  # 0.992 s: still moving
    moved_x = world.turtles["t"].x_m
    assert moved_x > 6.5
    now = steps(world, 2, now)  # past 1 s: stopped, and stays
    stopped = world.step(now + UPDATE_PERIOD_S)["t"]
    assert (stopped.linear_velocity_mps, stopped.angular_velocity_radps) == (0.0, 0.0)
    assert world.step(now + 2 * UPDATE_PERIOD_S)["t"].x_m == stopped.x_m


def test_turtlesim_theta_wraps_into_minus_pi_to_pi() -> None:
    assert normalize_angle(math.pi) == pytest.approx(-math.pi)
    assert normalize_angle(3 * math.pi / 2) == pytest.approx(-math.pi / 2)
    world = TurtleWorld()
    world.spawn("t", 5.0, 5.0, 3.13, 0.0)
    world.turtles["t"].command(0.0, 0.0, 2.0, 0.0)
    theta = world.step(UPDATE_PERIOD_S)["t"].theta_rad
    assert theta == pytest.approx(3.13 + 2.0 * UPDATE_PERIOD_S - 2 * math.pi)


def test_turtlesim_the_wall_clamps_and_says_where_from() -> None:
    world = TurtleWorld()
    world.spawn("t", SIZE_M - 0.01, 1.0, 0.0, 0.0)
    world.turtles["t"].command(2.0, 0.0, 0.0, 0.0)
    reading = world.step(UPDATE_PERIOD_S)["t"]
    assert reading.x_m == SIZE_M
    assert reading.clamped_from == pytest.approx((SIZE_M - 0.01 + 2.0 * UPDATE_PERIOD_S, SIZE_M - 1.0))


def test_turtlesim_teleports_wait_for_the_next_frame_and_run_in_order() -> None:
    world = TurtleWorld()
    world.spawn("t", 5.0, 5.0, 0.0, 0.0)
    turtle = world.turtles["t"]
    turtle.teleports += [
        Teleport(1.0, 2.0, 0.0),
        Teleport(theta_rad=math.pi / 2, linear_m=3.0, relative=True),
    ]
    assert (turtle.x_m, turtle.y_m) == (5.0, 5.0)
    reading = world.step(UPDATE_PERIOD_S)["t"]
    assert (reading.x_m, reading.y_m, reading.theta_rad) == pytest.approx((1.0, 5.0, math.pi / 2))
    assert turtle.teleports == []


def test_turtlesim_the_pen_draws_the_path_the_sensor_then_reads() -> None:
    world = TurtleWorld()
    world.spawn("a", 2.0, 2.0, 0.0, 0.0)
    world.turtles["a"].teleports.append(Teleport(6.0, 2.0, 0.0))
    world.step(UPDATE_PERIOD_S)
    world.spawn("b", 4.0, 2.0, 0.0, 0.0)  # on a's line
    world.spawn("c", 4.0, 4.0, 0.0, 0.0)  # off it
    readings = world.step(2 * UPDATE_PERIOD_S)
    assert (readings["b"].color, readings["c"].color) == (PEN, WHITE)
    world.turtles["c"].set_pen(255, 0, 0, 5, off=False)
    world.turtles["c"].teleports.append(Teleport(4.0, 2.0, 0.0))
    world.step(3 * UPDATE_PERIOD_S)
    assert world.step(4 * UPDATE_PERIOD_S)["b"].color == Rgb(255, 0, 0)
    world.canvas.clear()
    assert world.step(5 * UPDATE_PERIOD_S)["b"].color == WHITE


def test_turtlesim_a_lifted_pen_draws_nothing() -> None:
    world = TurtleWorld()
    world.spawn("a", 2.0, 2.0, 0.0, 0.0)
    world.turtles["a"].set_pen(0, 0, 0, 0, off=True)
    world.turtles["a"].teleports.append(Teleport(6.0, 2.0, 0.0))
    world.step(UPDATE_PERIOD_S)
    world.spawn("b", 4.0, 2.0, 0.0, 0.0)
    assert world.step(2 * UPDATE_PERIOD_S)["b"].color == WHITE


def test_turtlesim_names_spawn_kill_and_reset() -> None:
    world = TurtleWorld()
    assert world.spawn("", CENTER_M, CENTER_M, 0.0, 0.0) == "turtle1"
    assert world.spawn("turtle2", 1.0, 1.0, 0.0, 0.0) == "turtle2"
    assert world.spawn("", 1.0, 1.0, 0.0, 0.0) == "turtle3"  # turtle2 is taken
    assert world.spawn("turtle2", 3.0, 3.0, 0.0, 0.0) is None
    assert world.kill("turtle1") and not world.kill("turtle1")
    world.reset()
    assert world.turtles == {}
    assert world.spawn("", CENTER_M, CENTER_M, 0.0, 0.0) == "turtle1"
