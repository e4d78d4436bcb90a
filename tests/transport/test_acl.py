"""A class's Zenoh logins: derived from the instructor's token, one per world domain, and the
router's file of them private to the server and gone when it closes. (What the router does with
them is tested against a running class server in tests/classroom/test_classroom_zenoh.py.)"""

from __future__ import annotations

import json
import stat

import pytest

from server.transport.acl import CLASS_USER, ClassAuth, RouterLogins, process_config


def test_each_world_domain_has_a_login_of_its_own_that_another_class_cannot_guess() -> None:
    auth = ClassAuth("the-instructors-token")
    logins = [auth.world_credentials(d) for d in (1, 2, 232)]
    assert [c.user for c in logins] == ["ros2lab-world-1", "ros2lab-world-2", "ros2lab-world-232"]
    assert len({c.password for c in logins} | {auth.class_credentials().password}) == 4
    assert auth.world_credentials(1) == ClassAuth("the-instructors-token").world_credentials(1)  # derived
    assert ClassAuth("another-class").world_credentials(1).password != logins[0].password
    assert "the-instructors-token" not in auth.dictionary()
    assert "password" not in repr(auth.world_credentials(1)).replace("password=...", "")
    for domain in (0, 233):  # the class's own domain has no world; ROS stops at 232
        with pytest.raises(ValueError):
            auth.world_credentials(domain)


def test_the_router_knows_every_login_and_holds_each_world_to_its_own_domain() -> None:
    auth = ClassAuth("t")
    lines = auth.dictionary().splitlines()
    assert len(lines) == 1 + 232 and lines[0] == f"{CLASS_USER}:{auth.class_credentials().password}"
    acl = auth.access_control()
    assert acl["enabled"] is True and acl["default_permission"] == "deny"
    rules = {r["id"]: r for r in acl["rules"]}  # type: ignore[attr-defined]
    assert rules["class"]["key_exprs"] == ["**", "@ros2_lv/**"]
    assert rules["domain7"]["key_exprs"] == ["7/**", "@ros2_lv/7/**"]
    policies = acl["policies"]
    assert {"rules": ["domain7"], "subjects": ["world7"]} in policies  # type: ignore[operator]
    subjects = {s["id"]: s["usernames"] for s in acl["subjects"]}  # type: ignore[attr-defined]
    assert subjects["world7"] == ["ros2lab-world-7"]


def test_the_routers_login_file_is_private_and_removed_on_close() -> None:
    logins = RouterLogins(ClassAuth("t"))
    path = logins.path
    assert stat.S_IMODE(path.stat().st_mode) == 0o600
    assert path.read_text() == ClassAuth("t").dictionary()
    assert json.loads(logins.config["transport/auth/usrpwd/dictionary_file"]) == str(path)
    logins.close()
    assert not path.exists() and not path.parent.exists()


def test_a_class_node_process_is_a_logged_in_client_that_listens_nowhere() -> None:
    login = ClassAuth("t").world_credentials(3)
    config = process_config(login)
    assert json.loads(config["mode"]) == "client" and json.loads(config["listen/endpoints"]) == []
    assert json.loads(config["transport/auth/usrpwd/user"]) == "ros2lab-world-3"
    assert json.loads(config["transport/auth/usrpwd/password"]) == login.password
