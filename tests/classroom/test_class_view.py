"""The instructor's 3D view: every world's drone in one viser scene, an arena tile per
world; its page and WebSocket open for the instructor only. Through the real app, on a manual
clock; the view's viser server runs on loopback."""

from __future__ import annotations

import math
from collections.abc import Iterator

import pytest
import viser
from fastapi.testclient import TestClient
from support.ws import refusal

from api.errors import CloseCode
from node_runtime.bus import ManualClock
from server.app import create_app
from server.peripherals.viewer.class_view import COLUMNS, GONE_COLOR, TILE_M, ClassView, tile_origin

from .test_classroom_api import advance, auth, class_settings, classroom, join

VISER_PROTOCOL = f"viser-v{viser.__version__}"


# -- the scene -----------------------------------------------------------------------------------
@pytest.fixture
def view() -> Iterator[ClassView]:
    class_view = ClassView()
    yield class_view
    class_view.stop()


def drone_at(view: ClassView, world: str) -> tuple[float, float, float]:
    handle = view._tiles[world].drone
    return tuple(float(v) for v in handle.position)  # type: ignore[return-value]


def test_tiles_are_laid_out_in_rows_a_tile_apart() -> None:
    assert tile_origin(0) == (0.0, 0.0)
    assert tile_origin(1) == (TILE_M, 0.0)
    assert tile_origin(COLUMNS) == (0.0, -TILE_M)
    assert tile_origin(COLUMNS + 2) == (2 * TILE_M, -TILE_M)


def test_each_world_gets_a_tile_and_its_drone_is_drawn_where_it_flies_in_that_tile(view: ClassView) -> None:
    view.show({"ada": ("Ada", [0.0, 0.0, 3.0]), "bob": ("Bob", [5.0, 5.0, 10.0])})
    assert view.worlds == {"ada": 0, "bob": 1}
    assert drone_at(view, "ada") == pytest.approx((0.0, 0.0, 3.0))
    assert drone_at(view, "bob") == pytest.approx((TILE_M + 5.0, 5.0, 10.0))  # two drones never overlap
    view.show({"ada": ("Ada", [1.0, -2.0, 4.0]), "bob": ("Bob", [5.0, 5.0, 10.0])})
    assert drone_at(view, "ada") == pytest.approx((1.0, -2.0, 4.0))
    assert "Ada" in view._tiles["ada"].drone_label.text and "4.0 m" in view._tiles["ada"].drone_label.text


def test_a_world_that_leaves_frees_its_tile_and_the_next_to_join_takes_it(view: ClassView) -> None:
    view.show({"ada": ("Ada", [0.0, 0.0, 3.0]), "bob": ("Bob", [0.0, 0.0, 3.0])})
    view.show({"bob": ("Bob", [0.0, 0.0, 3.0])})
    assert view.worlds == {"bob": 1}  # bob stays where the instructor saw him
    view.show({"bob": ("Bob", [0.0, 0.0, 3.0]), "cy": ("Cy", [0.0, 0.0, 3.0])})
    assert view.worlds == {"bob": 1, "cy": 0}
    position, look_at = view.framing()  # a page that opens the view sees both tiles in use
    assert look_at == pytest.approx((TILE_M / 2, 0.0, 0.0))
    assert position[1] < look_at[1] and position[2] > 0.0  # from the south, above
    assert "**2 worlds**" in view._summary.content and "Cy (`cy`)" in view._summary.content


def test_a_drone_with_no_position_is_marked_and_keeps_its_place_until_one_comes(view: ClassView) -> None:
    view.show({"ada": ("Ada", [2.0, 0.0, 3.0])})
    view.show({"ada": ("Ada", None)})  # its worker is gone
    tile = view._tiles["ada"]
    assert tuple(tile.drone.color) == GONE_COLOR and "no position" in tile.drone_label.text
    assert drone_at(view, "ada") == pytest.approx((2.0, 0.0, 3.0))
    view.show({"ada": ("Ada", [0.0, 0.0, 0.0])})  # started again at home
    assert tuple(tile.drone.color) != GONE_COLOR and drone_at(view, "ada") == pytest.approx((0.0, 0.0, 0.0))
    view.show({"ada": ("Ada", [math.nan, 0.0, 0.0])})  # never drawn at NaN
    assert drone_at(view, "ada") == pytest.approx((0.0, 0.0, 0.0))


# -- through the app -----------------------------------------------------------------------------
@pytest.fixture
def clock() -> ManualClock:
    return ManualClock(1_000.0)


@pytest.fixture
def client(clock: ManualClock) -> Iterator[TestClient]:
    with TestClient(create_app(class_settings(viewer=True, max_worlds=2), clock)) as test_client:
        yield test_client


def test_the_class_view_shows_each_worlds_drone_where_its_gps_says(
    client: TestClient, clock: ManualClock
) -> None:
    ada, bob = join(client, "Ada"), join(client, "Bob")
    reply = client.post(
        "/api/publish",
        headers=auth(ada),
        json={"topic": "/uav/input/position", "msg": {"x": 2.0, "y": 1.0, "z": 5.0}},
    )
    assert reply.status_code == 200, reply.text
    advance(client, clock, 8.0)
    drones = classroom(client).drones()
    for world, token in (("ada", ada), ("bob", bob)):
        latest = client.get("/api/topics/uav/sensors/gps", headers=auth(token)).json()["latest"]["pose"][
            "position"
        ]
        student, position = drones[world]
        assert student == world.title() and position is not None
        assert position == pytest.approx([latest["x"], latest["y"], latest["z"]], abs=1e-3)
    assert drones["ada"][1] is not None and drones["ada"][1][2] > 4.0  # ada's climbed; bob's hovers at home
    assert drones["bob"][1] is not None and abs(drones["bob"][1][2] - 3.0) < 0.5
    view = classroom(client).view
    assert view is not None
    view.show(drones)
    assert drone_at(view, "ada") == pytest.approx(tuple(drones["ada"][1]), abs=1e-3)


def test_only_the_instructor_opens_the_class_view(client: TestClient) -> None:
    student = join(client, "Ada")
    instructor = classroom(client).instructor_token
    page = client.get("/instructor/view", headers=auth(instructor))
    assert page.status_code == 200 and "<html" in page.text.lower()
    assert page.headers["content-security-policy"] == "frame-ancestors 'self'"  # no other site frames it
    assert "/static/build/lab.js" not in page.text  # nothing on it flies a drone
    assert client.get("/instructor/view", headers=auth(student)).status_code == 401
    assert client.get("/instructor/view").status_code == 401
    refused = refusal(client, "/instructor/view", headers=auth(student), subprotocols=[VISER_PROTOCOL])
    assert refused.code == CloseCode.UNAUTHORIZED and "instructor" in refused.reason
    with client.websocket_connect(
        "/instructor/view", headers=auth(instructor), subprotocols=[VISER_PROTOCOL]
    ) as ws:
        assert ws.receive_bytes()  # viser's scene, through the proxy


def test_a_single_lab_has_no_class_view() -> None:
    with TestClient(create_app(class_settings(classroom=False, viewer=False))) as single:
        assert single.get("/instructor/view").status_code == 404
