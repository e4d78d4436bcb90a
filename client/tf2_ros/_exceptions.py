"""tf2's exceptions, as ``tf2_ros`` re-exports them: ``TransformException`` and its kinds."""

from __future__ import annotations


class TransformException(Exception):
    """Any failure to give a transform (tf2's base class: catch this one)."""


class LookupException(TransformException):
    """A frame the buffer has never heard of (or a tree with a loop)."""


class ConnectivityException(TransformException):
    """Both frames are known, but no chain of parents joins them."""


class ExtrapolationException(TransformException):
    """The chain exists, but not at the time asked: before the oldest or after the newest data."""


class InvalidArgumentException(TransformException):
    """A frame name tf2 does not take (empty, or starting with '/')."""


class TimeoutException(TransformException):
    """A wait for a transform ran out of time."""


__all__ = [
    "ConnectivityException",
    "ExtrapolationException",
    "InvalidArgumentException",
    "LookupException",
    "TimeoutException",
    "TransformException",
]
