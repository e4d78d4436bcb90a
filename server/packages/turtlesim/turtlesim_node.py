"""turtlesim_node: ROS 2's turtlesim without its window, on the lab's turtle sim (sim/turtlesim).

The node (``/turtlesim``) has turtlesim's graph: ``spawn``, ``kill``, ``clear`` and ``reset``, and
per turtle ``NAME/cmd_vel`` in, ``NAME/pose`` and ``NAME/color_sensor`` out every 16 ms, and the
services ``NAME/set_pen``, ``NAME/teleport_absolute`` and ``NAME/teleport_relative``, all named
relative to the node's namespace. Its parameters are turtlesim's: the background's
``background_r``/``_g``/``_b`` (0 to 255; the window would repaint when one is set, so the node
follows its own parameter events as turtlesim does) and ``holonomic`` (``linear.y`` moves the
turtle sideways too). It logs what turtlesim logs, in turtlesim's words. Each turtle serves
turtlesim's ``NAME/rotate_absolute`` action too (rotate_absolute.py).
"""

from __future__ import annotations

from typing import Any

from node_runtime.bus import InvalidNameError, Node, Publisher, ServiceServer, Subscription
from node_runtime.msgs import Twist
from node_runtime.msgs.generated.rcl_interfaces import IntegerRange, ParameterDescriptor, ParameterEvent
from node_runtime.msgs.generated.std_srvs import Empty, Empty_Response
from node_runtime.msgs.generated.turtlesim import (
    Color,
    Kill,
    Kill_Request,
    Kill_Response,
    Pose,
    SetPen,
    SetPen_Request,
    SetPen_Response,
    Spawn,
    Spawn_Request,
    Spawn_Response,
    TeleportAbsolute,
    TeleportAbsolute_Request,
    TeleportAbsolute_Response,
    TeleportRelative,
    TeleportRelative_Request,
    TeleportRelative_Response,
)
from server.packages.turtlesim.rotate_absolute import RotateAbsoluteServer
from sim.turtlesim import CENTER_M, UPDATE_PERIOD_S, Reading, Teleport, TurtleWorld

TOPIC_DEPTH = 7  # turtlesim's topics: reliable, keep last 7
BACKGROUND = {"background_r": 0x45, "background_g": 0x56, "background_b": 0xFF}
CHANNEL = {"background_r": "Red", "background_g": "Green", "background_b": "Blue"}


def _channel_descriptor(name: str) -> ParameterDescriptor:
    return ParameterDescriptor(
        description=f"{CHANNEL[name]} channel of the background color",
        integer_range=[IntegerRange(from_value=0, to_value=255, step=1)],
    )


class TurtleEndpoints:
    """One turtle's topics and services, which go with it when it is killed."""

    def __init__(self, node: TurtlesimNode, name: str) -> None:
        self.node, self.name = node, name
        self.pose_pub: Publisher = node.create_publisher(Pose, f"{name}/pose", TOPIC_DEPTH)
        self.color_pub: Publisher = node.create_publisher(Color, f"{name}/color_sensor", TOPIC_DEPTH)
        self.cmd_sub: Subscription = node.create_subscription(
            Twist, f"{name}/cmd_vel", self.on_cmd_vel, TOPIC_DEPTH, read_only=True
        )
        self.services: list[ServiceServer] = [
            node.create_service(SetPen, f"{name}/set_pen", self.on_set_pen),
            node.create_service(TeleportRelative, f"{name}/teleport_relative", self.on_teleport_relative),
            node.create_service(TeleportAbsolute, f"{name}/teleport_absolute", self.on_teleport_absolute),
        ]
        self.rotate = RotateAbsoluteServer(node, name, lambda: node.world.turtles[name])

    def on_cmd_vel(self, msg: Twist) -> None:
        turtle = self.node.world.turtles[self.name]
        sideways = msg.linear.y if self.node.get_parameter("holonomic").value else 0.0
        turtle.command(msg.linear.x, sideways, msg.angular.z, self.node.bus.clock.now())
        self.rotate.abort()

    def on_set_pen(self, request: SetPen_Request, response: SetPen_Response) -> SetPen_Response:
        self.node.world.turtles[self.name].set_pen(
            request.r, request.g, request.b, request.width, bool(request.off)
        )
        return response

    def on_teleport_relative(
        self, request: TeleportRelative_Request, response: TeleportRelative_Response
    ) -> TeleportRelative_Response:
        teleport = Teleport(theta_rad=request.angular, linear_m=request.linear, relative=True)
        self.node.world.turtles[self.name].teleports.append(teleport)
        return response

    def on_teleport_absolute(
        self, request: TeleportAbsolute_Request, response: TeleportAbsolute_Response
    ) -> TeleportAbsolute_Response:
        teleport = Teleport(request.x, request.y, request.theta)
        self.node.world.turtles[self.name].teleports.append(teleport)
        return response

    def publish(self, reading: Reading) -> None:
        self.pose_pub.publish(
            Pose(
                x=reading.x_m,
                y=reading.y_m,
                theta=reading.theta_rad,
                linear_velocity=reading.linear_velocity_mps,
                angular_velocity=reading.angular_velocity_radps,
            )
        )
        self.color_pub.publish(Color(r=reading.color.r, g=reading.color.g, b=reading.color.b))

    def destroy(self) -> None:
        self.node.destroy_publisher(self.pose_pub)
        self.node.destroy_publisher(self.color_pub)
        self.node.destroy_subscription(self.cmd_sub)
        for server in self.services:
            self.node.destroy_service(server)
        self.rotate.destroy()


