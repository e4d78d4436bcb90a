"""A drone's track drawn on the server as a small SVG: seen from the top (x, y) and from the side
(x, z), with the target marked. The report's picture when the page sent no capture."""

from __future__ import annotations

import base64
from collections.abc import Sequence
from html import escape

PANEL = 240  # px, each view's square
PAD = 24


def _scale(values: list[float]) -> tuple[float, float]:
    low, high = min(values), max(values)
    span = max(high - low, 1.0) * 1.15
    middle = (low + high) / 2
    return middle - span / 2, span


def _panel(points: list[tuple[float, float]], target: tuple[float, float] | None, x0: int, label: str) -> str:
    xs = [p[0] for p in points] + ([target[0]] if target else [])
    ys = [p[1] for p in points] + ([target[1]] if target else [])
    (lx, sx), (ly, sy) = _scale(xs), _scale(ys)
    span = max(sx, sy)

    def at(x: float, y: float) -> str:
        return f"{x0 + PAD + (x - lx) / span * PANEL:.1f},{PAD + PANEL - (y - ly) / span * PANEL:.1f}"

    out = [
        f'<rect x="{x0 + PAD}" y="{PAD}" width="{PANEL}" height="{PANEL}" fill="#f7f7f7" stroke="#999"/>',
        f'<text x="{x0 + PAD}" y="{PAD - 8}" font-size="13">{escape(label)}</text>',
    ]
    if len(points) > 1:
        out.append(
            f'<polyline fill="none" stroke="#1565c0" stroke-width="2" points="{" ".join(at(*p) for p in points)}"/>'
        )
    if points:
        out.append(
            f'<circle r="4" fill="#1565c0" cx="{at(*points[-1]).split(",")[0]}" cy="{at(*points[-1]).split(",")[1]}"/>'
        )
    if target is not None:
        cx, cy = at(*target).split(",")
        out.append(f'<circle r="6" fill="none" stroke="#c62828" stroke-width="2" cx="{cx}" cy="{cy}"/>')
    return "".join(out)


def track_svg(
    track: Sequence[Sequence[float]], target: Sequence[float] | None = None, title: str = ""
) -> str:
    """``track``: ``[t_s, x, y, z]`` rows (m); ``target``: ``(x, y, z)`` or None."""
    top = [(p[1], p[2]) for p in track]
    side = [(p[1], p[3]) for p in track]
    tgt_top = (target[0], target[1]) if target is not None else None
    tgt_side = (target[0], target[2]) if target is not None else None
    width, height = 2 * (PANEL + 2 * PAD), PANEL + 2 * PAD + 18
    return (
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" font-family="sans-serif">'
        f"<title>{escape(title)}</title>"
        + _panel(top, tgt_top, 0, "top: x → right, y ↑ (m)")
        + _panel(side, tgt_side, PANEL + 2 * PAD, "side: x → right, z ↑ (m)")
        + f'<text x="{PAD}" y="{height - 4}" font-size="11">blue: the drone\'s track, its last position dotted; red: the target</text>'
        + "</svg>"
    )


def svg_data_url(svg: str) -> str:
    return "data:image/svg+xml;base64," + base64.b64encode(svg.encode()).decode()
