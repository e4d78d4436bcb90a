"""sensor_msgs_py.point_cloud2: a cloud built and read back, its layout as its PointFields say,
NaNs skipped, a big-endian cloud read as numbers, and a cloud's bytes through CDR unchanged."""

from __future__ import annotations

import math
import struct

import numpy as np
import pytest
from sensor_msgs.msg import PointCloud2, PointField
from sensor_msgs_py import point_cloud2
from std_msgs.msg import Header

from node_runtime.transport.cdr import decode, encode

NAN = float("nan")


def xyzi_fields() -> list[PointField]:
    """x, y, z float32, a uint8 intensity after a gap, and a float64 time, in a 24-byte point."""
    return [
        PointField(name="x", offset=0, datatype=PointField.FLOAT32, count=1),
        PointField(name="y", offset=4, datatype=PointField.FLOAT32, count=1),
        PointField(name="z", offset=8, datatype=PointField.FLOAT32, count=1),
        PointField(name="intensity", offset=13, datatype=PointField.UINT8, count=1),
        PointField(name="t", offset=16, datatype=PointField.FLOAT64, count=1),
    ]


def test_dtype_from_fields_puts_each_field_at_its_offset_with_its_type() -> None:
    dtype = point_cloud2.dtype_from_fields(xyzi_fields(), point_step=32)
    assert dtype.names == ("x", "y", "z", "intensity", "t")
    assert [dtype.fields[n][1] for n in dtype.names] == [0, 4, 8, 13, 16]  # type: ignore[index]
    assert [dtype[n] for n in dtype.names] == [np.float32] * 3 + [np.uint8, np.float64]
    assert dtype.itemsize == 32
    counted = point_cloud2.dtype_from_fields(
        [PointField(name="rgb", offset=2, datatype=PointField.UINT16, count=3)]
    )
    assert counted.names == ("rgb_0", "rgb_1", "rgb_2")
    assert [counted.fields[n][1] for n in counted.names] == [2, 4, 6]  # type: ignore[index]
    unnamed = point_cloud2.dtype_from_fields([PointField(offset=0, datatype=PointField.INT8, count=1)])
    assert unnamed.names == ("unnamed_field_0",)


def test_a_cloud_built_from_tuples_reads_back_the_same_points() -> None:
    points = [(1.0, 2.0, 3.0, 7, 0.5), (-1.5, 0.25, 8.0, 255, 1e9)]
    cloud = point_cloud2.create_cloud(Header(frame_id="lidar"), xyzi_fields(), points)
    assert (cloud.height, cloud.width, cloud.point_step, cloud.row_step) == (1, 2, 24, 48)
    assert len(cloud.data) == 48 and not cloud.is_dense and cloud.header.frame_id == "lidar"
    # The bytes lie where the fields say: the second point's intensity is byte 24 + 13.
    assert cloud.data[24 + 13] == 255
    assert struct.unpack_from("<d", bytes(cloud.data), 24 + 16)[0] == 1e9
    read = point_cloud2.read_points(cloud)
    assert read.dtype.names == ("x", "y", "z", "intensity", "t")
    assert [tuple(p) for p in read.tolist()] == points
    listed = point_cloud2.read_points_list(cloud, field_names=["z", "intensity"])
    assert [(p.z, p.intensity) for p in listed] == [(3.0, 7), (8.0, 255)]


def test_create_cloud_xyz32_from_an_array_and_read_points_numpy() -> None:
    xyz = np.array([[0.0, 1.0, 2.0], [3.0, 4.0, 5.0], [6.0, 7.0, 8.0]], dtype=np.float32)
    cloud = point_cloud2.create_cloud_xyz32(Header(), xyz)
    assert [(f.name, f.offset, f.datatype, f.count) for f in cloud.fields] == [
        ("x", 0, PointField.FLOAT32, 1),
        ("y", 4, PointField.FLOAT32, 1),
        ("z", 8, PointField.FLOAT32, 1),
    ]
    assert cloud.point_step == 12 and cloud.width == 3
    assert np.array_equal(point_cloud2.read_points_numpy(cloud), xyz)
    structured = point_cloud2.read_points(cloud)
    again = point_cloud2.create_cloud_xyz32(Header(), structured)
    assert bytes(again.data) == bytes(cloud.data)


def test_skip_nans_drops_points_with_a_nan_in_a_field_read_unless_the_cloud_is_dense() -> None:
    cloud = point_cloud2.create_cloud_xyz32(Header(), [(1.0, 2.0, 3.0), (NAN, 0.0, 0.0), (4.0, 5.0, NAN)])
    assert len(point_cloud2.read_points(cloud)) == 3
    assert point_cloud2.read_points_list(cloud, skip_nans=True) == [(1.0, 2.0, 3.0)]
    # Only the fields read count: z's NaN is not among x and y.
    kept = point_cloud2.read_points(cloud, field_names=["x", "y"], skip_nans=True)
    assert kept.tolist() == [(1.0, 2.0), (4.0, 5.0)]
    cloud.is_dense = True  # a dense cloud says it has no invalid points: nothing is dropped
    assert len(point_cloud2.read_points(cloud, skip_nans=True)) == 3


def test_a_big_endian_cloud_reads_as_its_numbers() -> None:
    fields = [
        PointField(name="x", offset=0, datatype=PointField.FLOAT32, count=1),
        PointField(name="id", offset=4, datatype=PointField.UINT16, count=1),
    ]
    data = struct.pack(">fHxx", 1.5, 513) + struct.pack(">fHxx", -2.0, 7)
    cloud = PointCloud2(
        height=1, width=2, fields=fields, is_bigendian=True, point_step=8, row_step=16, data=data
    )
    assert point_cloud2.read_points_list(cloud) == [(1.5, 513), (-2.0, 7)]


def test_uvs_pick_points_of_an_organized_cloud_by_pixel() -> None:
    points = [(float(i), 0.0, 0.0) for i in range(6)]
    cloud = point_cloud2.create_cloud_xyz32(Header(), points)
    cloud.height, cloud.width, cloud.row_step = 2, 3, 36  # two rows of three
    picked = point_cloud2.read_points_list(cloud, field_names=["x"], uvs=[(0, 0), (2, 1), (1, 1)])
    assert [p.x for p in picked] == [0.0, 5.0, 4.0]
    assert [p.x for p in point_cloud2.read_points_list(cloud, uvs=[3])] == [3.0]


def test_a_cloud_through_cdr_keeps_its_points() -> None:
    cloud = point_cloud2.create_cloud(Header(frame_id="map"), xyzi_fields(), [(1.0, 2.0, 3.0, 9, math.pi)])
    back = decode(PointCloud2, encode(cloud))
    assert isinstance(back, PointCloud2)
    assert point_cloud2.read_points_list(back) == [(1.0, 2.0, 3.0, 9, math.pi)]


def test_bad_input_is_refused_with_what_was_wrong() -> None:
    with pytest.raises(TypeError, match="PointCloud2"):
        point_cloud2.read_points(Header())  # type: ignore[arg-type]
    cloud = point_cloud2.create_cloud_xyz32(Header(), [(1.0, 2.0, 3.0)])
    with pytest.raises(ValueError, match="no field"):
        point_cloud2.read_points(cloud, field_names=["rgb"])
    with pytest.raises(ValueError, match="datatype 42"):
        point_cloud2.dtype_from_fields([PointField(name="q", datatype=42, count=1)])
