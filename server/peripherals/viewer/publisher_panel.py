"""The Message Publisher panel, like rqt's: pick a topic and a type, fill in the fields, set a
rate, enable it (a periodic publisher of the publishers API) or publish once.

viser calls GUI callbacks on its own threads; every action hops to the app's loop first,
where the bus lives.
"""

from __future__ import annotations

import logging
from collections.abc import Iterator
from typing import Any

import yaml

from node_runtime.msgs import Field, Message, get_type, type_names

log = logging.getLogger("viewer.publisher")
NEW_TOPIC = "(new topic)"
DEFAULT_TOPIC = "/uav/input/position"
SKIPPED_FIELDS = ("header.stamp",)  # filled by the receiver's clock, as rqt leaves it at 0


def leaf_fields(msg_type: type[Message], prefix: str = "") -> Iterator[tuple[str, Field]]:
    """Every primitive field of a type, with its dotted path (``pose.position.x``)."""
    for field in msg_type.FIELDS:
        path = f"{prefix}{field.name}"
        if path in SKIPPED_FIELDS:
            continue
        if isinstance(field.kind, str):
            yield path, field
        else:
            yield from leaf_fields(field.kind, path + ".")


def flow_yaml(msg: dict[str, Any]) -> str:
    """A message as ``ros2 topic pub`` takes it on one line: ``{x: 5.0, y: 5.0, z: 10.0}``."""
    text: str = yaml.safe_dump(msg, default_flow_style=True, sort_keys=False, width=1_000_000)
    return text.strip()


def nest(values: dict[str, Any]) -> dict[str, Any]:
    """``{"a.b": 1}`` → ``{"a": {"b": 1}}``."""
    out: dict[str, Any] = {}
    for path, value in values.items():
        node = out
        *parents, last = path.split(".")
        for key in parents:
            node = node.setdefault(key, {})
        node[last] = value
    return out


