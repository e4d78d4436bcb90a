"""Whether two processes share one class's workspaces folder: the class server leaves a mark (a
random word) in its ``workspaces_dir``; a world worker reads the mark in its own and says it in
each hello. The same mark means the same folder, whether it is the same path on this host or a
shared mount on another, so a world moved between them finds its files."""

from __future__ import annotations

import secrets
from pathlib import Path

MARK_FILE = ".class-mark"  # a hidden name: never a world's (world names start with a letter or digit)
MAX_MARK_CHARS = 64


def leave_mark(workspaces_dir: Path) -> str:
    """The folder's mark, written (with the folder) if it has none yet: it stays across restarts."""
    found = read_mark(workspaces_dir)
    if found is not None:
        return found
    workspaces_dir.mkdir(parents=True, exist_ok=True)
    mark = secrets.token_hex(16)
    staged = workspaces_dir / f"{MARK_FILE}.{mark}"
    staged.write_text(mark)
    staged.replace(workspaces_dir / MARK_FILE)  # in one step: a reader never sees half a mark
    return mark


def read_mark(workspaces_dir: Path) -> str | None:
    """The mark in ``workspaces_dir`` (None: none there, or not a mark)."""
    try:
        text = (workspaces_dir / MARK_FILE).read_text(errors="replace").strip()
    except OSError:
        return None
    return text if 0 < len(text) <= MAX_MARK_CHARS and text.isalnum() else None
