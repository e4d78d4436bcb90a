"""Where the app's Zenoh router listens: loopback unless the user names another endpoint; the HTTP
``--host`` never widens it."""

from __future__ import annotations

import pytest

from node_runtime.transport.config import ZenohSettings, is_loopback
from server.__main__ import build_parser, zenoh_settings


def settings_for(*argv: str) -> ZenohSettings | None:
    return zenoh_settings(build_parser().parse_args(list(argv)))


@pytest.mark.parametrize("argv", [(), ("--host", "0.0.0.0"), ("--host", "192.168.1.20", "--port", "9000")])
def test_without_a_named_endpoint_zenoh_listens_on_loopback_only(argv: tuple[str, ...]) -> None:
    zenoh = settings_for(*argv)
    assert zenoh is not None and zenoh.mode == "router"
    assert zenoh.listen == ("tcp/127.0.0.1:7447",)
    assert all(is_loopback(endpoint) for endpoint in zenoh.listen)
    assert zenoh.connect == ()


def test_a_classroom_lan_listen_is_only_what_the_flag_names() -> None:
    zenoh = settings_for("--zenoh-listen", "tcp/0.0.0.0:7447", "--zenoh-listen", "tcp/127.0.0.1:7448")
    assert zenoh is not None
    assert zenoh.listen == ("tcp/0.0.0.0:7447", "tcp/127.0.0.1:7448")
    assert [is_loopback(endpoint) for endpoint in zenoh.listen] == [False, True]


def test_joining_another_router_listens_on_an_ephemeral_loopback_port() -> None:
    zenoh = settings_for("--host", "0.0.0.0", "--zenoh-connect", "tcp/10.0.0.5:7447")
    assert zenoh is not None and zenoh.mode == "peer"
    assert zenoh.connect == ("tcp/10.0.0.5:7447",)
    assert zenoh.listen == ("tcp/127.0.0.1:0",)


def test_no_zenoh_opens_no_session() -> None:
    assert settings_for("--no-zenoh", "--host", "0.0.0.0") is None


def test_domain_id_comes_from_ros_domain_id(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("ROS_DOMAIN_ID", "42")
    zenoh = settings_for()
    assert zenoh is not None and zenoh.domain_id == 42