class PublisherPanel:
    def __init__(self, lab: Any) -> None:
        self.lab = lab
        self.display = lab.display
        gui = self.display.gui
        self.publisher_id: str | None = None
        self.inputs: dict[str, Any] = {}
        self._graph_version = -1
        self.folder = gui.add_folder("Message Publisher", expand_by_default=False, order=50.0)
        with self.folder:
            self.topic = gui.add_dropdown(
                "Topic", [NEW_TOPIC], hint="an existing topic, or a new one", order=1.0
            )
            self.new_topic = gui.add_text("New topic", "/my_topic", visible=False, order=2.0)
            self.type = gui.add_dropdown(
                "Type", type_names(), initial_value="geometry_msgs/msg/Vector3", order=3.0
            )
            # What the server holds, as viser delivers it: a browser sends one GUI update per 50 ms
            # and keeps only the newest, so of two inputs changed within 50 ms only the second
            # reaches the server. This line shows the message as it will go out.
            self.preview = gui.add_markdown("", order=4.5)
            self.rate = gui.add_number("Rate (Hz)", 1.0, min=0.1, max=1000.0, step=0.1, order=5.0)
            self.enabled = gui.add_checkbox(
                "Enabled", False, hint="publish at the rate while checked", order=6.0
            )
            self.once = gui.add_button("Publish once", order=7.0)
            self.status = gui.add_markdown("", order=8.0)
        self.fields_folder: Any = None
        self.refresh_topics()
        self.rebuild_fields()
        self.topic.on_update(lambda _e: self._in_app(self.on_topic))
        self.type.on_update(lambda _e: self._in_app(self.on_type))
        self.enabled.on_update(lambda _e: self._in_app(self.on_enabled))
        self.rate.on_update(lambda _e: self._in_app(self.on_change))
        self.once.on_click(lambda _e: self._in_app(self.publish_once))

    def _in_app(self, fn: Any) -> None:
        self.display.call_in_app(fn)

    # -- keeping up with the graph ---------------------------------------------
    def refresh_topics(self) -> None:
        """Offer the current topics (called from a bus timer; cheap when nothing changed)."""
        if self.lab.bus.graph_version == self._graph_version:
            return
        self._graph_version = self.lab.bus.graph_version
        names = sorted(t.name for t in self.lab.bus.topics.values() if not t.hidden)
        current = self.topic.value
        self.topic.options = [*names, NEW_TOPIC]
        if current in names or (current == NEW_TOPIC and self.publisher_id is not None):
            self.topic.value = current
        elif DEFAULT_TOPIC in names and current == NEW_TOPIC and self.publisher_id is None:
            self.topic.value = DEFAULT_TOPIC
            self.on_topic()

    def on_topic(self) -> None:
        self.new_topic.visible = self.topic.value == NEW_TOPIC
        topic = self.lab.bus.topics.get(self.topic.value)
        if topic is not None and self.type.value != topic.msg_type.TYPE:
            self.type.value = topic.msg_type.TYPE
            self.rebuild_fields()
        self.stop()

    def on_type(self) -> None:
        self.rebuild_fields()
        self.stop()

    def rebuild_fields(self) -> None:
        gui = self.display.gui
        if self.fields_folder is not None:
            self.fields_folder.remove()
        msg_type = get_type(self.type.value)
        self.inputs = {}
        with self.folder:
            self.fields_folder = gui.add_folder("Fields", order=4.0)
        with self.fields_folder:
            for path, field in leaf_fields(msg_type):
                self.inputs[path] = self._input(gui, path, field)
        self.show_preview()

    def _input(self, gui: Any, path: str, field: Field) -> Any:
        kind = field.kind
        if kind == "bool":
            handle = gui.add_checkbox(path, bool(field.default))
        elif kind == "string":
            handle = gui.add_text(path, str(field.default))
        elif isinstance(kind, str) and kind.startswith(("int", "uint")):
            handle = gui.add_number(path, int(field.default), step=1)
        else:
            handle = gui.add_number(path, float(field.default), step=0.1)
        handle.on_update(lambda _e: self._in_app(self.on_change))
        return handle

    # -- publishing --------------------------------------------------------------
    def message(self) -> tuple[str, dict[str, Any], str]:
        topic = self.new_topic.value.strip() if self.topic.value == NEW_TOPIC else self.topic.value
        values = {path: handle.value for path, handle in self.inputs.items()}
        return topic, nest(values), self.type.value

    def publish_once(self) -> None:
        try:
            topic, msg, type_name = self.message()
            name, _, count = self.lab.publish(topic, msg, type_name)
            self.status.content = f"published once on `{name}` ({count} subscriber(s))"
        except Exception as exc:
            self.status.content = f"**error:** {exc}"

    def on_enabled(self) -> None:
        if self.enabled.value:
            self.start()
        else:
            self.stop()

    def start(self) -> None:
        try:
            topic, msg, type_name = self.message()
            item = self.lab.publishers.start(topic, msg, type_name, float(self.rate.value))
        except Exception as exc:
            self.enabled.value = False
            self.status.content = f"**error:** {exc}"
            return
        self.publisher_id = item.id
        self.status.content = f"publishing on `{item.topic}` at {item.rate_hz:g} Hz ({item.id})"

    def stop(self) -> None:
        if self.publisher_id is not None:
            if self.publisher_id in self.lab.publishers.items:
                self.lab.publishers.stop(self.publisher_id)
            self.publisher_id = None
            self.status.content = "stopped"
        if self.enabled.value:
            self.enabled.value = False

    def show_preview(self) -> None:
        _, msg, _ = self.message()
        self.preview.content = f"message: `{flow_yaml(msg)}` at {float(self.rate.value):g} Hz"

    def on_change(self) -> None:
        """Fields or rate changed: the preview shows them, and a running publisher takes them."""
        self.show_preview()
        if self.publisher_id is None or self.publisher_id not in self.lab.publishers.items:
            return
        try:
            _, msg, _ = self.message()
            item = self.lab.publishers.update(self.publisher_id, rate_hz=float(self.rate.value), msg=msg)
            self.status.content = f"publishing on `{item.topic}` at {item.rate_hz:g} Hz ({item.id})"
        except Exception as exc:
            self.status.content = f"**error:** {exc}"


class PageToolsNode:
    """Keeps the page's tools current: a hidden node ``_page_tools`` with a 1 Hz timer."""

    def __init__(self, lab: Any) -> None:
        from node_runtime.bus import Node
        from server.peripherals.viewer.teleop_panel import TeleopPanel, find_teleop_node

        with lab.bus.activate():
            self.node = Node("_page_tools")
        self.panel = PublisherPanel(lab)
        self.teleop = None
        if find_teleop_node(lab.bus.nodes) is not None:
            self.teleop = TeleopPanel(lab)
        self.node.create_timer(1.0, self.panel.refresh_topics)
