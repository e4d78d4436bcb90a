"""sensor_msgs_py.point_cloud2: a PointCloud2's points as numpy structured arrays, as ROS 2's own.

A cloud's ``fields`` say where each value lies in a point (``offset``), its type
(``datatype``, a PointField constant) and how many there are (``count``); ``point_step`` is a
point's size in bytes and ``data`` the points one after another, row by row. ``read_points``
views ``data`` through the numpy dtype those fields describe; ``create_cloud`` packs points into
a new cloud with the machine's byte order.
"""

from __future__ import annotations

import array
import sys
from collections import namedtuple
from collections.abc import Iterable, Sequence
from typing import Any, NamedTuple

import numpy as np
import numpy.typing as npt
from numpy.lib.recfunctions import unstructured_to_structured
from sensor_msgs.msg import PointCloud2, PointField
from std_msgs.msg import Header

__all__ = [
    "DUMMY_FIELD_PREFIX",
    "create_cloud",
    "create_cloud_xyz32",
    "dtype_from_fields",
    "read_points",
    "read_points_list",
    "read_points_numpy",
]

# The name a field without one gets (``unnamed_field_<its index>``).
DUMMY_FIELD_PREFIX = "unnamed_field"

_DATATYPES: dict[int, np.dtype[Any]] = {
    PointField.INT8: np.dtype(np.int8),
    PointField.UINT8: np.dtype(np.uint8),
    PointField.INT16: np.dtype(np.int16),
    PointField.UINT16: np.dtype(np.uint16),
    PointField.INT32: np.dtype(np.int32),
    PointField.UINT32: np.dtype(np.uint32),
    PointField.FLOAT32: np.dtype(np.float32),
    PointField.FLOAT64: np.dtype(np.float64),
}


def dtype_from_fields(fields: Iterable[PointField], point_step: int | None = None) -> np.dtype[Any]:
    """The structured dtype of one point: each field at its offset (a field with ``count`` n > 1
    is n values, ``name_0`` ... ``name_<n-1>``), the whole ``point_step`` bytes long if given."""
    names: list[str] = []
    formats: list[np.dtype[Any]] = []
    offsets: list[int] = []
    for i, field in enumerate(fields):
        if field.datatype not in _DATATYPES:
            raise ValueError(f"PointField {field.name!r}: unknown datatype {field.datatype}")
        datatype = _DATATYPES[field.datatype]
        name = field.name or f"{DUMMY_FIELD_PREFIX}_{i}"
        if field.count == 1:
            names.append(name)
            formats.append(datatype)
            offsets.append(field.offset)
            continue
        for k in range(field.count):
            names.append(f"{name}_{k}")
            formats.append(datatype)
            offsets.append(field.offset + k * datatype.itemsize)
    if point_step is None:
        return np.dtype({"names": names, "formats": formats, "offsets": offsets})
    return np.dtype({"names": names, "formats": formats, "offsets": offsets, "itemsize": point_step})


