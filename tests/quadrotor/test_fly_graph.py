"""fly.launch's graph (ref §3.1-3.2, §4): the lab's node names, topic names and message types."""

from __future__ import annotations

import pytest

from node_runtime.msgs import PoseStamped
from server.world.lab import Lab

from .conftest import make_lab, node

LAB_NODES = {
    "GUI_Controller_Node",
    "position_controller_node",
    "velocity_controller_node",
    "angle_controller_node",
    "flightgoggles_uav_dynamics",
    "pressure_node",
    "keyboard_manager_node",
    "keyboard",
}
LAB_TOPICS = {
    "/uav/input/position": "geometry_msgs/msg/Vector3",
    "/uav/input/velocity": "geometry_msgs/msg/Vector3",
    "/uav/input/rateThrust": "geometry_msgs/msg/TwistStamped",
    "/uav/sensors/gps": "geometry_msgs/msg/PoseStamped",
    "/uav/sensors/velocity": "geometry_msgs/msg/TwistStamped",
    "/uav/sensors/attitude": "geometry_msgs/msg/Vector3",
    "/uav/sensors/pressure": "std_msgs/msg/Float64",
    "/keydown": "keyboard_msgs/msg/Key",
}


def _launched(lab: Lab) -> set[str]:
    return {n.get_name() for n in lab.bus.nodes if not n.get_name().startswith("_")}


def _ends(lab: Lab, topic: str) -> tuple[set[str], set[str]]:
    """The names of the nodes publishing and subscribing to ``topic``."""
    t = lab.bus.get_topic(topic)
    return {p.node.get_name() for p in t.publishers}, {s.node.get_name() for s in t.subscriptions}


def test_fly_launch_default_graph_has_the_labs_nodes_all_started() -> None:
    lab = make_lab()
    lab.start_nodes()
    assert _launched(lab) == LAB_NODES
    assert [e.error for e in lab.launcher.launched] == [None] * len(LAB_NODES)
    assert node(lab, "position_controller_node").mode == "cascade"


def test_fly_launch_default_topics_have_the_labs_names_and_types() -> None:
    lab = make_lab()
    lab.start_nodes()
    types = {name: t.msg_type.TYPE for name, t in lab.bus.topics.items()}
    assert {name: types.get(name) for name in LAB_TOPICS} == LAB_TOPICS


def test_fly_launch_default_topics_are_wired_between_the_labs_nodes() -> None:
    lab = make_lab()
    lab.start_nodes()
    assert _ends(lab, "/uav/input/velocity") == ({"position_controller_node"}, {"velocity_controller_node"})
    assert _ends(lab, "/uav/input/rateThrust") == ({"angle_controller_node"}, {"flightgoggles_uav_dynamics"})
    pubs, subs = _ends(lab, "/uav/sensors/gps")
    assert pubs == {"flightgoggles_uav_dynamics"}
    assert {"position_controller_node", "GUI_Controller_Node", "pressure_node"} <= subs
    assert _ends(lab, "/keydown") == ({"keyboard"}, {"keyboard_manager_node"})


def test_fly_launch_gps_is_stamped_in_frame_world() -> None:
    lab = make_lab()
    lab.start_nodes()
    lab.executor.spin_until(0.5)
    gps = lab.bus.get_topic("/uav/sensors/gps").latest
    assert isinstance(gps, PoseStamped)
    assert gps.header.frame_id == "world"
    assert (gps.header.stamp.sec, gps.header.stamp.nanosec) == (0, 500_000_000)


@pytest.mark.parametrize("simple", ["true", "1"])
def test_fly_launch_simple_true_runs_simple_sim_and_lab_pid(simple: str) -> None:
    lab = make_lab(simple=simple)
    lab.start_nodes()
    names = _launched(lab)
    assert "SimpleSimNode" in names
    assert not names & {"flightgoggles_uav_dynamics", "velocity_controller_node", "angle_controller_node"}
    pc = node(lab, "position_controller_node")
    assert pc.mode == "lab"
    assert pc.period_s == pytest.approx(0.01)
    assert _ends(lab, "/uav/input/velocity") == ({"position_controller_node"}, {"SimpleSimNode"})
