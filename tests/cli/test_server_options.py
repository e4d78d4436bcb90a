"""``python -m server`` and ``ros2lab world-worker`` map their options onto the settings model,
and print its error: a bad combination exits 2 naming the options, a good one becomes settings."""

from __future__ import annotations

from pathlib import Path

import pytest

from server import world_worker
from server.__main__ import build_parser, main, settings_of, zenoh_settings
from server.classroom.worker_control import TOKEN_ENV
from server.host.settings import Settings


def server_settings(*argv: str) -> Settings:
    args = build_parser().parse_args(list(argv))
    return settings_of(args, zenoh_settings(args))


def exits_2(argv: list[str], capsys: pytest.CaptureFixture[str], run: object = main) -> str:
    with pytest.raises(SystemExit) as exited:
        run(argv)  # type: ignore[operator]
    assert exited.value.code == 2
    return capsys.readouterr().err


def test_a_class_servers_options_land_in_its_classroom_section() -> None:
    settings = server_settings(
        "--classroom",
        "--class-code",
        "ABC123",
        "--max-worlds",
        "5",
        "--local-worlds",
        "2",
        "--workers",
        "2",
        "--worker-timeout",
        "30",
        "--max-worlds-per-address",
        "1",
        "--world-log-level",
        "info",
        "--port",
        "8100",
    )
    klass = settings.classroom
    assert klass is not None and settings.worker is None
    assert (klass.code, klass.max_worlds, klass.local_worlds, klass.local_workers) == ("ABC123", 5, 2, 2)
    assert (klass.worker_timeout_s, klass.joins.max_worlds_per_address, klass.world_log_level) == (
        30.0,
        1,
        "info",
    )
    assert settings.listen.port == 8100 and settings.lab.zenoh_router is not None
    assert server_settings().classroom is None


@pytest.mark.parametrize(
    ("argv", "flag"),
    [
        (["--workers", "1"], "--workers"),
        (["--local-worlds", "0"], "--local-worlds"),
        (["--max-worlds-per-address", "2"], "--max-worlds-per-address"),
    ],
)
def test_a_class_option_without_classroom_is_refused(
    argv: list[str], flag: str, capsys: pytest.CaptureFixture[str]
) -> None:
    assert f"error: {flag} needs --classroom" in exits_2(argv, capsys)
    assert server_settings("--classroom", *argv).classroom is not None


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["--port", "70000"], "listen.port: Input should be less than or equal to 65535"),
        (["--rosbridge-port", "-1"], "lab.rosbridge_port: Input should be greater than or equal to 0"),
        (["--classroom", "--worker-timeout", "1"], "--worker-timeout must be in 2..3600 s"),
        (["--classroom", "--max-worlds", "0"], "--max-worlds must be at least 1"),
        (["--classroom", "--local-worlds", "1", "--no-zenoh"], "--local-worlds needs --classroom and Zenoh"),
    ],
)
def test_the_models_error_is_the_usage_error(
    argv: list[str], message: str, capsys: pytest.CaptureFixture[str]
) -> None:
    err = exits_2(argv, capsys)
    assert f"python -m server: error: {message}" in err and "usage:" in err


def test_a_token_lets_the_lab_listen_beyond_loopback(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["--host", "0.0.0.0", "--no-zenoh"]) == 2
    assert "refusing to listen on 0.0.0.0" in capsys.readouterr().err
    settings = server_settings("--host", "0.0.0.0", "--no-zenoh", "--token", "auto")
    assert settings.listen.token is not None and len(settings.listen.token) >= 24
    assert settings.confines_paths
    assert server_settings("--host", "0.0.0.0", "--classroom").classroom is not None


def worker_args(*argv: str) -> list[str]:
    return ["--connect", "tcp/127.0.0.1:7447", *argv]


def test_a_world_workers_options_land_in_its_sections() -> None:
    args = world_worker.build_parser().parse_args(worker_args("--host", "0.0.0.0", "--advertise", "10.0.0.5"))
    settings = world_worker.worker_settings(args, "instructor-token", 8123)
    assert settings.worker is not None and settings.classroom is not None
    assert settings.worker.url == "http://10.0.0.5:8123" and settings.worker.class_token == "instructor-token"
    assert settings.listen.allowed_hosts == ("10.0.0.5",) and settings.listen.port == 8123
    assert settings.lab.zenoh is not None and settings.lab.zenoh.connect == ("tcp/127.0.0.1:7447",)
    args = world_worker.build_parser().parse_args(worker_args("--host", "::1"))
    loopback = world_worker.worker_settings(args, "t", 8124)
    assert loopback.worker is not None and loopback.worker.url == "http://[::1]:8124"
    assert loopback.worker.start_slots is None  # started by hand: it paces its own node starts
    args = world_worker.build_parser().parse_args(
        worker_args("--start-slots", "/srv/class/state/start-slots")
    )
    shared = world_worker.worker_settings(args, "t", 8125).worker
    assert shared is not None and shared.start_slots == Path("/srv/class/state/start-slots")


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["--host", "0.0.0.0"], "with --host 0.0.0.0, name the address the class server reaches"),
        (["--max-worlds", "0"], "--max-worlds must be at least 1"),
        (["--orphan-timeout", "0.5"], "--orphan-timeout must be in 1..3600 s"),
        (["--port", "70000"], "listen.port: Input should be less than or equal to 65535"),
    ],
)
def test_a_world_worker_refuses_a_bad_combination_before_it_binds_or_connects(
    argv: list[str], message: str, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv(TOKEN_ENV, "instructor-token")
    err = exits_2(worker_args(*argv), capsys, world_worker.main)
    assert f"ros2lab world-worker: error: {message}" in err
