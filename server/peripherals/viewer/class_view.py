"""The instructor's 3D view: every world's drone in one viser scene.

Each world gets an arena tile of its own, laid out in rows of ``COLUMNS`` (the worlds all fly
around the same origin, so drawn in one place their drones would sit on one another at home). A
tile is the world's 20 m arena with its student's name; its drone is a sphere that carries a label
with the name and altitude. The instructor's page shows it in a frame (``/instructor/view``),
proxied like a student's 3D view; ``run_class_view`` moves the drones from each world's latest GPS
fix while the page is open, so it costs nothing when nobody looks. The class server hands it its
worlds' drones (``DroneSource``): this layer knows nothing of worlds, labs or workers.
"""

from __future__ import annotations

import asyncio
import logging
import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any, Protocol

from node_runtime.bus import Clock
from server.peripherals.viewer.display import Display

log = logging.getLogger("classroom.view")

ARENA_M = 20.0
TILE_M = 26.0  # an arena and a walkway
COLUMNS = 6
DRONE_RADIUS_M = 1.0  # larger than the drone, so a class of small arenas still shows each one
MOVED_M = 0.005  # a drone that moved less is not sent again
DRONE_COLOR = (40, 170, 90)
GONE_COLOR = (200, 60, 60)  # a world whose drone is not known now (its worker is gone)
VIEW_HZ = 10.0  # the instructor's 3D view: local worlds' drones
REMOTE_VIEW_HZ = 2.0  # and world workers' (one call per worker)
Position = list[float] | None  # a drone's x, y, z in its world (m), None when not known now


@dataclass
class _Tile:
    slot: int
    label: str
    nodes: list[Any]
    drone: Any
    drone_label: Any
    shown: tuple[float, float, float] | None = None  # the drone's position last sent, in its world
    lost: bool = False


def tile_origin(slot: int) -> tuple[float, float]:
    """Where tile ``slot`` (0, 1, ...) is centred: rows of COLUMNS going +x, then rows going -y."""
    row, col = divmod(slot, COLUMNS)
    return col * TILE_M, -row * TILE_M