class TurtlesimNode(Node):
    def __init__(self) -> None:
        super().__init__("turtlesim")
        for name, default in BACKGROUND.items():
            self.declare_parameter(name, default, _channel_descriptor(name))
        self.declare_parameter(
            "holonomic", False, ParameterDescriptor(description="If true, then turtles will be holonomic")
        )
        self.background = self._background()  # what the window would show
        self.world = TurtleWorld()
        self.endpoints: dict[str, TurtleEndpoints] = {}
        self.create_service(Empty, "clear", self.on_clear)
        self.create_service(Empty, "reset", self.on_reset)
        self.create_service(Spawn, "spawn", self.on_spawn)
        self.create_service(Kill, "kill", self.on_kill)
        self.create_subscription(ParameterEvent, "/parameter_events", self.on_parameter_event, 100)
        self.get_logger().info(f"Starting turtlesim with node name {self.get_fully_qualified_name()}")
        self.spawn("", CENTER_M, CENTER_M, 0.0)
        self.create_timer(UPDATE_PERIOD_S, self.update)

    def _background(self) -> tuple[int, int, int]:
        r, g, b = (int(self.get_parameter(name).value) for name in BACKGROUND)
        return r, g, b

    def spawn(self, name: str, x_m: float, y_m: float, theta_rad: float) -> str | None:
        real_name = self.world.spawn(name, x_m, y_m, theta_rad, self.bus.clock.now())
        if real_name is not None:
            self.endpoints[real_name] = TurtleEndpoints(self, real_name)
            turtle = self.world.turtles[real_name]
            self.get_logger().info(
                f"Spawning turtle [{real_name}] at x=[{turtle.x_m:f}], "
                f"y=[{turtle.y_m:f}], theta=[{turtle.theta_rad:f}]"
            )
        return real_name

    def on_spawn(self, request: Spawn_Request, response: Spawn_Response) -> Spawn_Response:
        try:  # turtlesim would crash on a name its topics cannot take; this one says so and goes on
            self.resolve_topic_name(f"{request.name or 'turtle'}/pose")
        except InvalidNameError as exc:
            self.get_logger().error(f"A turtle cannot be named [{request.name}]: {exc}")
            return response
        name = self.spawn(request.name, request.x, request.y, request.theta)
        if name is None:
            self.get_logger().error(f"A turtle named [{request.name}] already exists")
        else:
            response.name = name
        return response

    def on_kill(self, request: Kill_Request, response: Kill_Response) -> Kill_Response:
        if not self.world.kill(request.name):
            self.get_logger().error(f"Tried to kill turtle [{request.name}], which does not exist")
        else:
            self.endpoints.pop(request.name).destroy()
        return response

    def on_clear(self, _request: Any, response: Empty_Response) -> Empty_Response:
        self.get_logger().info("Clearing turtlesim.")
        self.world.canvas.clear()
        return response

    def on_reset(self, _request: Any, response: Empty_Response) -> Empty_Response:
        self.get_logger().info("Resetting turtlesim.")
        for endpoints in self.endpoints.values():
            endpoints.destroy()
        self.endpoints.clear()
        self.world.reset()
        self.spawn("", CENTER_M, CENTER_M, 0.0)
        return response

    def on_parameter_event(self, event: ParameterEvent) -> None:
        if event.node == self.get_fully_qualified_name():
            self.background = self._background()

    def update(self) -> None:
        for endpoints in self.endpoints.values():
            endpoints.rotate.before_frame()
        for name, reading in self.world.step(self.bus.clock.now()).items():
            self.endpoints[name].rotate.after_frame(reading.rotation)
            if reading.clamped_from is not None:
                x_m, y_down_m = reading.clamped_from
                self.get_logger().warning(
                    f"Oh no! I hit the wall! (Clamping from [x={x_m:f}, y={y_down_m:f}])"
                )
            self.endpoints[name].publish(reading)
