"""GUIControllerNode: draws the quadrotor as the lab's GUI does (green hub, blue arm along body x,
red arm along body y, L = 1 m) at its true (x, y, z), in the lab's arena, at 30 Hz rather than
the lab's 2 Hz; plus the setpoint marker, a short trail and a telemetry panel.

The page (web/src/lab/scene.ts) draws the drone between these updates from the pose stream, at the
display's rate, and moves the setpoint marker itself the moment a key goes down.
"""

from __future__ import annotations

import math
from collections import deque
from typing import Any

import numpy as np

from node_runtime.bus import Node
from node_runtime.bus.parameter_values import double_range
from node_runtime.msgs import PoseStamped, TwistStamped, Vector3
from server.packages.flightcontroller.setpoints import ARENA_MAX_M, ARENA_MIN_M
from server.peripherals.viewer.plots import TimePlot
from server.peripherals.viewer.views import Follow

ARM_M = 1.0  # the lab draws each arm 1 m from the hub
TRAIL_POINTS = 150
PLOT_WINDOW_S = 20.0
PLOT_SAMPLE_HZ = 10.0
PLOT_FLUSH_HZ = 4.0
TELEMETRY_HZ = 5.0  # text to read, not to watch move: each update costs the page a React render
# A hovering drone jitters by a few millimetres (process noise): drawn again only once it has
# moved this far from where it was last drawn. Each drawing keeps the page rendering for a while
# (viser renders for 0.25 s after any change), so a hover drawn at 30 Hz would keep a slow
# machine's page always busy, and a key pressed then would wait behind a frame under way. The
# page draws the drone itself between these drawings, from the pose stream, whenever it moves.
REDRAW_MIN_M = 0.02
REDRAW_MIN_RAD = math.radians(1.0)
HUB_GREEN, ARM_X_BLUE, ARM_Y_RED = (0, 200, 0), (30, 60, 255), (230, 30, 30)
DRONE_NODE, SETPOINT_NODE, TRAIL_NODE = "/drone_lab/drone", "/drone_lab/setpoint", "/drone_lab/trail"
# Both cameras look from -y, so on screen right = +x and away = +y, as the arrow keys move it.
# Fixed: the hover point (0, 0, 3) about 10 m away, the arms about a tenth of the view's height,
# the arena's far side and ceiling in view. Follow: 5.5 m behind and above the drone, the arms
# about a quarter of the view's height (viser's vertical field of view is 75 degrees).
CAMERA_POSITION, CAMERA_LOOK_AT = (0.0, -10.0, 6.0), (0.0, 0.0, 4.0)
FOLLOW_OFFSET_M = (0.0, -5.0, 2.2)


def _arena_edges() -> np.ndarray:
    (x0, y0, z0), (x1, y1, z1) = ARENA_MIN_M, ARENA_MAX_M
    corners = np.array([[x, y, z] for z in (z0, z1) for y in (y0, y1) for x in (x0, x1)], dtype=np.float32)
    pairs = [(0, 1), (2, 3), (0, 2), (1, 3), (4, 5), (6, 7), (4, 6), (5, 7), (0, 4), (1, 5), (2, 6), (3, 7)]
    return np.stack([corners[[a, b]] for a, b in pairs])


def euler_deg(w: float, x: float, y: float, z: float) -> tuple[float, float, float]:
    roll = math.atan2(2 * (w * x + y * z), 1 - 2 * (x * x + y * y))
    pitch = math.asin(max(-1.0, min(1.0, 2 * (w * y - z * x))))
    yaw = math.atan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z))
    return math.degrees(roll), math.degrees(pitch), math.degrees(yaw)


