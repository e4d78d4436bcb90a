"""The settings model: each rule across fields refuses its bad combination with a clear message,
and takes the good one; the sections are frozen and refuse names they do not know."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest
from pydantic import ValidationError

from node_runtime.transport.config import ZenohSettings
from server.host.settings import (
    LOCAL_WORLDS_RULE,
    MAX_LOCAL_WORKERS,
    WORKERS_RULE,
    ClassroomSettings,
    JoinLimits,
    LabSettings,
    Listening,
    SandboxSettings,
    Settings,
    WorkerSettings,
    choices_of,
    default_of,
    explain,
    is_refusal,
    shown,
)

ROUTER = ZenohSettings()  # tcp/127.0.0.1:7447, this machine only
CLIENT = ZenohSettings(mode="client", listen=(), connect=("tcp/127.0.0.1:7447",))


def refused(**sections: Any) -> ValidationError:
    with pytest.raises(ValidationError) as caught:
        Settings(**sections)
    return caught.value


def worker(url: str = "http://127.0.0.1:8100", **fields: Any) -> WorkerSettings:
    return WorkerSettings(id="w1", url=url, class_token="t", **fields)


def test_defaults_are_a_single_lab_on_loopback() -> None:
    settings = Settings()
    assert settings.classroom is None and settings.worker is None
    assert (settings.listen.host, settings.listen.port, settings.lab.launch) == ("127.0.0.1", 8000, "all")
    assert not settings.confines_paths


@pytest.mark.parametrize("port", [-1, 65536])
@pytest.mark.parametrize("where", ["listen.port", "lab.foxglove_port", "lab.rosbridge_port"])
def test_a_port_outside_0_to_65535_names_its_field(where: str, port: int) -> None:
    section, field = where.split(".")
    kind = Listening if section == "listen" else LabSettings
    with pytest.raises(ValidationError) as caught:
        kind(**{field: port})
    assert explain(caught.value).startswith(f"{field}: Input should be")
    assert kind(**{field: 0 if port < 0 else 65535}) is not None


def test_size_limits_too_small_to_carry_a_message_are_refused() -> None:
    for field, small, enough in (("max_body_bytes", 1023, 1024), ("max_ws_frame_bytes", 255, 256)):
        with pytest.raises(ValidationError, match=field):
            Listening(**{field: small})
        assert getattr(Listening(**{field: enough}), field) == enough


@pytest.mark.parametrize("workers", [-1, MAX_LOCAL_WORKERS + 1])
def test_local_workers_outside_their_range_are_refused(workers: int) -> None:
    error = refused(lab=LabSettings(zenoh=ROUTER), classroom={"local_workers": workers})
    assert explain(error) == WORKERS_RULE


@pytest.mark.parametrize("zenoh", [None, CLIENT], ids=["no zenoh", "not its own router"])
def test_local_workers_need_the_class_servers_own_router(zenoh: ZenohSettings | None) -> None:
    error = refused(lab=LabSettings(zenoh=zenoh), classroom=ClassroomSettings(local_workers=1))
    assert explain(error) == WORKERS_RULE and not is_refusal(error)
    good = Settings(
        lab=LabSettings(zenoh=ROUTER), classroom=ClassroomSettings(local_workers=MAX_LOCAL_WORKERS)
    )
    assert good.classroom is not None and good.classroom.local_workers == MAX_LOCAL_WORKERS


def test_local_worlds_need_zenoh_and_a_count_of_at_least_zero() -> None:
    assert explain(refused(classroom=ClassroomSettings(local_worlds=1))) == LOCAL_WORLDS_RULE
    assert (
        explain(refused(lab=LabSettings(zenoh=ROUTER), classroom={"local_worlds": -1})) == LOCAL_WORLDS_RULE
    )
    for zenoh in (ROUTER, CLIENT):  # a worker's own router or the class's: world workers join it
        good = Settings(
            lab=LabSettings(zenoh=zenoh), classroom=ClassroomSettings(local_worlds=0, max_worlds=5)
        )
        assert good.classroom is not None and good.classroom.local_capacity == 0
    assert ClassroomSettings(local_worlds=9, max_worlds=5).local_capacity == 5
    assert ClassroomSettings(max_worlds=5).local_capacity == 5


def test_a_class_holds_at_least_one_world_and_one_per_address() -> None:
    with pytest.raises(ValidationError, match="--max-worlds must be at least 1"):
        ClassroomSettings(max_worlds=0)
    with pytest.raises(ValidationError, match="--max-worlds-per-address needs --classroom, and N >= 1"):
        JoinLimits(max_worlds_per_address=0)
    assert JoinLimits(max_worlds_per_address=1).max_worlds_per_address == 1
    assert ClassroomSettings(max_worlds=1).max_worlds == 1


@pytest.mark.parametrize(("timeout_s", "ok"), [(1.9, False), (2.0, True), (3600.0, True), (3600.5, False)])
def test_the_worker_timeout_is_2_to_3600_s(timeout_s: float, ok: bool) -> None:
    if ok:
        assert ClassroomSettings(worker_timeout_s=timeout_s).worker_timeout_s == timeout_s
    else:
        with pytest.raises(ValidationError, match=r"--worker-timeout must be in 2\.\.3600 s"):
            ClassroomSettings(worker_timeout_s=timeout_s)


@pytest.mark.parametrize(("timeout_s", "ok"), [(0.5, False), (1.0, True), (3600.0, True), (3601.0, False)])
def test_the_orphan_timeout_is_1_to_3600_s(timeout_s: float, ok: bool) -> None:
    if ok:
        assert worker(orphan_timeout_s=timeout_s).orphan_timeout_s == timeout_s
    else:
        with pytest.raises(ValidationError, match=r"--orphan-timeout must be in 1\.\.3600 s"):
            worker(orphan_timeout_s=timeout_s)


def test_a_world_worker_needs_its_class_and_an_address_the_class_server_reaches() -> None:
    assert "needs the classroom section" in explain(refused(worker=worker()))
    for url in ("http://0.0.0.0:8100", "http://[::]:8100"):
        message = explain(refused(classroom=ClassroomSettings(), worker=worker(url)))
        assert message.startswith("with --host 0.0.0.0") and "--advertise HOST" in message
    good = Settings(
        listen=Listening(host="0.0.0.0", allowed_hosts=("10.0.0.5",)),
        classroom=ClassroomSettings(),
        worker=worker("http://10.0.0.5:8100"),
    )
    assert good.worker is not None and good.confines_paths
    assert "class_token" not in repr(good) and "'t'" not in repr(good)  # the instructor's, never shown


@pytest.mark.parametrize("host", ["0.0.0.0", "192.168.1.20", "::"])
def test_listening_beyond_loopback_needs_a_token_or_a_class(host: str) -> None:
    error = refused(listen=Listening(host=host))
    assert is_refusal(error)
    assert explain(error).startswith(f"refusing to listen on {host} with no login")
    assert Settings(listen=Listening(host=host, token="secret")).listen.token == "secret"
    assert Settings(listen=Listening(host=host), classroom=ClassroomSettings()).classroom is not None


def test_a_zenoh_router_beyond_loopback_needs_a_token_or_a_class() -> None:
    wide = ZenohSettings(listen=("tcp/127.0.0.1:7447", "tcp/0.0.0.0:7448"))
    error = refused(lab=LabSettings(zenoh=wide))
    assert is_refusal(error)
    assert explain(error).startswith("refusing to open the Zenoh router on tcp/0.0.0.0:7448 with no login")
    assert Settings(listen=Listening(token="t"), lab=LabSettings(zenoh=wide)).lab.zenoh == wide
    assert Settings(lab=LabSettings(zenoh=wide), classroom=ClassroomSettings()).lab.zenoh == wide
    peer = ZenohSettings(mode="peer", listen=("tcp/0.0.0.0:0",), connect=("tcp/127.0.0.1:7447",))
    assert Settings(lab=LabSettings(zenoh=peer)).lab.zenoh == peer  # only a router lets others in


def test_log_levels_are_the_consoles() -> None:
    with pytest.raises(
        ValidationError, match="a log level is one of debug, info, warning, error, got 'loud'"
    ):
        Settings(log_level="loud")
    with pytest.raises(ValidationError, match="got 'verbose'"):
        ClassroomSettings(world_log_level="verbose")
    assert (
        Settings(log_level="debug", classroom=ClassroomSettings(world_log_level="info")).log_level == "debug"
    )


def test_sections_are_frozen_and_refuse_unknown_names() -> None:
    settings = Settings()
    with pytest.raises(ValidationError, match="frozen"):
        settings.listen.port = 1  # type: ignore[misc]
    with pytest.raises(ValidationError, match="Extra inputs are not permitted"):
        LabSettings(lauch="fly")  # type: ignore[call-arg]
    with pytest.raises(ValidationError, match="zenoh"):
        LabSettings(zenoh={"mode": "router"})  # a ZenohSettings, never a dict
    assert LabSettings(launch="fly").launch == "fly"


def test_explain_gives_one_line_per_error() -> None:
    error = refused(listen={"port": 70000}, classroom={"max_worlds": 0})
    assert explain(error).splitlines() == [
        "listen.port: Input should be less than or equal to 65535",
        "--max-worlds must be at least 1",
    ]
    assert not is_refusal(error)


def test_a_worlds_lab_takes_the_smaller_of_each_limit_and_no_bridge_port() -> None:
    klass = Settings(
        lab=LabSettings(foxglove_port=8765, rosbridge_port=9090, launch="all"),
        limits={"max_launch_groups": 2, "max_nodes_per_launch": 64},
        classroom=ClassroomSettings(world={"launches": 4, "launch_nodes": 16, "socket_frames_hz": 300.0}),
    )
    world = klass.for_world("ada", CLIENT, "fly", {"simple": "true"})
    assert (world.lab.foxglove_port, world.lab.rosbridge_port, world.lab.zenoh) == (None, None, CLIENT)
    assert (world.lab.launch, world.lab.launch_args, world.lab.bag_dir) == (
        "fly",
        {"simple": "true"},
        klass.lab.bag_dir / "ada",
    )
    assert (world.limits.max_launch_groups, world.limits.max_nodes_per_launch) == (2, 16)
    assert (world.limits.socket_frames_hz, world.limits.socket_requests_hz) == (300.0, 200.0)
    assert world.classroom == klass.classroom and klass.lab.launch == "all"  # the class's own are untouched
    with pytest.raises(ValueError, match="only a class server or a world worker has worlds"):
        Settings().for_world("ada", None, "fly", {})


def test_a_fields_default_and_choices_are_read_from_the_model_as_the_command_lines_show_them() -> None:
    assert default_of(Listening, "port") == Listening().port
    assert default_of(ClassroomSettings, "workspaces_dir") == ClassroomSettings().workspaces_dir
    assert default_of(LabSettings, "launch_args") == {}  # a default factory's value
    assert choices_of(SandboxSettings, "student_code") == ("sandboxed", "unsandboxed")
    assert (shown(Path("bags")), shown(Path("/srv/bags")), shown(20.0), shown(7.5), shown("auto")) == (
        "./bags",
        "/srv/bags",
        "20",
        "7.5",
        "auto",
    )
