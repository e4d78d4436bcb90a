"""The rocket's 3D view: a tool node (hidden, like rqt) that watches the rocket's topics and draws.

``RocketTracker`` follows the topics the way MainControllerNode does, so the page can say
"counting down", "aborted" or "Abort Failed" without reaching into another node. The altitude
is the commanded velocity integrated, since the lab's rocket has no position model.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from node_runtime.bus import Node
from node_runtime.msgs import Bool, Float64, Int64
from server.peripherals.viewer.display import Display
from server.peripherals.viewer.plots import TimePlot

CMD_PERIOD_S = 0.1  # MainControllerNode publishes /cmd_vel at 10 Hz
PAD_XY = (60.0, 0.0)  # the rocket stands apart from the quadrotor's arena
REDRAW_HZ = 30.0
# What a page redraws for: the rocket's pose when it moved this far in the scene (under the
# display's ceiling a climbing rocket moves a fraction of a millimetre a frame, which no one
# sees), and the readouts (numbers to read, not to watch) at most this often, a change of
# phase, status or countdown at once. Each message makes every open page draw its 3D view.
MOVE_MIN_M = 0.005
READOUT_PERIOD_S = 0.2
# From the south-east, close enough that the rocket stands a quarter of the view's height, and
# high enough to keep its whole (squeezed) flight, pad to ceiling, in the picture.
CAMERA_OFFSET_M, CAMERA_LOOK_AT_Z_M = (11.0, -11.0, 9.0), 7.5
LABEL_ABOVE_PAD_M = 6.2  # the label's bottom in the rocket's frame (0.3 m up): 6.5 m, over the 6 m tower


@dataclass
class RocketTracker:
    phase: str = "ready"  # ready | counting down | launched | aborted | abort failed
    countdown: int | None = None
    cmd_vel_m_s: float = 0.0
    sensor_vel_m_s: float = 0.0
    altitude_m: float = 0.0
    version: int = 0

    def _changed(self) -> None:
        self.version += 1

    def on_countdown(self, n: int) -> None:
        if self.phase == "aborted":
            return
        self.countdown = n
        if n <= 0:
            self.phase = "launched" if self.phase != "abort failed" else self.phase
        elif self.phase == "ready":
            self.phase = "counting down"
        self._changed()

    def on_abort(self, data: bool) -> None:
        if not data:
            return
        if self.phase in ("launched", "abort failed"):
            self.phase = "abort failed"
        else:
            self.phase = "aborted"
        self._changed()

    def on_cmd_vel(self, v_m_s: float) -> None:
        self.cmd_vel_m_s = v_m_s
        self.altitude_m += v_m_s * CMD_PERIOD_S
        self._changed()

    def on_sensor_vel(self, v_m_s: float) -> None:
        if v_m_s != self.sensor_vel_m_s:
            self.sensor_vel_m_s = v_m_s
            self._changed()

    @property
    def status_text(self) -> str:
        if self.phase == "counting down":
            return f"Counting down: T-{self.countdown} s"
        if self.phase == "aborted":
            return "Aborted: Abort Abort Abort!!! The rocket stays on the pad."
        if self.phase == "abort failed":
            return "Abort Failed: the rocket had already launched."
        if self.phase == "launched":
            return "Launched"
        return "Ready for countdown"


DISPLAY_CEILING_M = 12.0  # scene height the rocket approaches but never leaves the view past
DISPLAY_HALF_M = 30.0  # true altitude shown at half the ceiling


def display_height(altitude_m: float) -> float:
    """Scene height for a true altitude: near-linear off the pad, then squeezed under a ceiling,
    so a rocket at 100 km is still in the picture (the label gives the true altitude)."""
    h = max(altitude_m, 0.0)
    return DISPLAY_CEILING_M * h / (h + DISPLAY_HALF_M)


def _cone(radius: float, height: float, segments: int = 24) -> tuple[np.ndarray, np.ndarray]:
    angles = np.linspace(0, 2 * np.pi, segments, endpoint=False)
    ring = np.stack([radius * np.cos(angles), radius * np.sin(angles), np.zeros(segments)], axis=1)
    vertices = np.vstack([ring, [[0, 0, height]], [[0, 0, 0]]]).astype(np.float32)
    tip, base = segments, segments + 1
    faces = [[i, (i + 1) % segments, tip] for i in range(segments)]
    faces += [[(i + 1) % segments, i, base] for i in range(segments)]
    return vertices, np.array(faces, dtype=np.uint32)


class RocketScene:
    """The viser objects: pad, rocket, flame, label and the GUI readouts."""

    def __init__(
        self, display: Display, on_reset: Callable[[], object], busy: Callable[[], bool] | None = None
    ) -> None:
        scene, gui = display.scene, display.gui
        x, y = PAD_XY
        dx, dy, z = CAMERA_OFFSET_M
        display.add_view("Rocket", (x + dx, y + dy, z), (x, y, CAMERA_LOOK_AT_Z_M), initial=True, busy=busy)
        scene.add_grid("/rocket_lab/ground", width=30, height=30, cell_size=1.0, position=(x, y, 0))
        scene.add_box(
            "/rocket_lab/pad", color=(110, 110, 120), dimensions=(3.0, 3.0, 0.3), position=(x, y, 0.15)
        )
        scene.add_box(
            "/rocket_lab/tower", color=(170, 60, 40), dimensions=(0.3, 0.3, 6.0), position=(x + 1.2, y, 3.0)
        )
        self.rocket = scene.add_frame("/rocket_lab/rocket", show_axes=False, position=(x, y, 0.3))
        scene.add_cylinder(
            "/rocket_lab/rocket/body",
            radius=0.35,
            height=4.0,
            color=(235, 235, 240),
            wxyz=(1.0, 0.0, 0.0, 0.0),
            position=(0, 0, 2.0),
        )
        nose_v, nose_f = _cone(0.35, 1.2)
        scene.add_mesh_simple(
            "/rocket_lab/rocket/nose", nose_v, nose_f, color=(200, 30, 30), position=(0, 0, 4.0)
        )
        for i, (fx, fy) in enumerate(((0.45, 0), (-0.45, 0), (0, 0.45), (0, -0.45))):
            dims = (0.5, 0.06, 0.8) if fy == 0 else (0.06, 0.5, 0.8)
            scene.add_box(
                f"/rocket_lab/rocket/fin{i}", color=(200, 30, 30), dimensions=dims, position=(fx, fy, 0.4)
            )
        flame_v, flame_f = _cone(0.3, -1.8)
        self.flame = scene.add_mesh_simple(
            "/rocket_lab/rocket/flame", flame_v, flame_f, color=(255, 150, 20), visible=False, side="double"
        )
        # Above the nose, its bottom edge centred on the rocket's axis: clear of the tower beside it
        # (whose top is 6 m up) whatever the text's length.
        self.label = scene.add_label(
            "/rocket_lab/rocket/label", "Ready", position=(0, 0, LABEL_ABOVE_PAD_M), anchor="bottom-center"
        )
        with gui.add_folder("Rocket lab"):
            self.status = gui.add_markdown("**Ready for countdown**")
            self.countdown = gui.add_number("Countdown (s)", 10, disabled=True)
            self.cmd_vel = gui.add_number("/cmd_vel (m/s)", 0.0, disabled=True, step=0.001)
            self.sensor_vel = gui.add_number("/sensor_vel (m/s)", 0.0, disabled=True, step=0.001)
            self.altitude = gui.add_number("Altitude (m)", 0.0, disabled=True, step=0.1)
            gui.add_markdown("Press **a** in this page during the countdown to abort.")
            reset = gui.add_button(
                "Reset rocket", color="blue", hint="Back on the pad; the countdown starts again"
            )
        with gui.add_folder("Rocket plot", expand_by_default=False):
            self.plot = TimePlot(
                gui,
                "/cmd_vel vs /sensor_vel (m/s)",
                ("/cmd_vel/data", "/sensor_vel/data"),
                ("#1f5fd6", "#d62728"),
                max_points=4000,
            )
        reset.on_click(lambda _event: display.call_in_app(on_reset))
        self._display = display
        self._height: float | None = None  # the scene height last sent
        self._read: tuple[str, str, int | None] | None = None  # phase, status, countdown last shown
        self._read_at = -float("inf")
        self.stale = False  # readouts held back: the next redraw sends them, changed or not

    def draw(self, t: RocketTracker, now_s: float) -> None:
        """Send what changed visibly: the pose when it moved, the readouts at most every
        READOUT_PERIOD_S unless the phase, status or countdown changed."""
        x, y = PAD_XY
        height = 0.3 + display_height(t.altitude_m)
        read = (t.phase, t.status_text, t.countdown)
        readouts = read != self._read or now_s - self._read_at >= READOUT_PERIOD_S
        self.stale = not readouts
        with self._display.server.atomic():
            if self._height is None or abs(height - self._height) >= MOVE_MIN_M:
                self.rocket.position = (x, y, height)
                self._height = height
            self.flame.visible = t.phase in ("launched", "abort failed") and t.cmd_vel_m_s > 0
            if readouts:
                self.label.text = f"{t.phase}  {t.altitude_m:,.0f} m" if t.altitude_m else t.phase
        if not readouts:
            return
        self._read, self._read_at = read, now_s
        self.status.content = f"**{t.status_text}**"
        self.countdown.value = t.countdown if t.countdown is not None else 10
        self.cmd_vel.value = round(t.cmd_vel_m_s, 3)
        self.sensor_vel.value = round(t.sensor_vel_m_s, 3)
        self.altitude.value = round(t.altitude_m, 1)

    def forget_drawn(self) -> None:
        """The rocket is back on its pad: draw all of it at the next redraw."""
        self._height, self._read = None, None


class RocketViewNode(Node):
    """Hidden tool node ``_rocket_view``: subscribes to the rocket's topics and redraws at 30 Hz."""

    def __init__(self, display: Display | None, on_reset: Callable[[], object]) -> None:
        super().__init__("_rocket_view")
        self.tracker = RocketTracker()
        self.scene = RocketScene(display, on_reset, self.before_liftoff) if display is not None else None
        self._drawn = -1
        self.create_subscription(Int64, "/countdown", lambda m: self.tracker.on_countdown(m.data), 100)
        self.create_subscription(Bool, "/abort_takeoff", lambda m: self.tracker.on_abort(m.data), 100)
        self.create_subscription(Float64, "/cmd_vel", lambda m: self.tracker.on_cmd_vel(m.data), 100)
        self.create_subscription(Float64, "/sensor_vel", self.on_sensor_vel, 100)
        self.create_timer(1.0 / REDRAW_HZ, self.redraw)
        self._t0 = self.bus.clock.now()
        if self.scene is not None:
            self.create_timer(0.25, self.scene.plot.flush)

    def before_liftoff(self) -> bool:
        """The rocket's part of the lab is under way: ready or counting down, not yet launched."""
        return self.tracker.phase in ("ready", "counting down")

    def on_sensor_vel(self, msg: Float64) -> None:
        """Track it, and plot both velocities as /sensor_vel arrives (10 Hz), like the lab's rqt_plot."""
        self.tracker.on_sensor_vel(msg.data)
        if self.scene is not None and self.tracker.phase != "ready":
            self.scene.plot.append(self.bus.clock.now() - self._t0, self.tracker.cmd_vel_m_s, msg.data)

    def reset(self) -> None:
        self.tracker = RocketTracker()
        self._drawn = -1
        self._t0 = self.bus.clock.now()
        if self.scene is not None:
            self.scene.plot.clear()
            self.scene.forget_drawn()

    def redraw(self) -> None:
        if self.scene is None or (self.tracker.version == self._drawn and not self.scene.stale):
            return
        self._drawn = self.tracker.version
        self.scene.draw(self.tracker, self.bus.clock.now())
