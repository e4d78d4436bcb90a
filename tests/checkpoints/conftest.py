"""Settings for the checkpoints' API tests: a lab without viser, reachable as TestClient's Host."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from server.host.settings import LabSettings, Listening, Settings

QUIET_START_DELAY = "3600"  # the rocket's countdown does not start during a test


def lab_settings(state_dir: Path, launch: str = "rocket", **args: Any) -> Settings:
    launch_args = {"start_delay": QUIET_START_DELAY} if launch == "rocket" else {}
    return Settings(
        listen=Listening(allowed_hosts=("testserver",)),
        lab=LabSettings(
            launch=launch, launch_args={**launch_args, **args}, viewer=False, state_dir=state_dir
        ),
    )
