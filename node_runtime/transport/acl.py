"""Who may join a class's Zenoh router, and what each may touch there.

A class server's router asks every session for a user and password (Zenoh's ``usrpwd``
authentication) and checks every message against an access-control list whose default is deny:

- ``ros2lab-class``: the class server's own sessions and its world workers, everything;
- ``ros2lab-world-<d>-<random>``: one world's graph and its node processes, ROS domain ``d``
  only: the data keys ``<d>/**`` and the graph's liveliness tokens ``@ros2_lv/<d>/**``, as
  rmw_zenoh names them.

The class's login is an HMAC of the instructor's token: the class server and its workers (which
hold that token) derive it. A world's login is random (``new_world_login``): nothing derives it,
it belongs to one world and is never given to another (server/classroom/class_router.py draws
and revokes them). A student's process gets their world's login from ``GET /api/zenoh/join``
with the student's token, so a student reads and publishes in their own world only, as on the
HTTP API. Plain data; no Zenoh import here.
"""

from __future__ import annotations

import contextlib
import hashlib
import hmac
import json
import os
import secrets
import tempfile
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path

from node_runtime.transport.keys import ADMIN_SPACE

CLASS_USER = "ros2lab-class"
WORLD_USER_PREFIX = "ros2lab-world-"
FIRST_WORLD_DOMAIN = 1
LAST_DOMAIN = 232  # ROS 2's highest ROS_DOMAIN_ID
# Every kind of message Zenoh's access control knows, both ways: a world's user may do anything
# inside its domain, and nothing outside it.
MESSAGES = (
    "put",
    "delete",
    "declare_subscriber",
    "query",
    "reply",
    "declare_queryable",
    "liveliness_token",
    "declare_liveliness_subscriber",
    "liveliness_query",
)
FLOWS = ("ingress", "egress")


@dataclass(frozen=True)
class Credentials:
    user: str
    password: str

    def __repr__(self) -> str:  # never in a log line
        return f"Credentials(user={self.user!r}, password=...)"

    def config(self) -> dict[str, str]:
        """The Zenoh config keys (path → JSON5 value) a session logs in with."""
        return {
            "transport/auth/usrpwd/user": json.dumps(self.user),
            "transport/auth/usrpwd/password": json.dumps(self.password),
        }


def process_config(login: Credentials) -> dict[str, str]:
    """A class's node process: logged in, and a client of the router only. A peer would also take
    links straight from other peers, around the router's access control."""
    return {"mode": json.dumps("client"), "listen/endpoints": "[]", **login.config()}


def new_world_login(domain_id: int) -> Credentials:
    """A fresh random login for a world in ``domain_id`` (the domain is in the user's name, for the
    router's log; the password is 160 random bits that nothing derives)."""
    if not FIRST_WORLD_DOMAIN <= domain_id <= LAST_DOMAIN:
        raise ValueError(f"a world's ROS domain is in {FIRST_WORLD_DOMAIN}..{LAST_DOMAIN}, got {domain_id}")
    return Credentials(f"{WORLD_USER_PREFIX}{domain_id}-{secrets.token_hex(4)}", secrets.token_hex(20))


def world_keys(domain_id: int) -> list[str]:
    """The key expressions of one ROS domain on rmw_zenoh: its data and its graph."""
    return [f"{domain_id}/**", f"{ADMIN_SPACE}/{domain_id}/**"]


@dataclass(frozen=True)
class ClassAuth:
    """The class's own login, derived from one secret (the instructor's token)."""

    secret: str

    def __repr__(self) -> str:
        return "ClassAuth(...)"

    def class_credentials(self) -> Credentials:
        mac = hmac.new(self.secret.encode(), f"zenoh-login/{CLASS_USER}".encode(), hashlib.sha256)
        return Credentials(CLASS_USER, mac.hexdigest()[:40])


@dataclass(frozen=True)
class RouterAccess:
    """Every login a router lets in: the class's (everything), and one per world domain (that
    domain only). Zenoh reads them once, when the router opens."""

    class_login: Credentials
    worlds: Mapping[int, Credentials] = field(default_factory=dict)  # ROS domain → its login

    def __repr__(self) -> str:
        return f"RouterAccess(worlds={sorted(self.worlds)})"

    def dictionary(self) -> str:
        """The router's ``user:password`` lines: the class's, then one per world domain."""
        logins = [self.class_login, *(self.worlds[d] for d in sorted(self.worlds))]
        return "".join(f"{c.user}:{c.password}\n" for c in logins)

    def access_control(self) -> dict[str, object]:
        """The router's access-control list: the class everything, each world its own domain."""
        domains = sorted(self.worlds)
        rule = {"messages": list(MESSAGES), "flows": list(FLOWS), "permission": "allow"}
        return {
            "enabled": True,
            "default_permission": "deny",
            # "@" chunks are verbatim: "**" does not match the graph's "@ros2_lv/..." keys.
            "rules": [{"id": "class", **rule, "key_exprs": ["**", f"{ADMIN_SPACE}/**"]}]
            + [{"id": f"domain{d}", **rule, "key_exprs": world_keys(d)} for d in domains],
            "subjects": [{"id": "class", "usernames": [self.class_login.user]}]
            + [{"id": f"world{d}", "usernames": [self.worlds[d].user]} for d in domains],
            "policies": [{"rules": ["class"], "subjects": ["class"]}]
            + [{"rules": [f"domain{d}"], "subjects": [f"world{d}"]} for d in domains],
        }


class RouterLogins:
    """The dictionary file a router reads its logins from (mode 0600, removed on close), and the
    router's config keys that turn authentication and access control on. Zenoh reads the file
    while the router opens, so ``open_session`` removes it as soon as the router is open."""

    def __init__(self, access: RouterAccess) -> None:
        self._dir = tempfile.mkdtemp(prefix="ros2lab-zenoh-")
        self.path = Path(self._dir) / "logins.txt"
        fd = os.open(self.path, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600)
        with os.fdopen(fd, "w") as out:
            out.write(access.dictionary())
        self.config: dict[str, str] = {
            "transport/auth/usrpwd/dictionary_file": json.dumps(str(self.path)),
            "access_control": json.dumps(access.access_control()),
        }

    def close(self) -> None:
        self.path.unlink(missing_ok=True)
        with contextlib.suppress(OSError):
            os.rmdir(self._dir)

    def __enter__(self) -> RouterLogins:
        return self

    def __exit__(self, *_: object) -> None:
        self.close()
