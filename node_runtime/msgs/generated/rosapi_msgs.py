"""rosapi_msgs: generated from node_runtime/msgs/interfaces/rosapi_msgs by `python -m node_runtime.msgs.generate`; do not edit."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

from node_runtime.msgs._base import Message, Service
from node_runtime.msgs.generated.builtin_interfaces import Time


class GetTime_Request(Message, type_name="rosapi_msgs/srv/GetTime_Request"):
    """rosapi_msgs/srv/GetTime_Request"""

    __slots__ = ()


class GetTime_Response(Message, type_name="rosapi_msgs/srv/GetTime_Response"):
    """rosapi_msgs/srv/GetTime_Response"""

    __slots__ = ("time",)
    time: Time

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            time: Time = ...,
        ) -> None: ...


class NodeDetails_Request(Message, type_name="rosapi_msgs/srv/NodeDetails_Request"):
    """rosapi_msgs/srv/NodeDetails_Request"""

    __slots__ = ("node",)
    node: str

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            node: str = ...,
        ) -> None: ...


class NodeDetails_Response(Message, type_name="rosapi_msgs/srv/NodeDetails_Response"):
    """rosapi_msgs/srv/NodeDetails_Response"""

    __slots__ = (
        "subscribing",
        "publishing",
        "services",
    )
    subscribing: list[str]
    publishing: list[str]
    services: list[str]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            subscribing: Sequence[str] = ...,
            publishing: Sequence[str] = ...,
            services: Sequence[str] = ...,
        ) -> None: ...


class Nodes_Request(Message, type_name="rosapi_msgs/srv/Nodes_Request"):
    """rosapi_msgs/srv/Nodes_Request"""

    __slots__ = ()


class Nodes_Response(Message, type_name="rosapi_msgs/srv/Nodes_Response"):
    """rosapi_msgs/srv/Nodes_Response"""

    __slots__ = ("nodes",)
    nodes: list[str]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            nodes: Sequence[str] = ...,
        ) -> None: ...


class Publishers_Request(Message, type_name="rosapi_msgs/srv/Publishers_Request"):
    """rosapi_msgs/srv/Publishers_Request"""

    __slots__ = ("topic",)
    topic: str

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            topic: str = ...,
        ) -> None: ...


class Publishers_Response(Message, type_name="rosapi_msgs/srv/Publishers_Response"):
    """rosapi_msgs/srv/Publishers_Response"""

    __slots__ = ("publishers",)
    publishers: list[str]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            publishers: Sequence[str] = ...,
        ) -> None: ...


class ServiceType_Request(Message, type_name="rosapi_msgs/srv/ServiceType_Request"):
    """rosapi_msgs/srv/ServiceType_Request"""

    __slots__ = ("service",)
    service: str

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            service: str = ...,
        ) -> None: ...


class ServiceType_Response(Message, type_name="rosapi_msgs/srv/ServiceType_Response"):
    """rosapi_msgs/srv/ServiceType_Response"""

    __slots__ = ("type",)
    type: str

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            type: str = ...,
        ) -> None: ...


class Services_Request(Message, type_name="rosapi_msgs/srv/Services_Request"):
    """rosapi_msgs/srv/Services_Request"""

    __slots__ = ()


class Services_Response(Message, type_name="rosapi_msgs/srv/Services_Response"):
    """rosapi_msgs/srv/Services_Response"""

    __slots__ = ("services",)
    services: list[str]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            services: Sequence[str] = ...,
        ) -> None: ...


class Subscribers_Request(Message, type_name="rosapi_msgs/srv/Subscribers_Request"):
    """rosapi_msgs/srv/Subscribers_Request"""

    __slots__ = ("topic",)
    topic: str

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            topic: str = ...,
        ) -> None: ...


class Subscribers_Response(Message, type_name="rosapi_msgs/srv/Subscribers_Response"):
    """rosapi_msgs/srv/Subscribers_Response"""

    __slots__ = ("subscribers",)
    subscribers: list[str]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            subscribers: Sequence[str] = ...,
        ) -> None: ...


class TopicType_Request(Message, type_name="rosapi_msgs/srv/TopicType_Request"):
    """rosapi_msgs/srv/TopicType_Request"""

    __slots__ = ("topic",)
    topic: str

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            topic: str = ...,
        ) -> None: ...


class TopicType_Response(Message, type_name="rosapi_msgs/srv/TopicType_Response"):
    """rosapi_msgs/srv/TopicType_Response"""

    __slots__ = ("type",)
    type: str

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            type: str = ...,
        ) -> None: ...


class Topics_Request(Message, type_name="rosapi_msgs/srv/Topics_Request"):
    """rosapi_msgs/srv/Topics_Request"""

    __slots__ = ()


class Topics_Response(Message, type_name="rosapi_msgs/srv/Topics_Response"):
    """rosapi_msgs/srv/Topics_Response"""

    __slots__ = (
        "topics",
        "types",
    )
    topics: list[str]
    types: list[str]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            topics: Sequence[str] = ...,
            types: Sequence[str] = ...,
        ) -> None: ...


class TopicsForType_Request(Message, type_name="rosapi_msgs/srv/TopicsForType_Request"):
    """rosapi_msgs/srv/TopicsForType_Request"""

    __slots__ = ("type",)
    type: str

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            type: str = ...,
        ) -> None: ...


class TopicsForType_Response(Message, type_name="rosapi_msgs/srv/TopicsForType_Response"):
    """rosapi_msgs/srv/TopicsForType_Response"""

    __slots__ = ("topics",)
    topics: list[str]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            topics: Sequence[str] = ...,
        ) -> None: ...


class GetTime(Service, type_name="rosapi_msgs/srv/GetTime"):
    """rosapi_msgs/srv/GetTime: call with a GetTime.Request, answered with a GetTime.Response."""

    Request = GetTime_Request
    Response = GetTime_Response


class NodeDetails(Service, type_name="rosapi_msgs/srv/NodeDetails"):
    """rosapi_msgs/srv/NodeDetails: call with a NodeDetails.Request, answered with a NodeDetails.Response."""

    Request = NodeDetails_Request
    Response = NodeDetails_Response


class Nodes(Service, type_name="rosapi_msgs/srv/Nodes"):
    """rosapi_msgs/srv/Nodes: call with a Nodes.Request, answered with a Nodes.Response."""

    Request = Nodes_Request
    Response = Nodes_Response


class Publishers(Service, type_name="rosapi_msgs/srv/Publishers"):
    """rosapi_msgs/srv/Publishers: call with a Publishers.Request, answered with a Publishers.Response."""

    Request = Publishers_Request
    Response = Publishers_Response


class ServiceType(Service, type_name="rosapi_msgs/srv/ServiceType"):
    """rosapi_msgs/srv/ServiceType: call with a ServiceType.Request, answered with a ServiceType.Response."""

    Request = ServiceType_Request
    Response = ServiceType_Response


class Services(Service, type_name="rosapi_msgs/srv/Services"):
    """rosapi_msgs/srv/Services: call with a Services.Request, answered with a Services.Response."""

    Request = Services_Request
    Response = Services_Response


class Subscribers(Service, type_name="rosapi_msgs/srv/Subscribers"):
    """rosapi_msgs/srv/Subscribers: call with a Subscribers.Request, answered with a Subscribers.Response."""

    Request = Subscribers_Request
    Response = Subscribers_Response


class TopicType(Service, type_name="rosapi_msgs/srv/TopicType"):
    """rosapi_msgs/srv/TopicType: call with a TopicType.Request, answered with a TopicType.Response."""

    Request = TopicType_Request
    Response = TopicType_Response


class Topics(Service, type_name="rosapi_msgs/srv/Topics"):
    """rosapi_msgs/srv/Topics: call with a Topics.Request, answered with a Topics.Response."""

    Request = Topics_Request
    Response = Topics_Response


class TopicsForType(Service, type_name="rosapi_msgs/srv/TopicsForType"):
    """rosapi_msgs/srv/TopicsForType: call with a TopicsForType.Request, answered with a TopicsForType.Response."""

    Request = TopicsForType_Request
    Response = TopicsForType_Response


__all__ = [
    "GetTime",
    "GetTime_Request",
    "GetTime_Response",
    "NodeDetails",
    "NodeDetails_Request",
    "NodeDetails_Response",
    "Nodes",
    "Nodes_Request",
    "Nodes_Response",
    "Publishers",
    "Publishers_Request",
    "Publishers_Response",
    "ServiceType",
    "ServiceType_Request",
    "ServiceType_Response",
    "Services",
    "Services_Request",
    "Services_Response",
    "Subscribers",
    "Subscribers_Request",
    "Subscribers_Response",
    "TopicType",
    "TopicType_Request",
    "TopicType_Response",
    "Topics",
    "TopicsForType",
    "TopicsForType_Request",
    "TopicsForType_Response",
    "Topics_Request",
    "Topics_Response",
]
