"""The page's Teleop panel: the drone keyboard manager's mode and hold speed, set as node
parameters (what ``ros2 param set`` does), and a help text of the keys."""

from __future__ import annotations

from typing import Any

from node_runtime.bus import Node, Parameter

MODE_LABELS = {
    "lab": "lab: 1 m per press, 20 Hz (handout)",
    "adopt": "adopt: 1 m per press",
    "hold": "hold: hold to move",
}
KEYS_HELP = (
    "**Keys** (click the 3D view first)  \n"
    "**a**: abort the rocket during the countdown  \n"
    "**→ ←**: drone +x / −x (right / left)  \n"
    "**↑ ↓**: drone +y / −y (away / towards you)  \n"
    "**PgUp/W, PgDn/S**: up / down  \n"
    "**?**: show or hide this help over the view"
)


def find_teleop_node(nodes: list[Node]) -> Node | None:
    """The drone's keyboard manager: the node with a ``hold_speed_m_s`` parameter."""
    return next((n for n in nodes if n.state == "active" and n.has_parameter("hold_speed_m_s")), None)


class TeleopPanel:
    def __init__(self, lab: Any) -> None:
        self.lab = lab
        gui = lab.display.gui
        node = find_teleop_node(lab.bus.nodes)
        mode = str(node.get_parameter("mode").value) if node else "adopt"
        speed = float(node.get_parameter("hold_speed_m_s").value) if node else 2.0
        with gui.add_folder("Teleop", order=40.0):
            self.mode = gui.add_dropdown(
                "Key mode", list(MODE_LABELS.values()), initial_value=MODE_LABELS[mode]
            )
            self.speed = gui.add_slider("Hold speed (m/s)", min=0.5, max=5.0, step=0.25, initial_value=speed)
            self.status = gui.add_markdown("")
            self.dark = gui.add_checkbox("Dark theme", False)
            gui.add_markdown(KEYS_HELP)
        self.dark.on_update(lambda _e: lab.display.set_theme(dark=bool(self.dark.value)))
        self.mode.on_update(lambda _e: lab.display.call_in_app(self.apply))
        self.speed.on_update(lambda _e: lab.display.call_in_app(self.apply))

    def apply(self) -> None:
        node = find_teleop_node(self.lab.bus.nodes)
        if node is None:
            self.status.content = "no drone keyboard manager is running"
            return
        mode = next(k for k, v in MODE_LABELS.items() if v == self.mode.value)
        try:
            node.set_parameters(
                [Parameter("mode", mode), Parameter("hold_speed_m_s", float(self.speed.value))]
            )
            self.status.content = (
                f"`{node.fully_qualified_name}`: mode {mode}, hold speed {self.speed.value:g} m/s"
            )
        except ValueError as exc:
            self.status.content = f"**error:** {exc}"