class ClassView:
    """One viser server with a tile per world; ``show`` brings it in line with the worlds."""

    def __init__(self, loop: asyncio.AbstractEventLoop | None = None) -> None:
        self.display = Display(loop)
        self.display.add_view(
            "Class", (2.5 * TILE_M, -2.2 * TILE_M, 2.0 * TILE_M), (2.5 * TILE_M, -0.5 * TILE_M, 0.0)
        )
        self._tiles: dict[str, _Tile] = {}
        with self.display.gui.add_folder("Class"):
            self._summary = self.display.gui.add_markdown("No student has joined yet.")
        self.display.server.on_client_connect(self._frame_all)

    def framing(self) -> tuple[tuple[float, float, float], tuple[float, float, float]]:
        """A camera position and the point it looks at that show every tile in use, from the
        south and above."""
        slots = [t.slot for t in list(self._tiles.values())] or [0]
        xs = [tile_origin(s)[0] for s in slots]
        ys = [tile_origin(s)[1] for s in slots]
        cx, cy = (min(xs) + max(xs)) / 2, (min(ys) + max(ys)) / 2
        extent = max(max(xs) - min(xs), max(ys) - min(ys)) + TILE_M
        return (cx, cy - 0.65 * extent, 0.5 * extent), (cx, cy, 0.0)

    def _frame_all(self, client: Any) -> None:  # viser's thread: a page opened the view
        position, look_at = self.framing()
        with client.atomic():
            client.camera.position = position
            client.camera.look_at = look_at
            client.camera.up_direction = (0.0, 0.0, 1.0)

    @property
    def worlds(self) -> dict[str, int]:
        """Each world shown, and its tile's slot."""
        return {name: tile.slot for name, tile in self._tiles.items()}

    def watched(self) -> bool:
        return self.display.watched()

    def show(self, worlds: dict[str, tuple[str, list[float] | None]]) -> None:
        """``worlds``: each world's student and its drone's position (None when not known now)."""
        for name in [n for n in self._tiles if n not in worlds]:
            for node in self._tiles.pop(name).nodes:
                node.remove()
        for name, (student, position) in worlds.items():
            tile = self._tiles.get(name) or self._add(name, student)
            self._place(tile, position)
        summary = self._summary_text(worlds)
        if summary != self._summary.content:
            self._summary.content = summary

    def _add(self, name: str, student: str) -> _Tile:
        taken = {t.slot for t in self._tiles.values()}
        slot = next(s for s in range(len(taken) + 1) if s not in taken)
        x, y = tile_origin(slot)
        scene = self.display.scene
        root = f"/class/{name}"
        ground = scene.add_grid(
            f"{root}/ground",
            width=ARENA_M,
            height=ARENA_M,
            cell_size=5.0,
            section_size=ARENA_M / 2,
            position=(x, y, 0.0),
        )
        name_label = scene.add_label(
            f"{root}/name", student, position=(x - ARENA_M / 2, y + ARENA_M / 2 + 1.0, 0.0)
        )
        drone = scene.add_icosphere(
            f"{root}/drone", radius=DRONE_RADIUS_M, color=DRONE_COLOR, position=(x, y, 0.0)
        )
        drone_label = scene.add_label(f"{root}/drone/label", student, position=(1.3, 0.0, 1.3))
        tile = _Tile(slot, student, [ground, name_label, drone], drone, drone_label)
        self._tiles[name] = tile
        return tile

    def _place(self, tile: _Tile, position: list[float] | None) -> None:
        if position is None or not all(math.isfinite(v) for v in position):
            if not tile.lost:
                tile.drone.color = GONE_COLOR
                tile.drone_label.text = f"{tile.label}: no position"
                tile.lost = True
            return
        px, py, pz = position
        if tile.lost:
            tile.drone.color = DRONE_COLOR
            tile.lost = False
        elif tile.shown is not None and math.dist(tile.shown, (px, py, pz)) < MOVED_M:
            return
        x, y = tile_origin(tile.slot)
        tile.drone.position = (x + px, y + py, pz)
        tile.drone_label.text = f"{tile.label} · {pz:.1f} m"
        tile.shown = (px, py, pz)

    @staticmethod
    def _summary_text(worlds: dict[str, tuple[str, list[float] | None]]) -> str:
        if not worlds:
            return "No student has joined yet."
        s = "s" if len(worlds) != 1 else ""
        lines = [f"**{len(worlds)} world{s}**, an arena each, in rows of {COLUMNS} in join order:"]
        for name, (student, position) in worlds.items():
            lines.append(f"- {student} (`{name}`){'' if position is not None else ': no position now'}")
        return "\n".join(lines)

    def stop(self) -> None:
        self.display.stop()


class DroneSource(Protocol):
    """Where the class view's drones are: those the class server can read itself, and those it
    must ask its world workers for."""

    def drones(self, remote: Mapping[str, Position]) -> dict[str, tuple[str, Position]]:
        """Each world's student and drone, the workers' worlds' taken from ``remote``."""
        ...

    async def remote_drones(self) -> dict[str, Position]:
        """The drones of the worlds on world workers, by world, as their workers report them now."""
        ...


async def run_class_view(view: ClassView, clock: Clock, source: DroneSource) -> None:
    """Move the class view's drones while the instructor's page shows it: local worlds' at
    VIEW_HZ from their latest GPS fix, workers' as often as REMOTE_VIEW_HZ asks them."""
    remote_at = -math.inf
    remote: dict[str, Position] = {}
    while True:
        await asyncio.sleep(1.0 / VIEW_HZ)
        if not view.watched():
            continue
        try:
            now = clock.now()
            if now - remote_at >= 1.0 / REMOTE_VIEW_HZ or now < remote_at:
                remote_at = now
                remote = await source.remote_drones()
            view.show(source.drones(remote))
        except Exception:  # the view must outlive any one round
            log.exception("updating the class view failed; trying again")
