"""The page's own controls, as the page shows them, for the Guide's steps and lines: one place, so
that a step names what the student sees (tests/checkpoints/test_guide_words.py checks each name
against where the page draws it)."""

from __future__ import annotations

from server.services.workspace.templates import TEMPLATES

CODE = "</> Code"  # the code view's tab (web/src/lab/codeview.ts)
RUN = "\u25b6 Run"  # the code view's buttons (web/src/editor/main.ts)
NEW_PACKAGE = "New package"
NEW_FILE = "New file"
GRAPH = "Graph & topics \u2197"  # the link to the graph page (web/src/lab/nav.ts)
RESET_ROCKET = (
    "Reset rocket"  # the rocket's button in the 3D view's panel (server/peripherals/viewer/rocket_view.py)
)
PUBLISHER = (
    "Message Publisher"  # the 3D view's publisher panel (server/peripherals/viewer/publisher_panel.py)
)
RATE = "Rate (Hz)"
ENABLED = "Enabled"

_TITLES = {t.name: t.title for t in TEMPLATES}  # the starting files that New file offers
ROCKET_TEMPLATE = _TITLES["rocket_keyboard_manager"]
DRONE_TEMPLATE = _TITLES["drone_keyboard_manager"]
POSITION_TEMPLATE = _TITLES["position_publisher"]
LAUNCH_TEMPLATE = _TITLES["fly_launch"]
