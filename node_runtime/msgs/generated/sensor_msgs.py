"""sensor_msgs: generated from ROS 2's definitions (the wheels node_runtime/msgs/ros_packages.txt pins) by `python -m node_runtime.msgs.generate`; do not edit."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any, ClassVar

if TYPE_CHECKING:
    import numpy as np
    import numpy.typing as npt

from node_runtime.msgs._base import Message, Service
from node_runtime.msgs._field import FloatArray, IntArray
from node_runtime.msgs.generated.builtin_interfaces import Time
from node_runtime.msgs.generated.geometry_msgs import Point32, Quaternion, Transform, Twist, Vector3, Wrench
from node_runtime.msgs.generated.std_msgs import Header


class BatteryState(Message, type_name="sensor_msgs/msg/BatteryState"):
    """sensor_msgs/msg/BatteryState: Constants are chosen to match the enums in the linux kernel"""

    __slots__ = (
        "header",
        "voltage",
        "temperature",
        "current",
        "charge",
        "capacity",
        "design_capacity",
        "percentage",
        "power_supply_status",
        "power_supply_health",
        "power_supply_technology",
        "present",
        "cell_voltage",
        "cell_temperature",
        "location",
        "serial_number",
    )
    POWER_SUPPLY_STATUS_UNKNOWN: ClassVar[int]
    POWER_SUPPLY_STATUS_CHARGING: ClassVar[int]
    POWER_SUPPLY_STATUS_DISCHARGING: ClassVar[int]
    POWER_SUPPLY_STATUS_NOT_CHARGING: ClassVar[int]
    POWER_SUPPLY_STATUS_FULL: ClassVar[int]
    POWER_SUPPLY_HEALTH_UNKNOWN: ClassVar[int]
    POWER_SUPPLY_HEALTH_GOOD: ClassVar[int]
    POWER_SUPPLY_HEALTH_OVERHEAT: ClassVar[int]
    POWER_SUPPLY_HEALTH_DEAD: ClassVar[int]
    POWER_SUPPLY_HEALTH_OVERVOLTAGE: ClassVar[int]
    POWER_SUPPLY_HEALTH_UNSPEC_FAILURE: ClassVar[int]
    POWER_SUPPLY_HEALTH_COLD: ClassVar[int]
    POWER_SUPPLY_HEALTH_WATCHDOG_TIMER_EXPIRE: ClassVar[int]
    POWER_SUPPLY_HEALTH_SAFETY_TIMER_EXPIRE: ClassVar[int]
    POWER_SUPPLY_TECHNOLOGY_UNKNOWN: ClassVar[int]
    POWER_SUPPLY_TECHNOLOGY_NIMH: ClassVar[int]
    POWER_SUPPLY_TECHNOLOGY_LION: ClassVar[int]
    POWER_SUPPLY_TECHNOLOGY_LIPO: ClassVar[int]
    POWER_SUPPLY_TECHNOLOGY_LIFE: ClassVar[int]
    POWER_SUPPLY_TECHNOLOGY_NICD: ClassVar[int]
    POWER_SUPPLY_TECHNOLOGY_LIMN: ClassVar[int]
    POWER_SUPPLY_TECHNOLOGY_TERNARY: ClassVar[int]
    POWER_SUPPLY_TECHNOLOGY_VRLA: ClassVar[int]
    header: Header
    voltage: float
    temperature: float
    current: float
    charge: float
    capacity: float
    design_capacity: float
    percentage: float
    power_supply_status: int
    power_supply_health: int
    power_supply_technology: int
    present: bool
    cell_voltage: FloatArray
    cell_temperature: FloatArray
    location: str
    serial_number: str

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            header: Header = ...,
            voltage: float = ...,
            temperature: float = ...,
            current: float = ...,
            charge: float = ...,
            capacity: float = ...,
            design_capacity: float = ...,
            percentage: float = ...,
            power_supply_status: int = ...,
            power_supply_health: int = ...,
            power_supply_technology: int = ...,
            present: bool = ...,
            cell_voltage: Sequence[float] | npt.NDArray[Any] = ...,
            cell_temperature: Sequence[float] | npt.NDArray[Any] = ...,
            location: str = ...,
            serial_number: str = ...,
        ) -> None: ...


class RegionOfInterest(Message, type_name="sensor_msgs/msg/RegionOfInterest"):
    """sensor_msgs/msg/RegionOfInterest: This message is used to specify a region of interest within an image."""

    __slots__ = (
        "x_offset",
        "y_offset",
        "height",
        "width",
        "do_rectify",
    )
    x_offset: int
    y_offset: int
    height: int
    width: int
    do_rectify: bool

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            x_offset: int = ...,
            y_offset: int = ...,
            height: int = ...,
            width: int = ...,
            do_rectify: bool = ...,
        ) -> None: ...


class CameraInfo(Message, type_name="sensor_msgs/msg/CameraInfo"):
    """sensor_msgs/msg/CameraInfo: This message defines meta information for a camera. It should be in a"""

    __slots__ = (
        "header",
        "height",
        "width",
        "distortion_model",
        "d",
        "k",
        "r",
        "p",
        "binning_x",
        "binning_y",
        "roi",
    )
    header: Header
    height: int
    width: int
    distortion_model: str
    d: FloatArray
    k: npt.NDArray[np.float64]
    r: npt.NDArray[np.float64]
    p: npt.NDArray[np.float64]
    binning_x: int
    binning_y: int
    roi: RegionOfInterest

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            header: Header = ...,
            height: int = ...,
            width: int = ...,
            distortion_model: str = ...,
            d: Sequence[float] | npt.NDArray[Any] = ...,
            k: Sequence[float] | npt.NDArray[Any] = ...,
            r: Sequence[float] | npt.NDArray[Any] = ...,
            p: Sequence[float] | npt.NDArray[Any] = ...,
            binning_x: int = ...,
            binning_y: int = ...,
            roi: RegionOfInterest = ...,
        ) -> None: ...


class ChannelFloat32(Message, type_name="sensor_msgs/msg/ChannelFloat32"):
    """sensor_msgs/msg/ChannelFloat32: This message is used by the PointCloud message to hold optional data"""

    __slots__ = (
        "name",
        "values",
    )
    name: str
    values: FloatArray

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            name: str = ...,
            values: Sequence[float] | npt.NDArray[Any] = ...,
        ) -> None: ...


class CompressedImage(Message, type_name="sensor_msgs/msg/CompressedImage"):
    """sensor_msgs/msg/CompressedImage: This message contains a compressed image."""

    __slots__ = (
        "header",
        "format",
        "data",
    )
    header: Header
    format: str
    data: IntArray

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            header: Header = ...,
            format: str = ...,
            data: Sequence[int] | npt.NDArray[Any] = ...,
        ) -> None: ...


class FluidPressure(Message, type_name="sensor_msgs/msg/FluidPressure"):
    """sensor_msgs/msg/FluidPressure: Single pressure reading.  This message is appropriate for measuring the"""

    __slots__ = (
        "header",
        "fluid_pressure",
        "variance",
    )
    header: Header
    fluid_pressure: float
    variance: float

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            header: Header = ...,
            fluid_pressure: float = ...,
            variance: float = ...,
        ) -> None: ...


class Illuminance(Message, type_name="sensor_msgs/msg/Illuminance"):
    """sensor_msgs/msg/Illuminance: Single photometric illuminance measurement.  Light should be assumed to be"""

    __slots__ = (
        "header",
        "illuminance",
        "variance",
    )
    header: Header
    illuminance: float
    variance: float

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            header: Header = ...,
            illuminance: float = ...,
            variance: float = ...,
        ) -> None: ...


class Image(Message, type_name="sensor_msgs/msg/Image"):
    """sensor_msgs/msg/Image: This message contains an uncompressed image"""

    __slots__ = (
        "header",
        "height",
        "width",
        "encoding",
        "is_bigendian",
        "step",
        "data",
    )
    header: Header
    height: int
    width: int
    encoding: str
    is_bigendian: int
    step: int
    data: IntArray

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            header: Header = ...,
            height: int = ...,
            width: int = ...,
            encoding: str = ...,
            is_bigendian: int = ...,
            step: int = ...,
            data: Sequence[int] | npt.NDArray[Any] = ...,
        ) -> None: ...


class Imu(Message, type_name="sensor_msgs/msg/Imu"):
    """sensor_msgs/msg/Imu: This is a message to hold data from an IMU (Inertial Measurement Unit)"""

    __slots__ = (
        "header",
        "orientation",
        "orientation_covariance",
        "angular_velocity",
        "angular_velocity_covariance",
        "linear_acceleration",
        "linear_acceleration_covariance",
    )
    header: Header
    orientation: Quaternion
    orientation_covariance: npt.NDArray[np.float64]
    angular_velocity: Vector3
    angular_velocity_covariance: npt.NDArray[np.float64]
    linear_acceleration: Vector3
    linear_acceleration_covariance: npt.NDArray[np.float64]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            header: Header = ...,
            orientation: Quaternion = ...,
            orientation_covariance: Sequence[float] | npt.NDArray[Any] = ...,
            angular_velocity: Vector3 = ...,
            angular_velocity_covariance: Sequence[float] | npt.NDArray[Any] = ...,
            linear_acceleration: Vector3 = ...,
            linear_acceleration_covariance: Sequence[float] | npt.NDArray[Any] = ...,
        ) -> None: ...


class JointState(Message, type_name="sensor_msgs/msg/JointState"):
    """sensor_msgs/msg/JointState: This is a message that holds data to describe the state of a set of torque controlled joints."""

    __slots__ = (
        "header",
        "name",
        "position",
        "velocity",
        "effort",
    )
    header: Header
    name: list[str]
    position: FloatArray
    velocity: FloatArray
    effort: FloatArray

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            header: Header = ...,
            name: Sequence[str] = ...,
            position: Sequence[float] | npt.NDArray[Any] = ...,
            velocity: Sequence[float] | npt.NDArray[Any] = ...,
            effort: Sequence[float] | npt.NDArray[Any] = ...,
        ) -> None: ...


class Joy(Message, type_name="sensor_msgs/msg/Joy"):
    """sensor_msgs/msg/Joy: Reports the state of a joystick's axes and buttons."""

    __slots__ = (
        "header",
        "axes",
        "buttons",
    )
    header: Header
    axes: FloatArray
    buttons: IntArray

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            header: Header = ...,
            axes: Sequence[float] | npt.NDArray[Any] = ...,
            buttons: Sequence[int] | npt.NDArray[Any] = ...,
        ) -> None: ...


