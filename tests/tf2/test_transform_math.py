"""tf2_ros' transform math: exact geometric properties of composition, inversion and slerp."""

from __future__ import annotations

import math

import numpy as np
import pytest
from tf2_ros._transform_math import RigidTransform, interpolate, quaternion_multiply, rotate, slerp


def about_z(angle_rad: float) -> np.ndarray:
    return np.array([0.0, 0.0, math.sin(angle_rad / 2), math.cos(angle_rad / 2)])


def random_transform(rng: np.random.Generator) -> RigidTransform:
    q = rng.normal(size=4)
    return RigidTransform(rng.uniform(-5, 5, size=3), q / np.linalg.norm(q))


def angle_between(a: np.ndarray, b: np.ndarray) -> float:
    """The rotation angle (rad) taking unit quaternion ``a`` to ``b``."""
    return 2.0 * math.acos(min(1.0, abs(float(np.dot(a, b)))))


def test_a_transform_composed_with_its_inverse_is_the_identity_either_way() -> None:
    rng = np.random.default_rng(7)
    for _ in range(20):
        t = random_transform(rng)
        for product in (t @ t.inverse(), t.inverse() @ t):
            np.testing.assert_allclose(product.translation, np.zeros(3), atol=1e-12)
            assert abs(abs(product.rotation[3]) - 1.0) < 1e-12  # w = ±1: no rotation


def test_composition_is_associative_and_applies_the_right_hand_transform_first() -> None:
    rng = np.random.default_rng(11)
    a, b, c = (random_transform(rng) for _ in range(3))
    p = rng.normal(size=3)
    np.testing.assert_allclose((a @ b).apply(p), a.apply(b.apply(p)), atol=1e-12)
    np.testing.assert_allclose(((a @ b) @ c).apply(p), (a @ (b @ c)).apply(p), atol=1e-12)


def test_a_quarter_turn_about_z_takes_x_to_y_and_keeps_lengths() -> None:
    q = about_z(math.pi / 2)
    np.testing.assert_allclose(rotate(q, np.array([1.0, 0.0, 0.0])), [0.0, 1.0, 0.0], atol=1e-15)
    v = np.array([3.0, -4.0, 12.0])
    assert np.linalg.norm(rotate(quaternion_multiply(q, about_z(0.3)), v)) == pytest.approx(13.0, abs=1e-12)


def test_slerp_halfway_between_no_turn_and_a_quarter_turn_is_an_eighth_turn() -> None:
    np.testing.assert_allclose(
        slerp(about_z(0.0), about_z(math.pi / 2), 0.5), about_z(math.pi / 4), atol=1e-15
    )


def test_slerp_turns_at_a_constant_rate_and_ends_on_both_quaternions() -> None:
    rng = np.random.default_rng(3)
    q0, q1 = (q / np.linalg.norm(q) for q in rng.normal(size=(2, 4)))
    total = angle_between(q0, q1)
    for ratio in (0.0, 0.1, 0.25, 0.5, 0.9, 1.0):
        q = slerp(q0, q1, ratio)
        assert np.linalg.norm(q) == pytest.approx(1.0, abs=1e-12)
        assert angle_between(q0, q) == pytest.approx(ratio * total, abs=1e-7)


def test_slerp_takes_the_short_way_whichever_sign_the_second_quaternion_has() -> None:
    q0, q1 = about_z(0.0), about_z(math.radians(60))
    np.testing.assert_allclose(slerp(q0, -q1, 0.5), about_z(math.radians(30)), atol=1e-15)


def test_interpolated_translation_moves_in_a_straight_line() -> None:
    a = RigidTransform(np.array([0.0, 0.0, 0.0]), about_z(0.0))
    b = RigidTransform(np.array([4.0, -2.0, 8.0]), about_z(math.pi))
    mid = interpolate(a, b, 0.25)
    np.testing.assert_allclose(mid.translation, [1.0, -0.5, 2.0])
    np.testing.assert_allclose(mid.rotation, about_z(math.pi / 4), atol=1e-15)