def read_points(
    cloud: PointCloud2,
    field_names: Sequence[str] | None = None,
    skip_nans: bool = False,
    uvs: Iterable[int] | Iterable[tuple[int, int]] | None = None,
    reshape_organized_cloud: bool = False,
) -> npt.NDArray[Any]:
    """The cloud's points as a structured array (only ``field_names`` if given; without the points
    where one of those is NaN if ``skip_nans`` and the cloud is not dense; only the points at
    ``uvs``, indices or (u, v) pixels, if given)."""
    if not isinstance(cloud, PointCloud2):
        raise TypeError(f"cloud is not a sensor_msgs.msg.PointCloud2 but {type(cloud).__name__}")
    dtype = dtype_from_fields(cloud.fields, point_step=cloud.point_step)
    if cloud.is_bigendian:
        dtype = dtype.newbyteorder(">")
    points: npt.NDArray[Any] = np.ndarray(
        shape=(cloud.width * cloud.height,), dtype=dtype, buffer=memoryview(cloud.data)
    )
    if field_names is not None:
        missing = [name for name in field_names if name not in (dtype.names or ())]
        if missing:
            raise ValueError(f"the cloud has no field(s) {', '.join(missing)} (it has {dtype.names})")
        points = points[list(field_names)]
    if cloud.is_bigendian != (sys.byteorder == "big"):  # values in the machine's byte order
        points = points.astype(points.dtype.newbyteorder("="))
    if skip_nans and not cloud.is_dense:
        keep = np.ones(len(points), dtype=bool)
        for name in points.dtype.names or ():
            if points.dtype[name].kind == "f":
                keep &= ~np.isnan(points[name])
        points = points[keep]
    if uvs is not None:
        indices = [uv if isinstance(uv, int) else uv[1] * cloud.width + uv[0] for uv in uvs]
        points = points[indices]
    if reshape_organized_cloud and cloud.height > 1:
        points = points.reshape(cloud.width, cloud.height)
    return points


def read_points_numpy(
    cloud: PointCloud2,
    field_names: Sequence[str] | None = None,
    skip_nans: bool = False,
    uvs: Iterable[int] | Iterable[tuple[int, int]] | None = None,
    reshape_organized_cloud: bool = False,
) -> npt.NDArray[Any]:
    """As ``read_points``, as a plain two-dimensional array (one row per point); every field read
    must have the same type."""
    points = read_points(cloud, field_names, skip_nans, uvs, reshape_organized_cloud)
    types = {points.dtype[name] for name in points.dtype.names or ()}
    if len(types) != 1:
        raise ValueError(f"the fields read have different types ({sorted(map(str, types))})")
    names = list(points.dtype.names or ())
    return np.stack([points[name] for name in names], axis=-1)


def read_points_list(
    cloud: PointCloud2,
    field_names: Sequence[str] | None = None,
    skip_nans: bool = False,
    uvs: Iterable[int] | Iterable[tuple[int, int]] | None = None,
) -> list[NamedTuple]:
    """As ``read_points``, as a list of named tuples (``point.x``)."""
    points = read_points(cloud, field_names, skip_nans, uvs)
    point = namedtuple("Point", points.dtype.names or ())  # type: ignore[misc]  # names from the cloud
    return [point._make(values) for values in points.tolist()]


def create_cloud(
    header: Header, fields: Sequence[PointField], points: Any, point_step: int | None = None
) -> PointCloud2:
    """A cloud of ``points`` (a structured array, a two-dimensional array with a column per value,
    or a list of tuples) laid out as ``fields`` say, one row, not dense."""
    dtype = dtype_from_fields(fields, point_step)
    if isinstance(points, np.ndarray) and points.dtype.names is not None:
        packed = points.astype(dtype) if points.dtype != dtype else points
    elif isinstance(points, np.ndarray):
        packed = unstructured_to_structured(points, dtype=dtype)
    else:
        packed = np.array([tuple(p) for p in points], dtype=dtype)
    cloud = PointCloud2(
        header=header,
        height=1,
        width=len(packed),
        is_dense=False,
        is_bigendian=sys.byteorder == "big",
        fields=list(fields),
        point_step=dtype.itemsize,
        row_step=dtype.itemsize * len(packed),
    )
    cloud.data = array.array("B", np.ascontiguousarray(packed).tobytes())
    return cloud


def create_cloud_xyz32(header: Header, points: Any) -> PointCloud2:
    """A cloud of x, y, z float32 points (12 bytes each)."""
    fields = [
        PointField(name="x", offset=0, datatype=PointField.FLOAT32, count=1),
        PointField(name="y", offset=4, datatype=PointField.FLOAT32, count=1),
        PointField(name="z", offset=8, datatype=PointField.FLOAT32, count=1),
    ]
    return create_cloud(header, fields, points)
