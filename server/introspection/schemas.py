"""Message types as draft 2020-12 JSON Schemas: the message layer's own (server.msgs.schema),
which the introspection API serves."""

from __future__ import annotations

from server.msgs._field import FLOAT32_MAX
from server.msgs.schema import JSON_SCHEMA_DIALECT, type_schema

__all__ = ["FLOAT32_MAX", "JSON_SCHEMA_DIALECT", "type_schema"]
