"""tf2_ros' BufferInterface: what every buffer answers (lookups, checks) and ``transform`` for
stamped types a package has registered a transform function for."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, ClassVar

from rclpy.duration import Duration

NO_WAIT = Duration()  # a lookup's default timeout: answer from what is there now


class TypeException(Exception):
    """A type nobody registered a transform function for."""

    def __init__(self, errstr: str) -> None:
        super().__init__(errstr)
        self.errstr = errstr


class NotImplementedException(Exception):
    """A BufferInterface subclass without lookups of its own."""

    def __init__(self) -> None:
        self.errstr = "CanTransform or LookupTransform not implemented"
        super().__init__(self.errstr)


class TransformRegistration:
    """Transform functions by the type they transform (``tf2_geometry_msgs`` registers its own)."""

    _functions: ClassVar[dict[type, Callable[[Any, Any], Any]]] = {}

    def add(self, key: type, callback: Callable[[Any, Any], Any]) -> None:
        TransformRegistration._functions[key] = callback

    def get(self, key: type) -> Callable[[Any, Any], Any]:
        if key not in TransformRegistration._functions:
            raise TypeException(f"Type {key} is not loaded or supported")
        return TransformRegistration._functions[key]


class BufferInterface:
    """The abstract buffer: subclasses give the lookups, this gives ``transform``."""

    def __init__(self) -> None:
        self.registration = TransformRegistration()

    def transform(
        self, object_stamped: Any, target_frame: str, timeout: Duration = NO_WAIT, new_type: Any = None
    ) -> Any:
        """``object_stamped`` (it has a ``header``) expressed in ``target_frame``."""
        do_transform = self.registration.get(type(object_stamped))
        header = object_stamped.header
        res = do_transform(
            object_stamped, self.lookup_transform(target_frame, header.frame_id, header.stamp, timeout)
        )
        return _as(res, new_type)

    def transform_full(
        self,
        object_stamped: Any,
        target_frame: str,
        target_time: Any,
        fixed_frame: str,
        timeout: Duration = NO_WAIT,
        new_type: Any = None,
    ) -> Any:
        do_transform = self.registration.get(type(object_stamped))
        header = object_stamped.header
        transform = self.lookup_transform_full(
            target_frame, target_time, header.frame_id, header.stamp, fixed_frame, timeout
        )
        return _as(do_transform(object_stamped, transform), new_type)

    def lookup_transform(
        self, target_frame: str, source_frame: str, time: Any, timeout: Duration = NO_WAIT
    ) -> Any:
        raise NotImplementedException()

    def lookup_transform_full(
        self,
        target_frame: str,
        target_time: Any,
        source_frame: str,
        source_time: Any,
        fixed_frame: str,
        timeout: Duration = NO_WAIT,
    ) -> Any:
        raise NotImplementedException()

    def can_transform(
        self, target_frame: str, source_frame: str, time: Any, timeout: Duration = NO_WAIT
    ) -> bool:
        raise NotImplementedException()

    def can_transform_full(
        self,
        target_frame: str,
        target_time: Any,
        source_frame: str,
        source_time: Any,
        fixed_frame: str,
        timeout: Duration = NO_WAIT,
    ) -> bool:
        raise NotImplementedException()


def _as(result: Any, new_type: Any) -> Any:
    if new_type is None or isinstance(result, new_type):
        return result
    raise TypeException(f"Type {new_type} is not loaded or supported")


__all__ = ["NO_WAIT", "BufferInterface", "NotImplementedException", "TransformRegistration", "TypeException"]
