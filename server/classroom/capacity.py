"""Whether the class has room for another world: the instructor's load panel and the join queue
read one verdict, ``ok``, ``near`` or ``full``, made from each place's worlds and CPU (load.py) and
how many worlds are late (lateness.py).

- ``full``: no place has room for another world by count (every place at its ``max_worlds``,
  or no world worker answers and this server hosts none itself) or by its machine's world budget
  (budget.py: ``--worlds-per-core`` for each core), or every place with room is
  saturated (its process uses ``PROCESS_FULL_CORES``; its machine ``HOST_FULL`` busy counts only
  beside another machine, as placement weighs it) **and** at least ``LATE_SHARE_FULL`` of the
  worlds are late. Both, because each alone misleads: a saturated process whose worlds keep time
  still has room, and a late tick on an idle process is a hiccup (a garbage collection, a reset),
  not a full machine. A join then waits in the queue (join_queue.py) instead of slowing everyone.
- ``near``: a place with room is saturated or its process passes ``NEAR_CORES``, a world is late,
  or at most ``NEAR_ROOM`` places for worlds are left (by count and budget). Joins still go
  ahead; the page warns.
- ``ok``: none of these.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Literal

from server.classroom.budget import MachineBudget, budgets, machine_of, spent
from server.classroom.load import CpuLoad

Verdict = Literal["ok", "near", "full"]
NEAR_CORES = 0.6  # a process's loop thread past 60 % of a core: the next worlds will crowd it
LATE_SHARE_FULL = 0.25  # a quarter of the worlds late (and no place with idle CPU): full
NEAR_ROOM = 2  # places for worlds left (by count and budget) at which the panel warns
SERVER_PLACE = "server"  # the class server itself, among the places worlds run


@dataclass(frozen=True)
class PlaceLoad:
    """One place worlds run: this class server (``place`` "server") or a world worker (its id)."""

    place: str
    worlds: int
    max_worlds: int
    load: CpuLoad | None  # None: it did not say
    late: int | None  # worlds late there; None: it did not say

    @property
    def room(self) -> int:
        return max(0, self.max_worlds - self.worlds)

    def describe(self) -> dict[str, Any]:
        return {
            "place": self.place,
            "worlds": self.worlds,
            "max_worlds": self.max_worlds,
            "late": self.late,
            "cpu": None if self.load is None else self.load.describe(),
        }


@dataclass(frozen=True)
class Capacity:
    """The verdict and why, from the places' loads at one moment."""

    verdict: Verdict
    reasons: tuple[str, ...]
    worlds: int
    late: int
    # Places for worlds left by count and budget, over every place (capped by the class's max_worlds).
    room: int
    machines: tuple[MachineBudget, ...] = ()  # each machine's world budget (none without one)


def _saturated(load: CpuLoad | None, machines: int) -> bool:
    if load is None:
        return False
    return load.process_full or (load.host_full and machines > 1)


def judge(places: list[PlaceLoad], class_room: int, per_core: int = 0) -> Capacity:
    """The verdict over ``places``; ``class_room`` is how many more worlds the class's
    ``max_worlds`` allows (a class at its cap is refused at the door, not queued); ``per_core``
    the worlds a machine runs for each of its cores (0: no budget)."""
    worlds = sum(p.worlds for p in places)
    late = sum(p.late or 0 for p in places)
    machines = budgets(((p.place, p.worlds, p.load) for p in places), per_core)
    by_count = [p for p in places if p.room > 0]
    open_places = [p for p in by_count if not spent(machines, p.place, p.load)]
    room = min(class_room, _room(open_places, machines))
    machine_count = len({p.load.machine for p in places if p.load is not None})
    full: list[str] = []
    near: list[str] = []
    if not by_count:
        full.append("no place has room for another world (every place is at its max_worlds)")
    elif not open_places:
        used = ", ".join(f"{b.worlds} worlds on {b.cores} cores" for b in machines.values() if b.room == 0)
        full.append(
            f"every place with room is on a machine at its world budget ({per_core} worlds a core: {used})"
        )
    elif all(_saturated(p.load, machine_count) for p in open_places):
        busy = "the CPU of every place with room is saturated"
        if worlds and late >= max(1, math.ceil(LATE_SHARE_FULL * worlds)):
            full.append(f"{busy} and {late} of {worlds} worlds are late")
        else:
            near.append(busy)
    else:
        crowded = [p.place for p in open_places if _saturated(p.load, machine_count)]
        crowded += [
            p.place
            for p in open_places
            if p.load is not None
            and not _saturated(p.load, machine_count)
            and p.load.process_cores >= NEAR_CORES
        ]
        if crowded:
            near.append(f"busy CPU on {', '.join(crowded)}")
    if late and not full:
        near.append(f"{late} of {worlds} worlds are late")
    if 0 < room <= NEAR_ROOM and not full:
        near.append(f"room for {room} more world{'s' if room != 1 else ''}")
    verdict: Verdict = "full" if full else "near" if near else "ok"
    return Capacity(verdict, tuple(full or near), worlds, late, room, tuple(machines.values()))


def _room(places: list[PlaceLoad], machines: dict[str, MachineBudget]) -> int:
    """Worlds that fit over ``places``: each place's room by count, but no more on a machine than
    its budget has left (places on one machine share it)."""
    unbudgeted = 0
    on: dict[str, int] = {}
    for p in places:
        key = machine_of(p.place, p.load)
        if key is None or key not in machines:
            unbudgeted += p.room
        else:
            on[key] = on.get(key, 0) + p.room
    return unbudgeted + sum(min(count, machines[key].room) for key, count in on.items())