class JoyFeedback(Message, type_name="sensor_msgs/msg/JoyFeedback"):
    """sensor_msgs/msg/JoyFeedback: Declare of the type of feedback"""

    __slots__ = (
        "type",
        "id",
        "intensity",
    )
    TYPE_LED: ClassVar[int]
    TYPE_RUMBLE: ClassVar[int]
    TYPE_BUZZER: ClassVar[int]
    type: int
    id: int
    intensity: float

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            type: int = ...,
            id: int = ...,
            intensity: float = ...,
        ) -> None: ...


class JoyFeedbackArray(Message, type_name="sensor_msgs/msg/JoyFeedbackArray"):
    """sensor_msgs/msg/JoyFeedbackArray: This message publishes values for multiple feedback at once."""

    __slots__ = ("array",)
    array: list[JoyFeedback]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            array: Sequence[JoyFeedback] = ...,
        ) -> None: ...


class LaserEcho(Message, type_name="sensor_msgs/msg/LaserEcho"):
    """sensor_msgs/msg/LaserEcho: This message is a submessage of MultiEchoLaserScan and is not intended"""

    __slots__ = ("echoes",)
    echoes: FloatArray

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            echoes: Sequence[float] | npt.NDArray[Any] = ...,
        ) -> None: ...


class LaserScan(Message, type_name="sensor_msgs/msg/LaserScan"):
    """sensor_msgs/msg/LaserScan: Single scan from a planar laser range-finder"""

    __slots__ = (
        "header",
        "angle_min",
        "angle_max",
        "angle_increment",
        "time_increment",
        "scan_time",
        "range_min",
        "range_max",
        "ranges",
        "intensities",
    )
    header: Header
    angle_min: float
    angle_max: float
    angle_increment: float
    time_increment: float
    scan_time: float
    range_min: float
    range_max: float
    ranges: FloatArray
    intensities: FloatArray

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            header: Header = ...,
            angle_min: float = ...,
            angle_max: float = ...,
            angle_increment: float = ...,
            time_increment: float = ...,
            scan_time: float = ...,
            range_min: float = ...,
            range_max: float = ...,
            ranges: Sequence[float] | npt.NDArray[Any] = ...,
            intensities: Sequence[float] | npt.NDArray[Any] = ...,
        ) -> None: ...


