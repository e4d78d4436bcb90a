"""Camera views of the page: one per lab (Rocket, Quadrotor), switched and followed in the page.

The page (web/src/lab/scene.ts) asks for them at ``GET /page/views``, opens on the view the browser
remembers, else on the one suggested here, and moves viser's camera itself: a switch costs no
round trip and leaves the keyboard where it was.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from typing_extensions import TypedDict

Vec3 = tuple[float, float, float]


class FollowJson(TypedDict):
    """A followed vehicle as the page reads it: viser scene node names, and the camera's offset
    from the vehicle (m, world frame, z up)."""

    node: str
    offset: Vec3
    setpoint: str | None
    trail: str | None


class ViewJson(TypedDict):
    """A camera view as the page reads it (m, world frame, z up)."""

    name: str
    position: Vec3
    look_at: Vec3
    follow: FollowJson | None


class PageViews(TypedDict):
    """``GET /page/views``: every view, and the one a page with no remembered choice opens on."""

    views: list[ViewJson]
    suggested: str | None


@dataclass(frozen=True)
class Follow:
    """A vehicle the camera can follow, and where the camera sits relative to it. The page draws
    that node from the pose stream between the server's updates, and the setpoint marker and trail
    named here are the ones it moves on a key and shortens when it must draw less."""

    node: str  # viser scene node name, e.g. "/drone_lab/drone"
    offset_m: Vec3  # camera position minus the node's position, world frame (z up)
    setpoint_node: str | None = None
    trail_node: str | None = None  # line segments, newest first


@dataclass(frozen=True)
class CameraView:
    """A fixed camera (world frame, metres, z up), and optionally a node to follow instead."""

    name: str
    position: Vec3
    look_at: Vec3
    follow: Follow | None = None
    # While this returns True the lab behind the view is under way (the rocket counting down),
    # so a page with no remembered choice opens on it.
    busy: Callable[[], bool] | None = None

    def to_json(self) -> ViewJson:
        f = self.follow
        follow: FollowJson | None = None
        if f is not None:
            follow = {
                "node": f.node,
                "offset": f.offset_m,
                "setpoint": f.setpoint_node,
                "trail": f.trail_node,
            }
        return {"name": self.name, "position": self.position, "look_at": self.look_at, "follow": follow}


class ViewRegistry:
    """The views, in the order the labs registered them."""

    def __init__(self) -> None:
        self._views: dict[str, CameraView] = {}

    def add(self, view: CameraView) -> None:
        self._views[view.name] = view

    def __getitem__(self, name: str) -> CameraView:
        return self._views[name]

    def __contains__(self, name: object) -> bool:
        return name in self._views

    def __len__(self) -> int:
        return len(self._views)

    def names(self) -> list[str]:
        return list(self._views)

    def suggested(self) -> str | None:
        """The view a student most likely wants: a lab under way (the rocket before lift-off),
        else a lab that is always live (the drone), else the first."""
        views = list(self._views.values())
        for view in views:
            if view.busy is not None and view.busy():
                return view.name
        for view in views:
            if view.busy is None:
                return view.name
        return views[0].name if views else None

    def to_json(self) -> PageViews:
        return {"views": [v.to_json() for v in self._views.values()], "suggested": self.suggested()}
