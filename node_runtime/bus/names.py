"""ROS 2 naming rules: validate topic, node and namespace names, and resolve topic names.

Follows rcl's rules: tokens of letters, digits and underscores that do not start with a digit,
separated by single slashes; ``~`` (private) only at the front; ``{node}`` and ``{ns}``
substitutions; relative names resolve against the node's namespace.
"""

from __future__ import annotations

import re
from collections.abc import Mapping

from node_runtime.bus.errors import InvalidNameError

MAX_TOPIC_NAME_CHARS = 247  # rmw's 255 less the 8-character prefix DDS adds
_TOKEN = re.compile(r"[A-Za-z_][A-Za-z0-9_]*\Z")
_SUBST = re.compile(r"\{(\w*)\}")


def validate_node_name(name: str) -> str:
    if not isinstance(name, str) or not name:
        raise InvalidNameError("node", str(name), "must not be empty")
    if not _TOKEN.match(name):
        if name[0].isdigit():
            raise InvalidNameError("node", name, "must not start with a digit")
        raise InvalidNameError("node", name, "may contain only letters, digits and underscores")
    if len(name) > 255:
        raise InvalidNameError("node", name, "longer than 255 characters")
    return name


def validate_namespace(namespace: str) -> str:
    """Return the namespace in its absolute form ('' → '/')."""
    ns = namespace or "/"
    if not ns.startswith("/"):
        ns = "/" + ns
    if ns == "/":
        return ns
    if ns.endswith("/"):
        raise InvalidNameError("namespace", namespace, "must not end with '/'")
    for token in ns[1:].split("/"):
        _check_token("namespace", namespace, token)
    return ns


def _check_token(kind: str, name: str, token: str) -> None:
    if not token:
        raise InvalidNameError(kind, name, "must not contain '//'")
    if token[0].isdigit():
        raise InvalidNameError(kind, name, f"token {token!r} must not start with a digit")
    if not _TOKEN.match(token):
        raise InvalidNameError(
            kind, name, f"token {token!r} may contain only letters, digits and underscores"
        )


def validate_topic_name(name: str) -> str:
    """Check a topic name as written (relative, private or absolute); return it unchanged."""
    if not isinstance(name, str) or not name:
        raise InvalidNameError("topic", str(name), "must not be empty")
    body = name
    if body.startswith("~"):
        if body not in ("~",) and not body.startswith("~/"):
            raise InvalidNameError("topic", name, "'~' must be followed by '/'")
        body = body[2:] if body != "~" else ""
    if "~" in body:
        raise InvalidNameError("topic", name, "'~' is allowed only as the first character")
    if body.startswith("/"):
        body = body[1:]
    if body == "" and name != "~":
        raise InvalidNameError("topic", name, "names no topic")
    if body.endswith("/"):
        raise InvalidNameError("topic", name, "must not end with '/'")
    for token in body.split("/") if body else []:
        if not _SUBST.fullmatch(token):
            _check_token("topic", name, token)
    if len(name) > MAX_TOPIC_NAME_CHARS:
        raise InvalidNameError("topic", name, f"longer than {MAX_TOPIC_NAME_CHARS} characters")
    return name


def is_fully_qualified(name: str) -> bool:
    """Whether ``name`` is a fully qualified topic or service name, as a graph carries one: ``/``
    then valid tokens, with no ``~`` and no substitution left (``/uav/sensors/gps``, never
    ``uav/sensors/gps``)."""
    if not isinstance(name, str) or not name.startswith("/") or "~" in name or "{" in name:
        return False
    try:
        validate_topic_name(name)
    except InvalidNameError:
        return False
    return True


def resolve_topic_name(
    name: str, node_name: str = "", namespace: str = "/", remappings: Mapping[str, str] | None = None
) -> str:
    """Resolve to a fully qualified name (``/ns/topic``), then apply remapping rules.

    As in ROS 2, both sides of a rule are expanded like the name itself, so ``cmd:=vel`` in
    namespace ``/ns`` means ``/ns/cmd:=/ns/vel``.
    """
    ns = validate_namespace(namespace)
    full = _expand(name, node_name, ns)
    for match, replacement in (remappings or {}).items():
        if _expand(match, node_name, ns) == full:
            return _expand(replacement, node_name, ns)
    return full


def _expand(name: str, node_name: str, ns: str) -> str:
    validate_topic_name(name)

    def subst(match: re.Match[str]) -> str:
        key = match.group(1)
        if key == "node" and node_name:
            return node_name
        if key in ("ns", "namespace"):
            return ns  # with its leading '/', as rcl does: "{ns}/x" is absolute
        raise InvalidNameError("topic", name, f"unknown substitution {{{key}}}")

    expanded = _SUBST.sub(subst, name)
    private_base = (ns.rstrip("/") + "/" + node_name) if node_name else ns.rstrip("/")
    if expanded == "~":
        full = private_base
    elif expanded.startswith("~/"):
        full = private_base + expanded[1:]
    elif expanded.startswith("/"):
        full = expanded
    else:
        full = ns.rstrip("/") + "/" + expanded
    full = "/" + "/".join(t for t in full.split("/") if t)
    validate_topic_name(full)
    return full


def is_hidden(name: str) -> bool:
    """ROS hides names with a token that starts with an underscore."""
    return any(t.startswith("_") for t in name.split("/") if t)
