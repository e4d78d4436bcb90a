"""Each default is written once, in the settings model: ``python -m server`` and ``ros2lab
world-worker`` read their options' defaults from its fields, and their help shows those values.

The command lines are parsed for real and mapped onto the model as ``main`` does, so an option
whose default drifts from its field's makes the settings differ from the model's own."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest
from pydantic import BaseModel

from server import world_worker
from server.__main__ import build_parser, settings_of, zenoh_settings
from server.cli.environment import DEFAULT_URL
from server.host.settings import (
    FOXGLOVE_PORT,
    WORKER_MAX_WORLDS,
    WORKER_PORT,
    ClassroomSettings,
    LabSettings,
    Listening,
    Settings,
    WorkerSettings,
    default_of,
)

CLASS_TOKEN = "instructor-token"


def server_settings(*argv: str) -> Settings:
    args = build_parser().parse_args(list(argv))
    return settings_of(args, zenoh_settings(args))


def worker_settings(*argv: str) -> Settings:
    args = world_worker.build_parser().parse_args(["--connect", "tcp/127.0.0.1:7447", *argv])
    return world_worker.worker_settings(args, CLASS_TOKEN, args.port)


def without_graph(settings: Settings) -> dict[str, Any]:
    """The settings as a dict, but for the Zenoh session: the command line's own (its defaults
    are the transport's, not the settings model's)."""
    return settings.model_copy(update={"lab": settings.lab.model_copy(update={"zenoh": None})}).model_dump()


def flat_help(parser: Any) -> str:
    return " ".join(parser.format_help().split())


def test_a_single_labs_options_default_to_the_models_fields() -> None:
    settings = server_settings()
    # A lab built by hand starts no Foxglove server; python -m server does, on its own port.
    assert without_graph(settings) == Settings(lab=LabSettings(foxglove_port=FOXGLOVE_PORT)).model_dump()
    assert server_settings("--no-foxglove").lab.foxglove_port is None


def test_a_class_servers_options_default_to_the_models_fields() -> None:
    settings = server_settings("--classroom")
    assert settings.classroom is not None
    assert settings.classroom.model_dump() == ClassroomSettings().model_dump()
    expected = Settings(lab=LabSettings(foxglove_port=FOXGLOVE_PORT), classroom=ClassroomSettings())
    assert without_graph(settings) == expected.model_dump()


def test_a_world_workers_options_default_to_the_models_fields() -> None:
    settings = worker_settings()
    assert settings.worker is not None
    # A worker's own defaults: a free port, and fewer worlds than a class server takes.
    assert settings.listen.port == WORKER_PORT
    expected = Settings(
        listen=Listening(port=WORKER_PORT),
        classroom=ClassroomSettings(max_worlds=WORKER_MAX_WORLDS),
        worker=WorkerSettings(id=settings.worker.id, url=settings.worker.url, class_token=CLASS_TOKEN),
    )
    assert without_graph(settings) == expected.model_dump()


def test_the_clients_default_url_is_where_a_lab_with_no_options_listens() -> None:
    """``ros2lab`` imports nothing of the server, so it writes the address itself: the model's."""
    listen = server_settings().listen
    assert f"http://{listen.host}:{listen.port}" == DEFAULT_URL


def changed_default(
    monkeypatch: pytest.MonkeyPatch, section: type[BaseModel], name: str, value: object
) -> None:
    """The field's default as if the model's source said ``value`` (what the parsers read of it)."""
    monkeypatch.setattr(section.model_fields[name], "default", value)
    assert default_of(section, name) == value


def test_a_default_changed_in_the_model_is_python_m_servers_and_its_help_shows_it(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    changed_default(monkeypatch, Listening, "port", 8123)
    changed_default(monkeypatch, LabSettings, "bag_dir", Path("recordings"))
    changed_default(monkeypatch, ClassroomSettings, "worker_timeout_s", 45.0)
    changed_default(monkeypatch, ClassroomSettings, "world_log_level", "error")
    shown = flat_help(build_parser())
    assert "port (default 8123)" in shown and "where recordings are written (default ./recordings)" in shown
    assert "under the same names and tokens (default 45)" in shown
    assert "this console shows (default error:" in shown
    settings = server_settings("--classroom")
    assert settings.classroom is not None
    assert (settings.listen.port, settings.lab.bag_dir) == (8123, Path("recordings"))
    assert (settings.classroom.worker_timeout_s, settings.classroom.world_log_level) == (45.0, "error")


def test_a_default_changed_in_the_model_is_the_world_workers_and_its_help_shows_it(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    changed_default(monkeypatch, ClassroomSettings, "workspaces_dir", Path("class-folders"))
    changed_default(monkeypatch, WorkerSettings, "orphan_timeout_s", 7.5)
    changed_default(monkeypatch, LabSettings, "state_dir", Path("/srv/lab/state"))
    shown = flat_help(world_worker.build_parser())
    assert "a folder per world (default ./class-folders)" in shown
    assert "(default 7.5; keep it below" in shown and "are kept (default /srv/lab/state)" in shown
    settings = worker_settings()
    assert settings.classroom is not None and settings.worker is not None
    assert settings.classroom.workspaces_dir == Path("class-folders")
    assert (settings.worker.orphan_timeout_s, settings.lab.state_dir) == (7.5, Path("/srv/lab/state"))
