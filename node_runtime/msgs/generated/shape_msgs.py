"""shape_msgs: generated from ROS 2's definitions (the wheels node_runtime/msgs/ros_packages.txt pins) by `python -m node_runtime.msgs.generate`; do not edit."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any, ClassVar

if TYPE_CHECKING:
    import numpy as np
    import numpy.typing as npt

from node_runtime.msgs._base import Message
from node_runtime.msgs._field import FloatArray
from node_runtime.msgs.generated.geometry_msgs import Point, Polygon


class MeshTriangle(Message, type_name="shape_msgs/msg/MeshTriangle"):
    """shape_msgs/msg/MeshTriangle: Definition of a triangle's vertices."""

    __slots__ = ("vertex_indices",)
    vertex_indices: npt.NDArray[np.uint32]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            vertex_indices: Sequence[int] | npt.NDArray[Any] = ...,
        ) -> None: ...


class Mesh(Message, type_name="shape_msgs/msg/Mesh"):
    """shape_msgs/msg/Mesh: Definition of a mesh."""

    __slots__ = (
        "triangles",
        "vertices",
    )
    triangles: list[MeshTriangle]
    vertices: list[Point]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            triangles: Sequence[MeshTriangle] = ...,
            vertices: Sequence[Point] = ...,
        ) -> None: ...


class Plane(Message, type_name="shape_msgs/msg/Plane"):
    """shape_msgs/msg/Plane: Representation of a plane, using the plane equation ax + by + cz + d = 0."""

    __slots__ = ("coef",)
    coef: npt.NDArray[np.float64]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            coef: Sequence[float] | npt.NDArray[Any] = ...,
        ) -> None: ...


class SolidPrimitive(Message, type_name="shape_msgs/msg/SolidPrimitive"):
    """shape_msgs/msg/SolidPrimitive: Defines box, sphere, cylinder, cone and prism."""

    __slots__ = (
        "type",
        "dimensions",
        "polygon",
    )
    BOX: ClassVar[int]
    SPHERE: ClassVar[int]
    CYLINDER: ClassVar[int]
    CONE: ClassVar[int]
    PRISM: ClassVar[int]
    BOX_X: ClassVar[int]
    BOX_Y: ClassVar[int]
    BOX_Z: ClassVar[int]
    SPHERE_RADIUS: ClassVar[int]
    CYLINDER_HEIGHT: ClassVar[int]
    CYLINDER_RADIUS: ClassVar[int]
    CONE_HEIGHT: ClassVar[int]
    CONE_RADIUS: ClassVar[int]
    PRISM_HEIGHT: ClassVar[int]
    type: int
    dimensions: FloatArray
    polygon: Polygon

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            type: int = ...,
            dimensions: Sequence[float] | npt.NDArray[Any] = ...,
            polygon: Polygon = ...,
        ) -> None: ...


__all__ = [
    "Mesh",
    "MeshTriangle",
    "Plane",
    "SolidPrimitive",
]
