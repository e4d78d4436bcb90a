"""A class's Zenoh logins: the class's derived from the instructor's token, each world's random,
and the router's file of them private to the server and gone when it closes. (What the router
does with them is tested against a running class server in tests/classroom/.)"""

from __future__ import annotations

import json
import stat

import pytest

from node_runtime.transport.acl import (
    CLASS_USER,
    ClassAuth,
    RouterAccess,
    RouterLogins,
    new_world_login,
    process_config,
)


def test_the_class_login_is_derived_and_another_class_cannot_guess_it() -> None:
    auth = ClassAuth("the-instructors-token")
    assert auth.class_credentials() == ClassAuth("the-instructors-token").class_credentials()
    assert auth.class_credentials().user == CLASS_USER
    assert ClassAuth("another-class").class_credentials().password != auth.class_credentials().password
    assert "the-instructors-token" not in auth.class_credentials().password


def test_a_worlds_login_is_random_and_names_its_domain_only_in_its_user() -> None:
    logins = [new_world_login(1) for _ in range(50)] + [new_world_login(232)]
    assert len({c.user for c in logins}) == len({c.password for c in logins}) == len(logins)
    assert all(c.user.startswith("ros2lab-world-1-") for c in logins[:-1])
    assert logins[-1].user.startswith("ros2lab-world-232-")
    assert all(len(c.password) == 40 for c in logins)
    assert "password" not in repr(logins[0]).replace("password=...", "")
    for domain in (0, 233):  # the class's own domain has no world; ROS stops at 232
        with pytest.raises(ValueError):
            new_world_login(domain)


def test_the_router_knows_exactly_the_logins_given_and_holds_each_world_to_its_own_domain() -> None:
    class_login = ClassAuth("t").class_credentials()
    worlds = {7: new_world_login(7), 9: new_world_login(9)}
    access = RouterAccess(class_login, worlds)
    lines = access.dictionary().splitlines()
    assert lines == [f"{c.user}:{c.password}" for c in (class_login, worlds[7], worlds[9])]
    acl = access.access_control()
    assert acl["enabled"] is True and acl["default_permission"] == "deny"
    rules = {r["id"]: r for r in acl["rules"]}  # type: ignore[attr-defined]
    assert rules["class"]["key_exprs"] == ["**", "@ros2_lv/**"]
    assert rules["domain7"]["key_exprs"] == ["7/**", "@ros2_lv/7/**"]
    assert set(rules) == {"class", "domain7", "domain9"}
    policies = acl["policies"]
    assert {"rules": ["domain7"], "subjects": ["world7"]} in policies  # type: ignore[operator]
    subjects = {s["id"]: s["usernames"] for s in acl["subjects"]}  # type: ignore[attr-defined]
    assert subjects["world7"] == [worlds[7].user] and subjects["class"] == [CLASS_USER]
    assert worlds[7].password not in repr(access)


def test_the_routers_login_file_is_private_and_removed_on_close() -> None:
    access = RouterAccess(ClassAuth("t").class_credentials(), {3: new_world_login(3)})
    logins = RouterLogins(access)
    path = logins.path
    assert stat.S_IMODE(path.stat().st_mode) == 0o600
    assert path.read_text() == access.dictionary()
    assert json.loads(logins.config["transport/auth/usrpwd/dictionary_file"]) == str(path)
    logins.close()
    assert not path.exists() and not path.parent.exists()


def test_a_class_node_process_is_a_logged_in_client_that_listens_nowhere() -> None:
    login = new_world_login(3)
    config = process_config(login)
    assert json.loads(config["mode"]) == "client" and json.loads(config["listen/endpoints"]) == []
    assert json.loads(config["transport/auth/usrpwd/user"]) == login.user
    assert json.loads(config["transport/auth/usrpwd/password"]) == login.password