class MagneticField(Message, type_name="sensor_msgs/msg/MagneticField"):
    """sensor_msgs/msg/MagneticField: Measurement of the Magnetic Field vector at a specific location."""

    __slots__ = (
        "header",
        "magnetic_field",
        "magnetic_field_covariance",
    )
    header: Header
    magnetic_field: Vector3
    magnetic_field_covariance: npt.NDArray[np.float64]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            header: Header = ...,
            magnetic_field: Vector3 = ...,
            magnetic_field_covariance: Sequence[float] | npt.NDArray[Any] = ...,
        ) -> None: ...


class MultiDOFJointState(Message, type_name="sensor_msgs/msg/MultiDOFJointState"):
    """sensor_msgs/msg/MultiDOFJointState: Representation of state for joints with multiple degrees of freedom,"""

    __slots__ = (
        "header",
        "joint_names",
        "transforms",
        "twist",
        "wrench",
    )
    header: Header
    joint_names: list[str]
    transforms: list[Transform]
    twist: list[Twist]
    wrench: list[Wrench]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            header: Header = ...,
            joint_names: Sequence[str] = ...,
            transforms: Sequence[Transform] = ...,
            twist: Sequence[Twist] = ...,
            wrench: Sequence[Wrench] = ...,
        ) -> None: ...


