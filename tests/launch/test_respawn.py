"""``RespawnBackoff`` on a ManualClock, and the launcher using it: delays double up to a cap, a
healthy run resets them, the launcher gives up after N fast failures and the node list says so."""

from __future__ import annotations

from pathlib import Path

import pytest

from node_runtime.bus import ManualClock, Node
from server.host.settings import LabSettings, Settings
from server.services.launch.respawn import RespawnBackoff, RespawnPolicy
from server.world.lab import Lab

POLICY = RespawnPolicy(base_delay_s=0.5, max_delay_s=4.0, healthy_after_s=10.0, max_fast_failures=5)


def test_respawn_fast_failures_double_the_delay_up_to_the_cap_then_give_up() -> None:
    clock = ManualClock()
    backoff = RespawnBackoff(POLICY, clock)
    delays = []
    for _ in range(6):
        clock.advance(0.1)  # crashes 0.1 s after each start
        delay = backoff.crashed()
        delays.append(delay)
        if delay is not None:
            clock.advance(delay)
            backoff.started()
    assert delays == [0.5, 1.0, 2.0, 4.0, 4.0, None]
    assert backoff.describe() == {"state": "gave up", "respawns": 5, "fast_failures": 6, "next_in_s": None}


def test_respawn_a_healthy_run_starts_the_backoff_again() -> None:
    clock = ManualClock()
    backoff = RespawnBackoff(POLICY, clock)
    clock.advance(1.0)
    assert backoff.crashed() == 0.5
    backoff.started()
    clock.advance(1.0)
    assert backoff.crashed() == 1.0
    backoff.started()
    clock.advance(POLICY.healthy_after_s)
    assert backoff.crashed() == 0.5
    assert backoff.fast_failures == 1


def test_respawn_launch_files_delay_is_a_minimum() -> None:
    clock = ManualClock()
    backoff = RespawnBackoff(POLICY, clock)
    assert backoff.crashed(minimum_delay_s=3.0) == 3.0
    assert backoff.describe()["state"] == "waiting"
    clock.advance(1.0)
    assert backoff.describe()["next_in_s"] == pytest.approx(2.0)


@pytest.mark.parametrize(
    "policy",
    [
        {"base_delay_s": 0.0},
        {"base_delay_s": 5.0, "max_delay_s": 1.0},
        {"healthy_after_s": 0.0},
        {"max_fast_failures": 0},
        {"base_delay_s": float("nan")},
    ],
)
def test_respawn_inconsistent_policy_refused(policy: dict[str, float]) -> None:
    with pytest.raises(ValueError, match="inconsistent respawn policy"):
        RespawnPolicy(**policy)  # type: ignore[arg-type]


class Flaky(Node):
    """A lab node (inside the app) that raises at its first tick."""

    def __init__(self) -> None:
        super().__init__("flaky")
        self.create_timer(0.05, self.tick)

    def tick(self) -> None:
        raise RuntimeError("crash at once")


def test_respawn_launcher_backs_off_and_gives_up_shown_in_the_node_list(tmp_path: Path) -> None:
    launch = tmp_path / "flaky.launch"
    launch.write_text('<launch><node pkg="my_pkg" exec="flaky" name="flaky" respawn="true"/></launch>')
    lab = Lab(Settings(lab=LabSettings(launch="rocket", viewer=False, workspace=None)), ManualClock(0.0))
    lab.packages.executables["my_pkg"] = {"flaky": Flaky}
    lab.start_nodes()
    lab.launch_groups.launch(launch, {})
    entry = next(e for e in lab.launcher.launched if e.action.exec == "flaky")

    lab.executor.spin_until(20.0)

    policy = lab.launcher.respawn_policy
    assert entry.starts == policy.max_fast_failures + 1, "no more respawns once it gave up"
    node = lab.bus.get_node("flaky")
    assert node.state == "crashed"
    assert lab.launcher.respawn_of(node) is entry.respawn
    assert entry.respawn is not None and entry.respawn.describe()["state"] == "gave up"
