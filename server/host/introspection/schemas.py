"""Message types as draft 2020-12 JSON Schemas: the message layer's own (node_runtime.msgs.schema),
which the introspection API serves."""

from __future__ import annotations

from node_runtime.msgs._field import FLOAT32_MAX
from node_runtime.msgs.schema import JSON_SCHEMA_DIALECT, type_schema

__all__ = ["FLOAT32_MAX", "JSON_SCHEMA_DIALECT", "type_schema"]