class MultiEchoLaserScan(Message, type_name="sensor_msgs/msg/MultiEchoLaserScan"):
    """sensor_msgs/msg/MultiEchoLaserScan: Single scan from a multi-echo planar laser range-finder"""

    __slots__ = (
        "header",
        "angle_min",
        "angle_max",
        "angle_increment",
        "time_increment",
        "scan_time",
        "range_min",
        "range_max",
        "ranges",
        "intensities",
    )
    header: Header
    angle_min: float
    angle_max: float
    angle_increment: float
    time_increment: float
    scan_time: float
    range_min: float
    range_max: float
    ranges: list[LaserEcho]
    intensities: list[LaserEcho]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            header: Header = ...,
            angle_min: float = ...,
            angle_max: float = ...,
            angle_increment: float = ...,
            time_increment: float = ...,
            scan_time: float = ...,
            range_min: float = ...,
            range_max: float = ...,
            ranges: Sequence[LaserEcho] = ...,
            intensities: Sequence[LaserEcho] = ...,
        ) -> None: ...


class NavSatStatus(Message, type_name="sensor_msgs/msg/NavSatStatus"):
    """sensor_msgs/msg/NavSatStatus: Navigation Satellite fix status for any Global Navigation Satellite System."""

    __slots__ = (
        "status",
        "service",
    )
    STATUS_UNKNOWN: ClassVar[int]
    STATUS_NO_FIX: ClassVar[int]
    STATUS_FIX: ClassVar[int]
    STATUS_SBAS_FIX: ClassVar[int]
    STATUS_GBAS_FIX: ClassVar[int]
    SERVICE_UNKNOWN: ClassVar[int]
    SERVICE_GPS: ClassVar[int]
    SERVICE_GLONASS: ClassVar[int]
    SERVICE_COMPASS: ClassVar[int]
    SERVICE_GALILEO: ClassVar[int]
    status: int
    service: int

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            status: int = ...,
            service: int = ...,
        ) -> None: ...


