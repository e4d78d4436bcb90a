"""Drone ids, their records, and the columns they own in a batch's arrays, as drones join and leave."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Generic, Protocol, TypeVar

import numpy as np
import numpy.typing as npt


class DroneRemovedError(LookupError):
    """The drone id is not, or no longer, in the batch."""


@dataclass
class DroneRecord:
    """What a batch keeps about one drone besides its columns."""

    rng: np.random.Generator | None
    """Its own noise generator; None when it has no noise."""
    start_step: int
    """The batch's step count when it joined or was last reset: its clock reads from there."""
    fault: str | None = None


class SlotTable:
    """Named arrays whose last axis is the drone, one column per drone, and each column's id and record.

    Ids are handed out in increasing order and never reused, so a handle kept by a world that
    has left cannot reach the drone of a world that joined later. A drone joins as a new last
    column of zeros; a drone that leaves takes its column out and the columns after it move up
    by one. Every array is reallocated at its exact new size, so the physics works on whole
    contiguous arrays; joins and leaves are rare beside steps.
    """

    def __init__(self, shapes: dict[str, tuple[tuple[int, ...], type]]) -> None:
        self.arrays: dict[str, npt.NDArray[Any]] = {
            name: np.zeros((*leading, 0), dtype=dtype) for name, (leading, dtype) in shapes.items()
        }
        self._ids: list[int] = []
        self._columns: dict[int, int] = {}
        self._records: dict[int, DroneRecord] = {}
        self._next_id = 0

    def __len__(self) -> int:
        return len(self._ids)

    @property
    def ids(self) -> tuple[int, ...]:
        """Drone ids in column order."""
        return tuple(self._ids)

    @property
    def records(self) -> list[DroneRecord]:
        """Drone records in column order."""
        return [self._records[i] for i in self._ids]

    def column(self, drone_id: int) -> int:
        """The column of drone_id, or DroneRemovedError."""
        try:
            return self._columns[drone_id]
        except KeyError:
            raise DroneRemovedError(f"no drone {drone_id} in this batch") from None

    def record(self, drone_id: int) -> DroneRecord:
        """The record of drone_id, or DroneRemovedError."""
        self.column(drone_id)
        return self._records[drone_id]

    def add(self, rng: np.random.Generator | None, start_step: int) -> int:
        """A new drone id with a zeroed last column in every array. ValueError if rng is another drone's."""
        if rng is not None and any(r.rng is rng for r in self._records.values()):
            # Two drones drawing from one generator would each replay differently with the other gone.
            raise ValueError(
                "each drone needs its own numpy.random.Generator: this rng is already in the batch"
            )
        for name, array in self.arrays.items():
            self.arrays[name] = np.concatenate(
                [array, np.zeros((*array.shape[:-1], 1), array.dtype)], axis=-1
            )
        drone_id = self._next_id
        self._next_id += 1
        self._columns[drone_id] = len(self._ids)
        self._ids.append(drone_id)
        self._records[drone_id] = DroneRecord(rng, start_step)
        return drone_id

    def remove(self, drone_id: int) -> None:
        """Drop drone_id's column from every array, and its record."""
        column = self.column(drone_id)
        for name, array in self.arrays.items():
            self.arrays[name] = np.delete(array, column, axis=-1)
        del self._ids[column]
        del self._records[drone_id]
        self._columns = {i: c for c, i in enumerate(self._ids)}


class _Batch(Protocol):
    def time_s(self, drone_id: int) -> float: ...

    def remove(self, drone_id: int) -> None: ...


BatchT = TypeVar("BatchT", bound=_Batch)


class DroneHandle(Generic[BatchT]):
    """One drone of a batch, by id: read it and command it between the batch's steps."""

    __slots__ = ("_batch", "id")

    def __init__(self, batch: BatchT, drone_id: int) -> None:
        self._batch = batch
        self.id = drone_id

    @property
    def time_s(self) -> float:
        """Its simulated time since it joined or was reset (s)."""
        return self._batch.time_s(self.id)

    def remove(self) -> None:
        """Take it out of its batch; the others keep their state and their replay."""
        self._batch.remove(self.id)
