"""Namespaces as launch_ros joins them: a relative one under the pushed one, always absolute."""

from __future__ import annotations


def prefix_namespace(base: str | None, namespace: str | None) -> str | None:
    if base is None or not base or (namespace is not None and namespace.startswith("/")):
        return namespace
    if namespace is None or not namespace:
        return base
    return base.rstrip("/") + "/" + namespace


def make_namespace_absolute(namespace: str | None) -> str | None:
    if namespace is None:
        return None
    return namespace if namespace.startswith("/") else "/" + namespace
