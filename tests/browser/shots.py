"""For the browser tests: what a screenshot of the lab page shows, by colour classes in the 3D
canvas (the drone's hub and arms, the rocket on its pad), and where the page's overlays are."""

from __future__ import annotations

import io
import itertools
import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from PIL import Image
from playwright.sync_api import Page

# Colour classes rather than distances to the scene's nominal colours: SwiftShader shades the hub
# from (0, 120, 0) to (120, 230, 120), and viser draws line segments lighter than given: the blue
# arm (30, 60, 255) comes out about (118, 149, 226), the red one (230, 30, 30) about (238, 114, 107).
GIZMO_PX = 100  # viser's axes gizmo (red, green and blue) in the canvas's bottom-left corner
MIN_HUB_PX, MIN_BLUE_ARM_PX, MIN_RED_ARM_PX = 15, 15, 4  # the least for a drone seen at all
ARM_REACH_PX = 80  # the arms' pixels lie this close to the hub's centroid, at the least ...
ARM_PER_HUB_RADIUS = 4.0  # ... or this many hub radii (arm 1 m, hub 0.3 m): close cameras

# The 3D canvas's rectangle, and which of its points (on a grid of SAMPLE_PX) show the canvas
# itself: not viser's control panel or a 3D label floating over it, nor one of our overlays
# (the HUD lets the pointer through, so elementFromPoint does not see it); the workbench's panes
# that hold the canvas are not overlays.
SAMPLE_PX = 4
SCENE_POINTS_JS = """(step) => {
  const canvas = window.__viserMutable?.canvas
    ?? [...document.querySelectorAll('canvas')].sort((a, b) => b.width * b.height - a.width * a.height)[0];
  const box = canvas.getBoundingClientRect();
  // viser stacks a pointer-catching canvas of the same size over the WebGL one.
  const isScene = (e) => { if (!e || e.tagName !== 'CANVAS') return false; const r = e.getBoundingClientRect();
    return Math.abs(r.left - box.left) < 1 && Math.abs(r.top - box.top) < 1 && Math.abs(r.width - box.width) < 1; };
  const ours = [...document.querySelectorAll('[id^="teleop-"]')].filter((e) => !e.contains(canvas))
    .map((e) => e.getBoundingClientRect());
  const cols = Math.ceil(box.width / step), rows = Math.ceil(box.height / step);
  let shown = '';
  for (let j = 0; j < rows; j++) for (let i = 0; i < cols; i++) {
    const x = box.left + (i + 0.5) * step, y = box.top + (j + 0.5) * step;
    const hidden = !isScene(document.elementFromPoint(x, y))
      || ours.some((r) => x >= r.left && x <= r.right && y >= r.top && y <= r.bottom);
    shown += hidden ? '0' : '1';
  }
  return { box: [box.left, box.top, box.width, box.height], cols, rows, shown };
}"""


@dataclass(frozen=True)
class CanvasShot:
    """The 3D canvas's part of a screenshot, and which of its pixels show the scene."""

    rgb: np.ndarray  # H x W x 3, int16 (so channel differences do not wrap)
    scene: np.ndarray  # H x W bool: not under the GUI or an overlay (HUD, help), nor viser's gizmo

    @classmethod
    def of(cls, page: Page, png: bytes) -> CanvasShot:
        layout = page.evaluate(SCENE_POINTS_JS, SAMPLE_PX)
        image = np.asarray(Image.open(io.BytesIO(png)).convert("RGB")).astype(np.int16)
        x, y, w, h = (round(v) for v in layout["box"])
        rgb = image[y : y + h, x : x + w]
        grid = np.frombuffer(layout["shown"].encode(), dtype=np.uint8).reshape(
            layout["rows"], layout["cols"]
        ) == ord("1")
        scene = np.repeat(np.repeat(grid, SAMPLE_PX, axis=0), SAMPLE_PX, axis=1)[
            : rgb.shape[0], : rgb.shape[1]
        ]
        scene[-GIZMO_PX:, :GIZMO_PX] = False
        return cls(rgb, scene)

    def mask(self, colour_class: Callable[[np.ndarray, np.ndarray, np.ndarray], np.ndarray]) -> np.ndarray:
        r, g, b = self.rgb[..., 0], self.rgb[..., 1], self.rgb[..., 2]
        return colour_class(r, g, b) & self.scene


def hub_green(r: np.ndarray, g: np.ndarray, b: np.ndarray) -> np.ndarray:
    return (g >= 90) & (g - r >= 60) & (g - b >= 60)


def arm_blue(r: np.ndarray, g: np.ndarray, b: np.ndarray) -> np.ndarray:
    return (b >= 150) & (b - r >= 60) & (b - g >= 40)


def red(r: np.ndarray, g: np.ndarray, b: np.ndarray) -> np.ndarray:
    return (r >= 120) & (r - g >= 70) & (r - b >= 50)


def rocket_white(r: np.ndarray, g: np.ndarray, b: np.ndarray) -> np.ndarray:
    """The body (235, 235, 240), shaded: light, grey, and not the page's white background."""
    hi, lo = np.maximum(np.maximum(r, g), b), np.minimum(np.minimum(r, g), b)
    return (lo >= 140) & (hi <= 245) & (hi - lo <= 35)


def pad_grey(r: np.ndarray, g: np.ndarray, b: np.ndarray) -> np.ndarray:
    """The pad (110, 110, 120), shaded from about (68, 67, 82) to (110, 110, 127)."""
    hi, lo = np.maximum(np.maximum(r, g), b), np.minimum(np.minimum(r, g), b)
    return (lo >= 40) & (hi <= 150) & (hi - lo <= 35)


