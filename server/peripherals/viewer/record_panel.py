"""The page's Recording panel: one button records the current flight as ros2 bag record -a would,
the same button stops it, and a link downloads the last bag's MCAP (which Foxglove, Lichtblick
and ``ros2 bag info`` open). A separate folder of its own, so the page can place it anywhere.

viser calls the button on its own threads; the work hops to the app's loop, where the bus is.
"""

from __future__ import annotations

import asyncio
import logging
from typing import Any

log = logging.getLogger("viewer.record")
IDLE_LABEL, RECORDING_LABEL = "Record flight", "Stop recording"


def download_markdown(name: str, messages: int) -> str:
    return f"[Download {name} (MCAP, {messages} messages)](/api/bag/recordings/{name}/download)"


class RecordPanel:
    def __init__(self, lab: Any) -> None:
        self.lab = lab
        gui = lab.display.gui
        self.recording: str | None = None
        with gui.add_folder("Recording", expand_by_default=False, order=60.0):
            self.button = gui.add_button(
                IDLE_LABEL, hint="record every topic into a bag (ros2 bag record -a)"
            )
            self.link = gui.add_markdown("")
        self.button.on_click(lambda _e: lab.display.call_in_app(self.toggle))

    def toggle(self) -> None:
        """Start a recording, or stop the one running (on the app's loop)."""
        if self.recording is None:
            try:
                self.recording = self.lab.bags.record(all_topics=True).name
            except (ValueError, RuntimeError, OSError) as exc:
                self.link.content = f"**error:** {exc}"
                return
            self.button.label = RECORDING_LABEL
            self.link.content = f"recording `{self.recording}` ..."
            return
        name, self.recording = self.recording, None
        recording = self.lab.bags.detach_recording(name)
        self.button.label = IDLE_LABEL
        self.link.content = f"finishing `{name}` ..."
        task = asyncio.get_running_loop().create_task(asyncio.to_thread(recording.writer.close))
        task.add_done_callback(lambda _t: self._finished(name))

    def _finished(self, name: str) -> None:
        summary = self.lab.bags.recordings[name].describe()
        self.link.content = download_markdown(name, summary["messages"])
