"""A machine's world budget (``--worlds-per-core``): how many worlds the places on one machine (the
class server, the world workers it started beside itself, workers in containers on the same host)
run between them, so many for each of its cores.

A process's CPU and its worlds' lateness say a machine is full only once its worlds have slowed;
worse, a class joins in a minute with no node running and starts its nodes afterwards, when every
join is already in. The budget says it before: a machine that has its budget takes no more worlds
while another has room, and a class whose machines all have theirs is full, so the next join
waits in the queue (capacity.py, join_queue.py) instead of slowing every world. Places are grouped
by the machine their hello names (load.py's digest of the boot id; a place that names none is a
machine of its own), and a machine's cores are the most any of its places may run on. A place
that reports no load is not budgeted: nothing says which machine it is on.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass
from typing import Any

from server.classroom.load import Choice, CpuLoad, Ref


@dataclass(frozen=True)
class MachineBudget:
    machine: str
    worlds: int  # on every place of this machine
    cores: int
    most: int  # worlds per core times cores

    @property
    def room(self) -> int:
        return max(0, self.most - self.worlds)

    def describe(self) -> dict[str, Any]:
        return {"machine": self.machine, "worlds": self.worlds, "cores": self.cores, "budget": self.most}


def machine_of(place: str, load: CpuLoad | None) -> str | None:
    """The machine ``place`` runs on, as budgets key it; None when it reported no load."""
    if load is None:
        return None
    return load.machine or f"place:{place}"


def budgets(places: Iterable[tuple[str, int, CpuLoad | None]], per_core: int) -> dict[str, MachineBudget]:
    """Each machine's budget over ``places`` (place, worlds, load); none when ``per_core`` is 0."""
    if per_core <= 0:
        return {}
    worlds: dict[str, int] = {}
    cores: dict[str, int] = {}
    for place, count, load in places:
        key = machine_of(place, load)
        if key is None or load is None:
            continue
        worlds[key] = worlds.get(key, 0) + count
        cores[key] = max(cores.get(key, 1), load.cores)
    return {key: MachineBudget(key, worlds[key], cores[key], per_core * cores[key]) for key in cores}


def spent(machines: dict[str, MachineBudget], place: str, load: CpuLoad | None) -> bool:
    """Whether the machine of ``place`` has used its budget."""
    key = machine_of(place, load)
    return key is not None and key in machines and machines[key].room == 0


def within_budget(
    choices: list[tuple[str, Choice[Ref]]], places: Iterable[tuple[str, int, CpuLoad | None]], per_core: int
) -> list[Choice[Ref]]:
    """The ``choices`` (place, choice) on machines with budget left, weighed over every place
    (those at their count too: their worlds are on the machine); all of them when none has any
    (the instructor let a join past a full class: it still goes somewhere)."""
    machines = budgets(places, per_core)
    left = [choice for place, choice in choices if not spent(machines, place, choice.load)]
    return left or [choice for _, choice in choices]
