"""visualization_msgs: generated from ROS 2's definitions (the wheels node_runtime/msgs/ros_packages.txt pins) by `python -m node_runtime.msgs.generate`; do not edit."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any, ClassVar

if TYPE_CHECKING:
    import numpy.typing as npt

from node_runtime.msgs._base import Message, Service
from node_runtime.msgs._field import IntArray
from node_runtime.msgs.generated.builtin_interfaces import Duration
from node_runtime.msgs.generated.geometry_msgs import Point, Pose, Quaternion, Vector3
from node_runtime.msgs.generated.sensor_msgs import CompressedImage
from node_runtime.msgs.generated.std_msgs import ColorRGBA, Header


class ImageMarker(Message, type_name="visualization_msgs/msg/ImageMarker"):
    """visualization_msgs/msg/ImageMarker: Namespace which is used with the id to form a unique id."""

    __slots__ = (
        "header",
        "ns",
        "id",
        "type",
        "action",
        "position",
        "scale",
        "outline_color",
        "filled",
        "fill_color",
        "lifetime",
        "points",
        "outline_colors",
    )
    CIRCLE: ClassVar[int]
    LINE_STRIP: ClassVar[int]
    LINE_LIST: ClassVar[int]
    POLYGON: ClassVar[int]
    POINTS: ClassVar[int]
    ADD: ClassVar[int]
    REMOVE: ClassVar[int]
    header: Header
    ns: str
    id: int
    type: int
    action: int
    position: Point
    scale: float
    outline_color: ColorRGBA
    filled: int
    fill_color: ColorRGBA
    lifetime: Duration
    points: list[Point]
    outline_colors: list[ColorRGBA]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            header: Header = ...,
            ns: str = ...,
            id: int = ...,
            type: int = ...,
            action: int = ...,
            position: Point = ...,
            scale: float = ...,
            outline_color: ColorRGBA = ...,
            filled: int = ...,
            fill_color: ColorRGBA = ...,
            lifetime: Duration = ...,
            points: Sequence[Point] = ...,
            outline_colors: Sequence[ColorRGBA] = ...,
        ) -> None: ...


class MenuEntry(Message, type_name="visualization_msgs/msg/MenuEntry"):
    """visualization_msgs/msg/MenuEntry: MenuEntry message."""

    __slots__ = (
        "id",
        "parent_id",
        "title",
        "command",
        "command_type",
    )
    FEEDBACK: ClassVar[int]
    ROSRUN: ClassVar[int]
    ROSLAUNCH: ClassVar[int]
    id: int
    parent_id: int
    title: str
    command: str
    command_type: int

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            id: int = ...,
            parent_id: int = ...,
            title: str = ...,
            command: str = ...,
            command_type: int = ...,
        ) -> None: ...


class UVCoordinate(Message, type_name="visualization_msgs/msg/UVCoordinate"):
    """visualization_msgs/msg/UVCoordinate: Location of the pixel as a ratio of the width of a 2D texture."""

    __slots__ = (
        "u",
        "v",
    )
    u: float
    v: float

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            u: float = ...,
            v: float = ...,
        ) -> None: ...


class MeshFile(Message, type_name="visualization_msgs/msg/MeshFile"):
    """visualization_msgs/msg/MeshFile: Used to send raw mesh files."""

    __slots__ = (
        "filename",
        "data",
    )
    filename: str
    data: IntArray

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            filename: str = ...,
            data: Sequence[int] | npt.NDArray[Any] = ...,
        ) -> None: ...


class Marker(Message, type_name="visualization_msgs/msg/Marker"):
    """visualization_msgs/msg/Marker: See:"""

    __slots__ = (
        "header",
        "ns",
        "id",
        "type",
        "action",
        "pose",
        "scale",
        "color",
        "lifetime",
        "frame_locked",
        "points",
        "colors",
        "texture_resource",
        "texture",
        "uv_coordinates",
        "text",
        "mesh_resource",
        "mesh_file",
        "mesh_use_embedded_materials",
    )
    ARROW: ClassVar[int]
    CUBE: ClassVar[int]
    SPHERE: ClassVar[int]
    CYLINDER: ClassVar[int]
    LINE_STRIP: ClassVar[int]
    LINE_LIST: ClassVar[int]
    CUBE_LIST: ClassVar[int]
    SPHERE_LIST: ClassVar[int]
    POINTS: ClassVar[int]
    TEXT_VIEW_FACING: ClassVar[int]
    MESH_RESOURCE: ClassVar[int]
    TRIANGLE_LIST: ClassVar[int]
    ARROW_STRIP: ClassVar[int]
    ADD: ClassVar[int]
    MODIFY: ClassVar[int]
    DELETE: ClassVar[int]
    DELETEALL: ClassVar[int]
    header: Header
    ns: str
    id: int
    type: int
    action: int
    pose: Pose
    scale: Vector3
    color: ColorRGBA
    lifetime: Duration
    frame_locked: bool
    points: list[Point]
    colors: list[ColorRGBA]
    texture_resource: str
    texture: CompressedImage
    uv_coordinates: list[UVCoordinate]
    text: str
    mesh_resource: str
    mesh_file: MeshFile
    mesh_use_embedded_materials: bool

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            header: Header = ...,
            ns: str = ...,
            id: int = ...,
            type: int = ...,
            action: int = ...,
            pose: Pose = ...,
            scale: Vector3 = ...,
            color: ColorRGBA = ...,
            lifetime: Duration = ...,
            frame_locked: bool = ...,
            points: Sequence[Point] = ...,
            colors: Sequence[ColorRGBA] = ...,
            texture_resource: str = ...,
            texture: CompressedImage = ...,
            uv_coordinates: Sequence[UVCoordinate] = ...,
            text: str = ...,
            mesh_resource: str = ...,
            mesh_file: MeshFile = ...,
            mesh_use_embedded_materials: bool = ...,
        ) -> None: ...


class InteractiveMarkerControl(Message, type_name="visualization_msgs/msg/InteractiveMarkerControl"):
    """visualization_msgs/msg/InteractiveMarkerControl: Represents a control that is to be displayed together with an interactive marker"""

    __slots__ = (
        "name",
        "orientation",
        "orientation_mode",
        "interaction_mode",
        "always_visible",
        "markers",
        "independent_marker_orientation",
        "description",
    )
    INHERIT: ClassVar[int]
    FIXED: ClassVar[int]
    VIEW_FACING: ClassVar[int]
    NONE: ClassVar[int]
    MENU: ClassVar[int]
    BUTTON: ClassVar[int]
    MOVE_AXIS: ClassVar[int]
    MOVE_PLANE: ClassVar[int]
    ROTATE_AXIS: ClassVar[int]
    MOVE_ROTATE: ClassVar[int]
    MOVE_3D: ClassVar[int]
    ROTATE_3D: ClassVar[int]
    MOVE_ROTATE_3D: ClassVar[int]
    name: str
    orientation: Quaternion
    orientation_mode: int
    interaction_mode: int
    always_visible: bool
    markers: list[Marker]
    independent_marker_orientation: bool
    description: str

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            name: str = ...,
            orientation: Quaternion = ...,
            orientation_mode: int = ...,
            interaction_mode: int = ...,
            always_visible: bool = ...,
            markers: Sequence[Marker] = ...,
            independent_marker_orientation: bool = ...,
            description: str = ...,
        ) -> None: ...


class InteractiveMarker(Message, type_name="visualization_msgs/msg/InteractiveMarker"):
    """visualization_msgs/msg/InteractiveMarker: Time/frame info."""

    __slots__ = (
        "header",
        "pose",
        "name",
        "description",
        "scale",
        "menu_entries",
        "controls",
    )
    header: Header
    pose: Pose
    name: str
    description: str
    scale: float
    menu_entries: list[MenuEntry]
    controls: list[InteractiveMarkerControl]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            header: Header = ...,
            pose: Pose = ...,
            name: str = ...,
            description: str = ...,
            scale: float = ...,
            menu_entries: Sequence[MenuEntry] = ...,
            controls: Sequence[InteractiveMarkerControl] = ...,
        ) -> None: ...


class InteractiveMarkerFeedback(Message, type_name="visualization_msgs/msg/InteractiveMarkerFeedback"):
    """visualization_msgs/msg/InteractiveMarkerFeedback: Time/frame info."""

    __slots__ = (
        "header",
        "client_id",
        "marker_name",
        "control_name",
        "event_type",
        "pose",
        "menu_entry_id",
        "mouse_point",
        "mouse_point_valid",
    )
    KEEP_ALIVE: ClassVar[int]
    POSE_UPDATE: ClassVar[int]
    MENU_SELECT: ClassVar[int]
    BUTTON_CLICK: ClassVar[int]
    MOUSE_DOWN: ClassVar[int]
    MOUSE_UP: ClassVar[int]
    header: Header
    client_id: str
    marker_name: str
    control_name: str
    event_type: int
    pose: Pose
    menu_entry_id: int
    mouse_point: Point
    mouse_point_valid: bool

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            header: Header = ...,
            client_id: str = ...,
            marker_name: str = ...,
            control_name: str = ...,
            event_type: int = ...,
            pose: Pose = ...,
            menu_entry_id: int = ...,
            mouse_point: Point = ...,
            mouse_point_valid: bool = ...,
        ) -> None: ...


class InteractiveMarkerInit(Message, type_name="visualization_msgs/msg/InteractiveMarkerInit"):
    """visualization_msgs/msg/InteractiveMarkerInit: Identifying string. Must be unique in the topic namespace"""

    __slots__ = (
        "server_id",
        "seq_num",
        "markers",
    )
    server_id: str
    seq_num: int
    markers: list[InteractiveMarker]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            server_id: str = ...,
            seq_num: int = ...,
            markers: Sequence[InteractiveMarker] = ...,
        ) -> None: ...


class InteractiveMarkerPose(Message, type_name="visualization_msgs/msg/InteractiveMarkerPose"):
    """visualization_msgs/msg/InteractiveMarkerPose: Time/frame info."""

    __slots__ = (
        "header",
        "pose",
        "name",
    )
    header: Header
    pose: Pose
    name: str

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            header: Header = ...,
            pose: Pose = ...,
            name: str = ...,
        ) -> None: ...


class InteractiveMarkerUpdate(Message, type_name="visualization_msgs/msg/InteractiveMarkerUpdate"):
    """visualization_msgs/msg/InteractiveMarkerUpdate: Identifying string. Must be unique in the topic namespace"""

    __slots__ = (
        "server_id",
        "seq_num",
        "type",
        "markers",
        "poses",
        "erases",
    )
    KEEP_ALIVE: ClassVar[int]
    UPDATE: ClassVar[int]
    server_id: str
    seq_num: int
    type: int
    markers: list[InteractiveMarker]
    poses: list[InteractiveMarkerPose]
    erases: list[str]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            server_id: str = ...,
            seq_num: int = ...,
            type: int = ...,
            markers: Sequence[InteractiveMarker] = ...,
            poses: Sequence[InteractiveMarkerPose] = ...,
            erases: Sequence[str] = ...,
        ) -> None: ...


class MarkerArray(Message, type_name="visualization_msgs/msg/MarkerArray"):
    """visualization_msgs/msg/MarkerArray"""

    __slots__ = ("markers",)
    markers: list[Marker]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            markers: Sequence[Marker] = ...,
        ) -> None: ...


class GetInteractiveMarkers_Request(
    Message, type_name="visualization_msgs/srv/GetInteractiveMarkers_Request"
):
    """visualization_msgs/srv/GetInteractiveMarkers_Request"""

    __slots__ = ()


class GetInteractiveMarkers_Response(
    Message, type_name="visualization_msgs/srv/GetInteractiveMarkers_Response"
):
    """visualization_msgs/srv/GetInteractiveMarkers_Response: Sequence number."""

    __slots__ = (
        "sequence_number",
        "markers",
    )
    sequence_number: int
    markers: list[InteractiveMarker]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            sequence_number: int = ...,
            markers: Sequence[InteractiveMarker] = ...,
        ) -> None: ...


class GetInteractiveMarkers(Service, type_name="visualization_msgs/srv/GetInteractiveMarkers"):
    """visualization_msgs/srv/GetInteractiveMarkers: call with a GetInteractiveMarkers.Request, answered with a GetInteractiveMarkers.Response."""

    Request = GetInteractiveMarkers_Request
    Response = GetInteractiveMarkers_Response


__all__ = [
    "GetInteractiveMarkers",
    "GetInteractiveMarkers_Request",
    "GetInteractiveMarkers_Response",
    "ImageMarker",
    "InteractiveMarker",
    "InteractiveMarkerControl",
    "InteractiveMarkerFeedback",
    "InteractiveMarkerInit",
    "InteractiveMarkerPose",
    "InteractiveMarkerUpdate",
    "Marker",
    "MarkerArray",
    "MenuEntry",
    "MeshFile",
    "UVCoordinate",
]
