"""rmw_zenoh's names on the wire: data keys, liveliness tokens, their QoS field and entity GIDs.

Facts from ros2/rmw_zenoh (docs/design.md, liveliness_utils.cpp) for Kilted and Jazzy >= 0.2.4:
- data key ``<domain>/<name without leading/trailing '/'>/<pkg>::msg::dds_::<Type>_/RIHS01_<hex>``;
- liveliness token ``@ros2_lv/<domain>/<zid>/<node id>/<entity id>/<NN|MP|MS|SS|SC>/<enclave>/
  <namespace>/<node>[/<topic>/<type>/<hash>/<qos>]`` with every name mangled ``/`` → ``%``;
- the QoS field writes a value only where it differs from rmw_zenoh's default profile;
- an entity's GID is the XXH3-128 of its token, low 64 bits then high 64 bits, little-endian.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from enum import StrEnum

import xxhash

ADMIN_SPACE = "@ros2_lv"
GID_BYTES = 16


class EntityKind(StrEnum):
    NODE = "NN"
    PUBLISHER = "MP"
    SUBSCRIPTION = "MS"
    SERVICE = "SS"
    CLIENT = "SC"


# rmw's enum values, as the QoS field writes them.
RELIABLE, BEST_EFFORT = 1, 2
TRANSIENT_LOCAL, VOLATILE = 1, 2
KEEP_LAST, KEEP_ALL = 1, 2
LIVELINESS_AUTOMATIC = 1


@dataclass(frozen=True)
class QoS:
    """A QoS profile as rmw_zenoh carries it in a token (durations in whole s and ns; 0 = infinite)."""

    reliability: int = RELIABLE
    durability: int = VOLATILE
    history: int = KEEP_LAST
    depth: int = 42
    deadline: tuple[int, int] = (0, 0)
    lifespan: tuple[int, int] = (0, 0)
    liveliness: int = LIVELINESS_AUTOMATIC
    lease: tuple[int, int] = (0, 0)


RMW_ZENOH_DEFAULT_QOS = QoS()


def _diff(value: object, default: object) -> str:
    return "" if value == default else str(value)


def qos_text(qos: QoS) -> str:
    """``<rel>:<dur>:<hist>,<depth>:<deadline>:<lifespan>:<liveliness>`` with defaults left empty."""
    d = RMW_ZENOH_DEFAULT_QOS
    return ":".join(
        [
            _diff(qos.reliability, d.reliability),
            _diff(qos.durability, d.durability),
            f"{_diff(qos.history, d.history)},{_diff(qos.depth, d.depth)}",
            f"{_diff(qos.deadline[0], d.deadline[0])},{_diff(qos.deadline[1], d.deadline[1])}",
            f"{_diff(qos.lifespan[0], d.lifespan[0])},{_diff(qos.lifespan[1], d.lifespan[1])}",
            f"{_diff(qos.liveliness, d.liveliness)},{_diff(qos.lease[0], d.lease[0])},"
            f"{_diff(qos.lease[1], d.lease[1])}",
        ]
    )


def parse_qos(text: str) -> QoS | None:
    """The profile a token's QoS field stands for; None if it is not of that shape."""
    parts = text.split(":")
    if len(parts) < 6:
        return None
    groups = [parts[0:1], parts[1:2], *(p.split(",") for p in parts[2:6])]
    if [len(g) for g in groups] != [1, 1, 2, 2, 2, 3]:
        return None
    d = RMW_ZENOH_DEFAULT_QOS

    def num(value: str, default: int) -> int:
        if value == "":
            return default
        if not value.isdigit():
            raise ValueError(value)
        return int(value)

    try:
        return QoS(
            reliability=num(groups[0][0], d.reliability),
            durability=num(groups[1][0], d.durability),
            history=num(groups[2][0], d.history),
            depth=num(groups[2][1], d.depth),
            deadline=(num(groups[3][0], 0), num(groups[3][1], 0)),
            lifespan=(num(groups[4][0], 0), num(groups[4][1], 0)),
            liveliness=num(groups[5][0], d.liveliness),
            lease=(num(groups[5][1], 0), num(groups[5][2], 0)),
        )
    except ValueError:
        return None