class DroneScene:
    def __init__(self, display: Any) -> None:
        scene, gui = display.scene, display.gui
        display.add_view(
            "Quadrotor",
            CAMERA_POSITION,
            CAMERA_LOOK_AT,
            follow=Follow(DRONE_NODE, FOLLOW_OFFSET_M, SETPOINT_NODE, TRAIL_NODE),
        )
        scene.add_grid("/drone_lab/ground", width=20, height=20, cell_size=1.0, section_size=5.0)
        scene.add_line_segments("/drone_lab/bounds", _arena_edges(), colors=(150, 150, 160), thickness=0.03)
        self.drone = scene.add_frame(DRONE_NODE, show_axes=False)
        scene.add_icosphere("/drone_lab/drone/hub", radius=0.3, color=HUB_GREEN)
        arms = np.array([[[-ARM_M, 0, 0], [ARM_M, 0, 0]], [[0, -ARM_M, 0], [0, ARM_M, 0]]], dtype=np.float32)
        colors = np.array([[ARM_X_BLUE] * 2, [ARM_Y_RED] * 2], dtype=np.uint8)
        scene.add_line_segments("/drone_lab/drone/arms", arms, colors=colors, thickness=0.15)
        self.setpoint = scene.add_icosphere(
            SETPOINT_NODE, radius=0.15, color=(255, 150, 0), opacity=0.6, position=(0.0, 0.0, 3.0)
        )
        self.trail = scene.add_line_segments(
            TRAIL_NODE, np.zeros((1, 2, 3), np.float32), colors=(90, 160, 90), thickness=0.03
        )
        with gui.add_folder("Quadrotor"):
            self.telemetry = gui.add_markdown("waiting for /uav/sensors/gps ...")
            gui.add_markdown(
                "Arrow keys move the setpoint: **→** +x, **←** −x, **↑** +y (away), **↓** −y; "
                "**PgUp/W** up, **PgDn/S** down."
            )
        with gui.add_folder("Quadrotor plots", expand_by_default=False):
            self.plots = tuple(
                TimePlot(
                    gui,
                    f"{axis} (m): drone vs setpoint",
                    (axis, f"{axis} setpoint"),
                    ("#2a6", "#e80"),
                    window_s=PLOT_WINDOW_S,
                )
                for axis in "xyz"
            )
        self._display = display

    def plot(
        self, t_s: float, pos: tuple[float, float, float], setpoint: tuple[float, float, float] | None
    ) -> None:
        sp = setpoint if setpoint is not None else (float("nan"),) * 3
        for plot, value, target in zip(self.plots, pos, sp, strict=True):
            plot.append(t_s, value, target)

    def watched(self) -> bool:
        return bool(self._display.watched())

    def flush_plots(self) -> None:
        for plot in self.plots:
            plot.flush()

    def draw(
        self,
        pos: tuple[float, float, float],
        wxyz: tuple[float, float, float, float],
        setpoint: tuple[float, float, float] | None,
        trail: np.ndarray,
    ) -> None:
        with self._display.server.atomic():
            self.drone.position = pos
            self.drone.wxyz = wxyz
            if setpoint is not None:
                self.setpoint.position = setpoint
            if len(trail) >= 2:
                # Newest segment first: the page draws only the first N when it must save time.
                self.trail.points = np.stack([trail[:0:-1], trail[-2::-1]], axis=1)


