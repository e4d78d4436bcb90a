"""A single lab with a workspace in a temporary folder, behind a TestClient (no 3D view, no
countdown during the test), and the calls the workspace tests make."""

from __future__ import annotations

import io
import zipfile
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

from fastapi.testclient import TestClient

from server.app import create_app
from server.host.settings import LabLimits, LabSettings, Listening, Settings, WorkspaceLimits

FILES = "/api/workspace/files"


def lab_settings(workspace: Path | None, **lab: Any) -> Settings:
    limits = lab.pop("limits", {})
    files = lab.pop("files", {})
    return Settings(
        listen=Listening(allowed_hosts=("testserver",)),
        lab=LabSettings(
            **{
                "launch": "rocket",
                "launch_args": {"start_delay": "3600"},
                "viewer": False,
                "workspace": workspace,
                **lab,
            }
        ),
        limits=LabLimits(**limits),
        workspace=WorkspaceLimits(**files),
    )


@contextmanager
def lab_client(settings: Settings) -> Iterator[TestClient]:
    with TestClient(create_app(settings)) as client:
        yield client


def tree(client: TestClient, **headers: str) -> dict[str, Any]:
    reply = client.get(FILES, headers=headers)
    assert reply.status_code == 200, reply.text
    return reply.json()


def save(client: TestClient, path: str, text: str, **headers: str) -> Any:
    return client.put(f"{FILES}/{path}", json={"text": text}, headers=headers)


def zip_of(entries: dict[str, bytes | str]) -> bytes:
    buffer = io.BytesIO()
    with zipfile.ZipFile(buffer, "w", zipfile.ZIP_DEFLATED) as archive:
        for name, data in entries.items():
            archive.writestr(name, data)
    return buffer.getvalue()


def upload(client: TestClient, data: bytes, **headers: str) -> Any:
    return client.post(
        "/api/workspace/archive", content=data, headers={"content-type": "application/zip", **headers}
    )


def names_in(data: bytes) -> list[str]:
    with zipfile.ZipFile(io.BytesIO(data)) as archive:
        return sorted(archive.namelist())
