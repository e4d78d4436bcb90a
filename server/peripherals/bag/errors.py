"""What recording and playing refuse, each mapped once to a status in api/errors.py."""

from __future__ import annotations


class BagError(ValueError):
    """A request the bag tools cannot take: a bad name, nothing to record, a file that is not a bag
    this lab can play, a rate out of range."""


class BagNotFoundError(LookupError):
    """No recording, bag or playback with that name or id."""


class BagExistsError(RuntimeError):
    """A bag with that name is already in the bag folder."""


class BagBusyError(RuntimeError):
    """The bag is still being recorded: stop it first."""


class BagLimitError(RuntimeError):
    """Too many recordings or playbacks at once."""
