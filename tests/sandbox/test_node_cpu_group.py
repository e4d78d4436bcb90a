"""Students' nodes weigh as one CPU group against the worlds, however many they are
(server/host/processes/cgroups.py), where at nice 19 in sessions of their own (as a sandbox makes
them) they weighed 15 each, and forty of them took a third of a core from a world's loop beside
them.

Read on the kernel itself, as root: a stand-in server (a child process calling the same
``cgroups.parent()`` a server calls) starts one busy loop for the worlds (a session of its own at
nice 0, as a server's) and forty busy loops for nodes, each leading its own session at nice 19
with its session's group at 19 too (node_runtime/process/priority.py), all on one CPU, for a few
seconds: once in the nodes' groups the sandbox puts them in, once without. What the worlds' loop
gets of that CPU is the ratio of their CPU times, measured in the same run."""

from __future__ import annotations

import json
import os
import subprocess
import sys

import pytest
from support.app import REPO

pytestmark = pytest.mark.timing  # CPU shares on one core: alone, with no other test loading it

NODES = 40
RUN_S = 1.5
STAND_IN = r"""
import json, os, subprocess, sys, time
from server.host.processes import cgroups

grouped, nodes, run_s = sys.argv[1] == "grouped", int(sys.argv[2]), float(sys.argv[3])
cpu = str(min(os.sched_getaffinity(0)))
spin = "while :; do :; done"
as_node = f"renice -n 19 -p $$ >/dev/null; echo 19 > /proc/$$/autogroup; {spin}"
parent = cgroups.parent()
if grouped and (isinstance(parent, str) or not parent.cpu_weighed):
    print(json.dumps({"why": parent if isinstance(parent, str) else "no cpu controller to weigh nodes"}))
    sys.exit(0)
groups, procs, world = [], [], None
try:
    for i in range(nodes):
        prefix = []
        if grouped:
            groups.append(parent.make(f"spin-{i}", 64, 16))
            prefix = groups[-1].join_prefix()
        procs.append(subprocess.Popen([*prefix, "taskset", "-c", cpu, "sh", "-c", as_node], start_new_session=True))
    world = subprocess.Popen(["taskset", "-c", cpu, "sh", "-c", spin], start_new_session=True)
    time.sleep(run_s)

    def cpu_s(pid):  # to the nanosecond: forty loops sharing a few percent get under a tick each
        return int(open(f"/proc/{pid}/schedstat").read().split()[0]) / 1e9

    print(json.dumps({"world": cpu_s(world.pid), "nodes": sum(cpu_s(p.pid) for p in procs)}))
finally:  # the worlds' loop first: the nodes' loops then have the CPU to end
    for p in [*([world] if world is not None else []), *procs]:
        p.kill()
        p.wait()
    for group in groups:
        group.remove()
"""


def shares(grouped: bool) -> dict[str, float]:
    done = subprocess.run(
        [sys.executable, "-c", STAND_IN, "grouped" if grouped else "apart", str(NODES), str(RUN_S)],
        cwd=REPO,
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.returncode == 0, done.stderr[-2000:]
    result: dict[str, float] = json.loads(done.stdout.strip().splitlines()[-1])
    return result


@pytest.mark.skipif(os.geteuid() != 0, reason="cgroups are made by a root server (as containers run it)")
def test_forty_nodes_take_from_a_worlds_loop_what_one_group_weighs_not_what_forty_sessions_did() -> None:
    grouped = shares(grouped=True)
    if "why" in grouped:
        assert os.environ.get("CI") != "true", f"no CPU group for nodes on the CI machine: {grouped['why']}"
        pytest.skip(f"this machine gives no CPU group for nodes: {grouped['why']}")
    apart = shares(grouped=False)
    world_grouped = grouped["world"] / (grouped["world"] + grouped["nodes"])
    world_apart = apart["world"] / (apart["world"] + apart["nodes"])
    # Apart, forty groups of 15 against the world's 1024: about 0.63 of the CPU for the world.
    assert world_apart < 0.75, apart
    # Together, 64 against 1024: about 0.94; and the nodes still ran.
    assert world_grouped > 0.85, grouped
    assert grouped["nodes"] > 0.01 * RUN_S, grouped