def keep_last(depth: int, *, best_effort: bool = False, transient_local: bool = False) -> QoS:
    return replace(
        RMW_ZENOH_DEFAULT_QOS,
        depth=depth,
        reliability=BEST_EFFORT if best_effort else RELIABLE,
        durability=TRANSIENT_LOCAL if transient_local else VOLATILE,
    )


def mangle(name: str) -> str:
    """``/uav/sensors/gps`` → ``%uav%sensors%gps``; an empty name is ``%``."""
    return name.replace("/", "%") if name else "%"


def demangle(name: str) -> str:
    return name.replace("%", "/")


def data_key(domain_id: int, name: str, dds_type: str, type_hash: str) -> str:
    """The key a topic's samples (or a service's queries) travel on."""
    return f"{domain_id}/{name.strip('/')}/{dds_type}/{type_hash}"


@dataclass(frozen=True)
class EntityToken:
    """One liveliness token: a node (``kind`` NN, no topic fields) or one of its endpoints."""

    domain_id: int
    zid: str
    node_id: int
    entity_id: int
    kind: EntityKind
    namespace: str
    node_name: str
    enclave: str = "/"
    topic: str | None = None
    dds_type: str | None = None
    type_hash: str | None = None
    qos: QoS | None = None

    @property
    def key(self) -> str:
        parts = [
            ADMIN_SPACE,
            str(self.domain_id),
            self.zid,
            str(self.node_id),
            str(self.entity_id),
            self.kind.value,
            mangle(self.enclave),
            mangle(self.namespace),
            mangle(self.node_name),
        ]
        if self.kind is not EntityKind.NODE:
            if self.topic is None or self.dds_type is None or self.type_hash is None or self.qos is None:
                raise ValueError(f"a {self.kind.name.lower()} token needs a topic, type, hash and QoS")
            parts += [mangle(self.topic), mangle(self.dds_type), mangle(self.type_hash), qos_text(self.qos)]
        return "/".join(parts)

    @property
    def gid(self) -> bytes:
        return entity_gid(self.key)

    @property
    def node_fqn(self) -> str:
        return self.namespace.rstrip("/") + "/" + self.node_name

    @classmethod
    def parse(cls, key: str) -> EntityToken | None:
        """The token a key expression stands for; None for anything malformed (never raises)."""
        parts = key.split("/")
        if len(parts) < 9 or parts[0] != ADMIN_SPACE or any(not p for p in parts):
            return None
        try:
            kind = EntityKind(parts[5])
            domain, node_id, entity_id = int(parts[1]), int(parts[3]), int(parts[4])
        except ValueError:
            return None
        base = {
            "domain_id": domain,
            "zid": parts[2],
            "node_id": node_id,
            "entity_id": entity_id,
            "kind": kind,
            "enclave": demangle(parts[6]),
            "namespace": demangle(parts[7]),
            "node_name": demangle(parts[8]),
        }
        if kind is EntityKind.NODE:
            return cls(**base) if len(parts) == 9 else None  # type: ignore[arg-type]
        if len(parts) != 13:
            return None
        qos = parse_qos(parts[12])
        if qos is None:
            return None
        return cls(
            **base,  # type: ignore[arg-type]
            topic=demangle(parts[9]),
            dds_type=demangle(parts[10]),
            type_hash=demangle(parts[11]),
            qos=qos,
        )


def entity_gid(token_key: str) -> bytes:
    """XXH3-128 of the token, as 16 bytes: the low 64 bits, then the high 64, each little-endian."""
    digest = xxhash.xxh3_128_intdigest(token_key.encode())
    return (digest & (2**64 - 1)).to_bytes(8, "little") + (digest >> 64).to_bytes(8, "little")


def liveliness_prefix(domain_id: int) -> str:
    return f"{ADMIN_SPACE}/{domain_id}/**"
