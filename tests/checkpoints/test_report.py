"""The report, its signature and a lab's own checkpoints, without a server."""

from __future__ import annotations

import base64
import json
from pathlib import Path

import pytest

from server.world.checkpoints.catalog import LAB_CHECKPOINTS, CheckpointLoadError, load
from server.world.checkpoints.progress import Progress
from server.world.checkpoints.report import build, signed_files
from server.world.checkpoints.signing import ReportSigner, canonical

SIGNER = ReportSigner(b"\x07" * 32)
TRACK = [[float(t), t * 0.5, t * 0.5, 3 + t * 0.7] for t in range(10)]


def progress_with_a_track() -> Progress:
    progress = Progress(LAB_CHECKPOINTS, "Ada", wall=lambda: 1_800_000_000.0)
    progress.met("fly_to_point", {"target": [5.0, 5.0, 10.0], "track": TRACK, "rate_hz": 1.0})
    progress.answer("q1", "four nodes </script><script>alert(1)</script>")
    return progress


def test_report_without_a_capture_draws_the_track_top_and_side() -> None:
    report = build(progress_with_a_track(), {}, "ada")
    fly = next(c for c in report["checkpoints"] if c["name"] == "fly_to_point")
    assert fly["state"] == "done" and fly["done_at"] == "2027-01-15T08:00:00Z"
    assert fly["picture"].startswith("data:image/svg+xml;base64,")
    svg = base64.b64decode(fly["picture"].split(",", 1)[1]).decode()
    assert svg.count("<polyline") == 2 and "top: x" in svg and "side: x" in svg
    assert next(c for c in report["checkpoints"] if c["name"] == "keyboard_abort")["picture"] is None


def test_report_page_embeds_the_json_and_no_student_text_becomes_markup() -> None:
    json_file, page = signed_files(SIGNER, build(progress_with_a_track(), {}, "ada"))
    assert b"<script>alert(1)</script>" not in page
    assert page.count(b"</script>") == 1  # only the embedded report's own end
    assert SIGNER.verify(page).valid and SIGNER.verify(json_file).valid
    assert SIGNER.verify(page).student == "Ada"


def test_verify_json_reordered_or_reformatted_is_edited_though_it_says_the_same() -> None:
    json_file, _ = signed_files(SIGNER, build(progress_with_a_track(), {}, "ada"))
    pretty = json.dumps(json.loads(json_file), indent=2).encode()
    assert "edited" in SIGNER.verify(pretty).reason
    assert SIGNER.verify(json_file + b"\n").valid  # a trailing newline an editor adds is not content


def test_verify_a_page_with_its_signature_changed_or_removed() -> None:
    _, page = signed_files(SIGNER, build(progress_with_a_track(), {}, "ada"))
    start = page.index(b'content="') + len(b'content="')
    forged = page[:start] + SIGNER.key_id.encode() + b":" + b"0" * 64 + page[page.index(b'">', start) :]
    assert "edited" in SIGNER.verify(forged).reason
    unsigned = page.replace(
        page[page.index(b'<meta name="report-signature"') : page.index(b'">', start) + 2], b""
    )
    assert SIGNER.verify(unsigned).reason.startswith("not a report")


def test_sign_html_needs_one_empty_signature_tag() -> None:
    with pytest.raises(ValueError, match="exactly one"):
        SIGNER.sign_html(b"<html>no tag</html>")


def test_canonical_json_is_sorted_and_compact() -> None:
    assert canonical({"b": 1, "a": [1, "é"]}) == '{"a":[1,"é"],"b":1}'.encode()


def test_key_is_made_once_in_the_state_folder_and_kept(tmp_path: Path) -> None:
    first = ReportSigner.in_folder(tmp_path / "state")
    again = ReportSigner.in_folder(tmp_path / "state")
    assert first.key_id == again.key_id
    assert ReportSigner.in_folder(tmp_path / "other").key_id != first.key_id


CLIMB = """
from server.world.checkpoints.declared import Checkpoint, Step
from server.world.checkpoints.events import Gps


class ClimbCheck:
    started = False

    def feed(self, event):
        if isinstance(event, Gps) and event.xyz[2] >= 20.0:
            return {"altitude_m": event.xyz[2]}
        return None

    def tick(self, now_s):
        return None

    def progress(self, now_s):
        return "climb to 20 m"


CLIMB = Checkpoint(name="climb", title="Climb to 20 m", steps=(Step("Publish z = 20."),), check=ClimbCheck)
NOT_ONE = 42
"""


def test_a_labs_own_checkpoint_joins_the_three_by_name(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    (tmp_path / "my_lab_checks.py").write_text(CLIMB)
    monkeypatch.syspath_prepend(str(tmp_path))
    checkpoints = load(["my_lab_checks:CLIMB"])
    assert [c.name for c in checkpoints] == ["keyboard_abort", "fly_to_point", "launch_and_keys", "climb"]
    for bad, says in [
        ("my_lab_checks:NOT_ONE", "not a Checkpoint"),
        ("my_lab_checks:NOPE", "NOPE"),
        ("no_such_module:X", "no_such_module"),
    ]:
        with pytest.raises(CheckpointLoadError, match=says):
            load([bad])
    with pytest.raises(CheckpointLoadError, match="taken"):
        load(["my_lab_checks:CLIMB", "my_lab_checks:CLIMB"])
