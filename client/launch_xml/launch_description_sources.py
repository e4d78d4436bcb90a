"""``XMLLaunchDescriptionSource(path)``: include a XML launch file from a Python one."""

from __future__ import annotations

from typing import Any

from launch.launch_description_sources import FrontendLaunchDescriptionSource


class XMLLaunchDescriptionSource(FrontendLaunchDescriptionSource):
    def __init__(self, launch_file_path: Any) -> None:
        super().__init__(launch_file_path)


__all__ = ["XMLLaunchDescriptionSource"]
