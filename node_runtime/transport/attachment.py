"""The 33-byte attachment rmw_zenoh puts on every sample, query and reply.

``<int64 LE sequence number><int64 LE source timestamp ns><byte 16><16-byte GID>``, which is
what zenoh's serializer writes for (int64, int64, uint8[16]). rmw_zenoh drops a sample without
it; so do we, and count it.
"""

from __future__ import annotations

import struct
from dataclasses import dataclass

from node_runtime.transport.keys import GID_BYTES

ATTACHMENT_BYTES = 8 + 8 + 1 + GID_BYTES
_HEAD = struct.Struct("<qqB")


@dataclass(frozen=True)
class Attachment:
    sequence_number: int
    source_timestamp_ns: int
    gid: bytes

    def pack(self) -> bytes:
        if len(self.gid) != GID_BYTES:
            raise ValueError(f"a GID is {GID_BYTES} bytes, got {len(self.gid)}")
        return _HEAD.pack(self.sequence_number, self.source_timestamp_ns, GID_BYTES) + self.gid

    @classmethod
    def unpack(cls, data: bytes | None) -> Attachment | None:
        """The attachment in ``data``, or None when it is missing or not rmw_zenoh's shape."""
        if data is None or len(data) != ATTACHMENT_BYTES:
            return None
        seq, stamp, length = _HEAD.unpack_from(data)
        if length != GID_BYTES:
            return None
        return cls(seq, stamp, bytes(data[_HEAD.size :]))