class NavSatFix(Message, type_name="sensor_msgs/msg/NavSatFix"):
    """sensor_msgs/msg/NavSatFix: Navigation Satellite fix for any Global Navigation Satellite System"""

    __slots__ = (
        "header",
        "status",
        "latitude",
        "longitude",
        "altitude",
        "position_covariance",
        "position_covariance_type",
    )
    COVARIANCE_TYPE_UNKNOWN: ClassVar[int]
    COVARIANCE_TYPE_APPROXIMATED: ClassVar[int]
    COVARIANCE_TYPE_DIAGONAL_KNOWN: ClassVar[int]
    COVARIANCE_TYPE_KNOWN: ClassVar[int]
    header: Header
    status: NavSatStatus
    latitude: float
    longitude: float
    altitude: float
    position_covariance: npt.NDArray[np.float64]
    position_covariance_type: int

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            header: Header = ...,
            status: NavSatStatus = ...,
            latitude: float = ...,
            longitude: float = ...,
            altitude: float = ...,
            position_covariance: Sequence[float] | npt.NDArray[Any] = ...,
            position_covariance_type: int = ...,
        ) -> None: ...


class PointCloud(Message, type_name="sensor_msgs/msg/PointCloud"):
    """sensor_msgs/msg/PointCloud: THIS MESSAGE IS DEPRECATED AS OF FOXY"""

    __slots__ = (
        "header",
        "points",
        "channels",
    )
    header: Header
    points: list[Point32]
    channels: list[ChannelFloat32]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            header: Header = ...,
            points: Sequence[Point32] = ...,
            channels: Sequence[ChannelFloat32] = ...,
        ) -> None: ...


class PointField(Message, type_name="sensor_msgs/msg/PointField"):
    """sensor_msgs/msg/PointField: This message holds the description of one point entry in the"""

    __slots__ = (
        "name",
        "offset",
        "datatype",
        "count",
    )
    INT8: ClassVar[int]
    UINT8: ClassVar[int]
    INT16: ClassVar[int]
    UINT16: ClassVar[int]
    INT32: ClassVar[int]
    UINT32: ClassVar[int]
    FLOAT32: ClassVar[int]
    FLOAT64: ClassVar[int]
    name: str
    offset: int
    datatype: int
    count: int

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            name: str = ...,
            offset: int = ...,
            datatype: int = ...,
            count: int = ...,
        ) -> None: ...


class PointCloud2(Message, type_name="sensor_msgs/msg/PointCloud2"):
    """sensor_msgs/msg/PointCloud2: This message holds a collection of N-dimensional points, which may"""

    __slots__ = (
        "header",
        "height",
        "width",
        "fields",
        "is_bigendian",
        "point_step",
        "row_step",
        "data",
        "is_dense",
    )
    header: Header
    height: int
    width: int
    fields: list[PointField]
    is_bigendian: bool
    point_step: int
    row_step: int
    data: IntArray
    is_dense: bool

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            header: Header = ...,
            height: int = ...,
            width: int = ...,
            fields: Sequence[PointField] = ...,
            is_bigendian: bool = ...,
            point_step: int = ...,
            row_step: int = ...,
            data: Sequence[int] | npt.NDArray[Any] = ...,
            is_dense: bool = ...,
        ) -> None: ...