class GUIControllerNode(Node):
    def __init__(self) -> None:
        super().__init__("GUIControllerNode")
        redraw_hz = float(
            self.declare_parameter(
                "redraw_hz", 30.0, double_range(1.0, 60.0, "redraws a second", fixed=True)
            ).value
        )
        if not 1.0 <= redraw_hz <= 60.0:
            raise ValueError(f"redraw_hz must be in 1..60, got {redraw_hz}")
        display = self.bus.devices.get("display")
        self.scene = DroneScene(display) if display is not None else None
        self.pose: tuple[tuple[float, float, float], tuple[float, float, float, float]] | None = None
        self.velocity: tuple[float, float, float] | None = None
        self.setpoint: tuple[float, float, float] | None = None
        self.trail: deque[tuple[float, float, float]] = deque(maxlen=TRAIL_POINTS)
        self.frames_drawn = 0
        self._dirty = False
        self._drawn: tuple[tuple[float, float, float], tuple[float, float, float, float]] | None = None
        self._unsent = False  # a frame drawn while no page watched: sent once one does
        self.create_subscription(PoseStamped, "uav/sensors/gps", self.on_gps, 10, read_only=True)
        self.create_subscription(TwistStamped, "uav/sensors/velocity", self.on_velocity, 1, read_only=True)
        self.create_subscription(Vector3, "uav/input/position", self.on_setpoint, 10, read_only=True)
        self.create_timer(1.0 / redraw_hz, self.redraw)
        if self.scene is not None:
            self.create_timer(1.0 / TELEMETRY_HZ, self.write_telemetry)
            self.create_timer(1.0 / PLOT_SAMPLE_HZ, self.sample_plots)
            self.create_timer(1.0 / PLOT_FLUSH_HZ, self.flush_plots)
        self._t0 = self.bus.clock.now()

    def on_gps(self, msg: PoseStamped) -> None:
        p, q = msg.pose.position, msg.pose.orientation
        self.pose = ((p.x, p.y, p.z), (q.w, q.x, q.y, q.z))
        self._dirty = True

    def on_velocity(self, msg: TwistStamped) -> None:
        v = msg.twist.linear
        self.velocity = (v.x, v.y, v.z)

    def on_setpoint(self, msg: Vector3) -> None:
        if self.setpoint != (msg.x, msg.y, msg.z):
            self._drawn = None  # draw the new setpoint, however still the drone
        self.setpoint = (msg.x, msg.y, msg.z)
        self._dirty = True

    def moved_since_drawn(self) -> bool:
        assert self.pose is not None
        if self._drawn is None:
            return True
        (pos, wxyz), (pos0, wxyz0) = self.pose, self._drawn
        dot = min(1.0, abs(sum(a * b for a, b in zip(wxyz, wxyz0, strict=True))))
        return math.dist(pos, pos0) > REDRAW_MIN_M or 2 * math.acos(dot) > REDRAW_MIN_RAD

    def redraw(self) -> None:
        if self._dirty and self.pose is not None:
            self._dirty = False
            if self.moved_since_drawn():
                self._drawn = self.pose
                self.trail.append(self.pose[0])
                self.frames_drawn += 1
                self._unsent = True
        # The 3D view is sent only while a page shows it; one that opens later gets the latest frame.
        if self._unsent and self._drawn is not None and self.scene is not None and self.scene.watched():
            self._unsent = False
            pos, wxyz = self._drawn
            self.scene.draw(pos, wxyz, self.setpoint, np.array(self.trail, dtype=np.float32))

    def write_telemetry(self) -> None:
        if self.pose is not None and self.scene is not None and self.scene.watched():
            self.scene.telemetry.content = self.telemetry_text()

    def flush_plots(self) -> None:
        """The plots' new samples, while a page shows them (they keep sampling either way)."""
        if self.scene is not None and self.scene.watched():
            self.scene.flush_plots()

    def sample_plots(self) -> None:
        if self.pose is not None and self.scene is not None:
            self.scene.plot(self.bus.clock.now() - self._t0, self.pose[0], self.setpoint)

    def telemetry_text(self) -> str:
        assert self.pose is not None
        (x, y, z), wxyz = self.pose
        roll, pitch, yaw = euler_deg(*wxyz)
        lines = [f"**Position** ({x:6.2f}, {y:6.2f}, {z:6.2f}) m"]
        if self.velocity is not None:
            vx, vy, vz = self.velocity
            lines.append(f"**Velocity** ({vx:5.2f}, {vy:5.2f}, {vz:5.2f}) m/s")
        lines.append(f"**Attitude** roll {roll:5.1f}°, pitch {pitch:5.1f}°, yaw {yaw:5.1f}°")
        if self.setpoint is not None:
            sx, sy, sz = self.setpoint
            lines.append(f"**Setpoint** ({sx:.2f}, {sy:.2f}, {sz:.2f}) m")
        return "  \n".join(lines)