def blobs(mask: np.ndarray) -> list[list[tuple[int, int]]]:
    """The 8-connected regions of ``mask``, each as its (row, column) pixels."""
    left = {(int(r), int(c)) for r, c in zip(*np.nonzero(mask), strict=True)}
    found: list[list[tuple[int, int]]] = []
    while left:
        stack, blob = [left.pop()], []
        while stack:
            r, c = stack.pop()
            blob.append((r, c))
            for n in ((r + dr, c + dc) for dr in (-1, 0, 1) for dc in (-1, 0, 1)):
                if n in left:
                    left.remove(n)
                    stack.append(n)
        found.append(blob)
    return found


def largest_blob(mask: np.ndarray) -> np.ndarray:
    """The (row, column) pixels of the largest 8-connected region of ``mask``."""
    best = max(blobs(mask), key=len, default=[])
    return np.array(best, dtype=float).reshape(-1, 2)


@dataclass(frozen=True)
class DroneSeen:
    hub_px: int
    blue_px: int  # blue-arm pixels within reach of the hub
    red_px: int
    centre: tuple[float, float]  # the hub's centroid (column, row) in canvas pixels; rows grow downwards


def find_drone(shot: CanvasShot) -> DroneSeen:
    hub = largest_blob(shot.mask(hub_green))
    if not len(hub):
        return DroneSeen(0, 0, 0, (math.nan, math.nan))
    row, col = hub.mean(axis=0)
    rows, cols = np.indices(shot.scene.shape)
    reach = max(ARM_REACH_PX, ARM_PER_HUB_RADIUS * math.sqrt(len(hub) / math.pi))
    near = (rows - row) ** 2 + (cols - col) ** 2 <= reach**2
    blue, red_ = int((shot.mask(arm_blue) & near).sum()), int((shot.mask(red) & near).sum())
    return DroneSeen(len(hub), blue, red_, (float(col), float(row)))


def assert_drone_seen(
    seen: DroneSeen, name: str, least: tuple[int, int, int] = (MIN_HUB_PX, MIN_BLUE_ARM_PX, MIN_RED_ARM_PX)
) -> None:
    """At least ``least`` = (hub, blue arm, red arm) pixels of the drone."""
    hub, blue, red_ = least
    assert seen.hub_px >= hub, f"{name}: hub smaller than {hub} px ({seen})"
    assert seen.blue_px >= blue, f"{name}: blue arm smaller than {blue} px by the hub ({seen})"
    assert seen.red_px >= red_, f"{name}: red arm smaller than {red_} px by the hub ({seen})"


MIN_NOSE_ROWS, MIN_BODY_ROWS, MIN_PAD_ROWS = 4, 15, 3
MAX_GAP_ROWS = 3  # anti-aliased edges between two parts
MIN_ROCKET_COLUMNS = 3
FIN_REACH_PX = 30
MIN_FIN_PX = 3


def rocket_columns(shot: CanvasShot) -> dict[int, tuple[int, int]]:
    """Columns that read, top to bottom, red nose → white body → grey pad (a rocket standing on
    it), each with its body's first and last row."""
    labels = np.zeros(shot.scene.shape, dtype=np.int8)  # 0 other, 1 red, 2 white, 3 pad
    labels[shot.mask(red)] = 1
    labels[shot.mask(rocket_white)] = 2
    labels[shot.mask(pad_grey)] = 3
    wanted = [(1, MIN_NOSE_ROWS), (2, MIN_BODY_ROWS), (3, MIN_PAD_ROWS)]
    found = {}
    for col in range(labels.shape[1]):
        runs: list[list[int]] = []  # [label, first row, rows], top to bottom, thin gaps dropped
        row = 0
        for label, group in itertools.groupby(labels[:, col].tolist()):
            rows = len(list(group))
            if runs and runs[-1][0] == label:
                runs[-1][2] = row + rows - runs[-1][1]
            elif label or rows > MAX_GAP_ROWS:  # a thin gap is an anti-aliased edge between parts
                runs.append([label, row, rows])
            row += rows
        for i in range(len(runs) - 2):
            if all(
                runs[i + k][0] == label and runs[i + k][2] >= rows for k, (label, rows) in enumerate(wanted)
            ):
                found[col] = (runs[i + 1][1], runs[i + 1][1] + runs[i + 1][2] - 1)
                break
    return found


def assert_rocket_on_pad(shot: CanvasShot, name: str) -> None:
    """A red nose over a white body on the grey pad, and red fins on both sides of the body's foot."""
    columns = rocket_columns(shot)
    assert len(columns) >= MIN_ROCKET_COLUMNS, f"{name}: no column reads nose → body → pad ({columns})"
    axis = int(np.median(list(columns)))
    top, bottom = columns[min(columns, key=lambda c: abs(c - axis))]
    foot = slice(max(bottom - (bottom - top) * 2 // 5, 0), bottom + 4)  # fins: the lowest fifth of the rocket
    reds = shot.mask(red)
    left = int(reds[foot, max(axis - FIN_REACH_PX, 0) : axis - 3].sum())
    right = int(reds[foot, axis + 4 : axis + FIN_REACH_PX].sum())
    assert left >= MIN_FIN_PX and right >= MIN_FIN_PX, (
        f"{name}: no fins on both sides (left {left}, right {right} px)"
    )