class Range(Message, type_name="sensor_msgs/msg/Range"):
    """sensor_msgs/msg/Range: Single range reading from an active ranger that emits energy and reports"""

    __slots__ = (
        "header",
        "radiation_type",
        "field_of_view",
        "min_range",
        "max_range",
        "range",
        "variance",
    )
    ULTRASOUND: ClassVar[int]
    INFRARED: ClassVar[int]
    header: Header
    radiation_type: int
    field_of_view: float
    min_range: float
    max_range: float
    range: float
    variance: float

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            header: Header = ...,
            radiation_type: int = ...,
            field_of_view: float = ...,
            min_range: float = ...,
            max_range: float = ...,
            range: float = ...,
            variance: float = ...,
        ) -> None: ...


class RelativeHumidity(Message, type_name="sensor_msgs/msg/RelativeHumidity"):
    """sensor_msgs/msg/RelativeHumidity: Single reading from a relative humidity sensor."""

    __slots__ = (
        "header",
        "relative_humidity",
        "variance",
    )
    header: Header
    relative_humidity: float
    variance: float

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            header: Header = ...,
            relative_humidity: float = ...,
            variance: float = ...,
        ) -> None: ...


class Temperature(Message, type_name="sensor_msgs/msg/Temperature"):
    """sensor_msgs/msg/Temperature: Single temperature reading."""

    __slots__ = (
        "header",
        "temperature",
        "variance",
    )
    header: Header
    temperature: float
    variance: float

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            header: Header = ...,
            temperature: float = ...,
            variance: float = ...,
        ) -> None: ...


class TimeReference(Message, type_name="sensor_msgs/msg/TimeReference"):
    """sensor_msgs/msg/TimeReference: Measurement from an external time source not actively synchronized with the system clock."""

    __slots__ = (
        "header",
        "time_ref",
        "source",
    )
    header: Header
    time_ref: Time
    source: str

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            header: Header = ...,
            time_ref: Time = ...,
            source: str = ...,
        ) -> None: ...


class SetCameraInfo_Request(Message, type_name="sensor_msgs/srv/SetCameraInfo_Request"):
    """sensor_msgs/srv/SetCameraInfo_Request: This service requests that a camera stores the given CameraInfo as that"""

    __slots__ = ("camera_info",)
    camera_info: CameraInfo

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            camera_info: CameraInfo = ...,
        ) -> None: ...


class SetCameraInfo_Response(Message, type_name="sensor_msgs/srv/SetCameraInfo_Response"):
    """sensor_msgs/srv/SetCameraInfo_Response"""

    __slots__ = (
        "success",
        "status_message",
    )
    success: bool
    status_message: str

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            success: bool = ...,
            status_message: str = ...,
        ) -> None: ...


class SetCameraInfo(Service, type_name="sensor_msgs/srv/SetCameraInfo"):
    """sensor_msgs/srv/SetCameraInfo: call with a SetCameraInfo.Request, answered with a SetCameraInfo.Response."""

    Request = SetCameraInfo_Request
    Response = SetCameraInfo_Response


__all__ = [
    "BatteryState",
    "CameraInfo",
    "ChannelFloat32",
    "CompressedImage",
    "FluidPressure",
    "Illuminance",
    "Image",
    "Imu",
    "JointState",
    "Joy",
    "JoyFeedback",
    "JoyFeedbackArray",
    "LaserEcho",
    "LaserScan",
    "MagneticField",
    "MultiDOFJointState",
    "MultiEchoLaserScan",
    "NavSatFix",
    "NavSatStatus",
    "PointCloud",
    "PointCloud2",
    "PointField",
    "Range",
    "RegionOfInterest",
    "RelativeHumidity",
    "SetCameraInfo",
    "SetCameraInfo_Request",
    "SetCameraInfo_Response",
    "Temperature",
    "TimeReference",
]
