"""A class server's progress across its restart, through the real app (``python -m server
--classroom`` in a subprocess, ended by its id): Ada meets fly_to_point and answers, Bob answers;
the class server is ended and a new one started on the same state folder.

Before anyone joins again, the instructor's table, its CSV and the class's zip list both, as not
joined, with what their files keep. Eve joining as "Ada" without Ada's token (or with a made-up
one) is refused with 409 and changes nothing; Ada joining again from her browser (the old token in
her cookie) takes her progress. Code is kept as progress is: Cy, who wrote code and met no
checkpoint, is refused the same way to anyone else and gets it back from her browser; Dan, who
joined and kept nothing, leaves his name free. The instructor releases Bob's progress, and the next join as "Bob"
takes it; the owner record released is kept beside, never removed."""

from __future__ import annotations

import csv
import hashlib
import io
import json
import textwrap
import zipfile
from pathlib import Path
from typing import Any

import httpx
from support.app import App, instructor_token
from support.http import HTTP

from server.world.checkpoints.owner import OWNER_FILE
from server.world.checkpoints.store import PROGRESS_DIR

from .test_restart import FLY_SIMPLE, NOTHING, meet_fly_to_point

CODE = "RST042"


def start(root: Path, run: str, launch: str) -> tuple[App, str]:
    (root / run).mkdir()
    app = App(
        root / run,
        "--classroom",
        "--class-code",
        CODE,
        "--launch",
        str(root / launch),
        "--state-dir",
        str(root / "state"),
        "--no-foxglove",
        cwd=root,
    )
    return app, instructor_token(app.log_tail(100_000))


def bearer(token: str) -> dict[str, str]:
    return {"Authorization": f"Bearer {token}"}


def join(app: App, name: str, **headers: str) -> httpx.Response:
    return HTTP.post(
        f"{app.url}/api/classroom/join", json={"name": name, "code": CODE}, headers=headers, timeout=60
    )


def joined(app: App, name: str, **headers: str) -> str:
    reply = join(app, name, **headers)
    assert reply.status_code == 201, reply.text
    return str(reply.json()["token"])


def students(app: App, teacher: str) -> dict[str, dict[str, Any]]:
    reply = HTTP.get(f"{app.url}/api/classroom/checkpoints", headers=bearer(teacher), timeout=10)
    assert reply.status_code == 200, reply.text
    return {s["world"]: s for s in reply.json()["students"]}


def answer(app: App, token: str, text: str, qid: str = "q1") -> None:
    reply = HTTP.put(f"{app.url}/api/checkpoints/answers/{qid}", json={"text": text}, headers=bearer(token))
    assert reply.status_code == 200, reply.text


CY_CODE = "print('my keyboard manager')\n"
CY_FILE = "src/mine/mine/keyboard_manager.py"


def save_code(app: App, token: str, text: str) -> None:
    reply = HTTP.put(f"{app.url}/api/workspace/files/{CY_FILE}", json={"text": text}, headers=bearer(token))
    assert reply.status_code == 201, reply.text


def code_of(app: App, token: str) -> str:
    reply = HTTP.get(f"{app.url}/api/workspace/files/{CY_FILE}", headers=bearer(token), timeout=10)
    assert reply.status_code == 200, reply.text
    return str(reply.json()["text"])


def world_view(app: App, token: str) -> dict[str, Any]:
    reply = HTTP.get(f"{app.url}/api/checkpoints", headers=bearer(token), timeout=10)
    assert reply.status_code == 200, reply.text
    return dict(reply.json())


class World:
    """What a test keeps of a student's world to fly it with meet_fly_to_point."""

    def __init__(self, app: App, token: str) -> None:
        self.url, self.token, self.log_tail = app.url, token, app.log_tail

    def post(self, path: str, body: dict[str, Any]) -> httpx.Response:
        return HTTP.post(self.url + path, json=body, headers=bearer(self.token), timeout=30)

    def get(self, path: str, **params: Any) -> Any:
        reply = HTTP.get(self.url + path, params=params, headers=bearer(self.token), timeout=10)
        reply.raise_for_status()
        return reply.json()


def test_a_restarted_class_lists_saved_students_and_gives_their_progress_to_them_alone(
    tmp_path: Path,
) -> None:
    (tmp_path / "fly_simple.launch").write_text(textwrap.dedent(FLY_SIMPLE).lstrip())
    (tmp_path / "nothing.launch").write_text(NOTHING)
    first, _ = start(tmp_path, "first", "fly_simple.launch")
    try:
        ada = joined(first, "Ada")
        bob = joined(first, "Bob")
        cy = joined(first, "Cy")  # writes code and meets no checkpoint
        joined(first, "Dan")  # does nothing
        answer(first, ada, "four nodes")
        answer(first, bob, "two nodes")
        save_code(first, cy, CY_CODE)
        met = meet_fly_to_point(World(first, ada))  # type: ignore[arg-type]
    finally:
        first.stop()  # Ctrl-C to its id: it writes what waits, then ends

    second, teacher = start(tmp_path, "second", "nothing.launch")
    try:
        # Listed before anyone joins again: not joined, with what their files keep.
        before = students(second, teacher)
        assert set(before) == {"ada", "bob"}
        assert before["ada"]["name"] == "Ada" and before["ada"]["joined"] is False
        assert before["ada"]["cells"]["fly_to_point"] == {"state": "done", "done_at": met["done_at"]}
        assert (
            before["ada"]["answers"]["q1"] == "four nodes" and before["bob"]["answers"]["q1"] == "two nodes"
        )
        assert before["bob"]["cells"]["fly_to_point"]["state"] == "not_started"
        table = HTTP.get(
            f"{second.url}/api/classroom/checkpoints",
            params={"format": "csv"},
            headers=bearer(teacher),
            timeout=10,
        )
        header = next(csv.reader(io.StringIO(table.text)))
        assert header[:2] == ["student", "world"] and header[-1] == "joined"
        rows = {r["world"]: r for r in csv.DictReader(io.StringIO(table.text))}
        assert rows["ada"]["fly_to_point state"] == "done" and rows["ada"]["joined"] == "no"
        zipped = HTTP.get(
            f"{second.url}/api/classroom/checkpoints/reports", headers=bearer(teacher), timeout=30
        )
        with zipfile.ZipFile(io.BytesIO(zipped.content)) as archive:
            assert sorted(archive.namelist()) == ["ada.html", "ada.json", "bob.html", "bob.json"]
            report = json.loads(archive.read("ada.json"))
        assert report["student"] == "Ada"
        assert next(c for c in report["checkpoints"] if c["name"] == "fly_to_point")["state"] == "done"

        # Someone else under Ada's name: refused, naming why, and nothing changes.
        for headers in ({}, bearer(bob), {"Cookie": "lab_token=made.up"}):
            refused = join(second, "ada", **headers)
            assert refused.status_code == 409, refused.text
            assert "belongs to the student who joined as 'Ada'" in refused.json()["detail"]
        assert students(second, teacher) == before
        owner = tmp_path / "state" / PROGRESS_DIR / "ada" / OWNER_FILE
        assert json.loads(owner.read_text())["token_sha256"] == hashlib.sha256(ada.encode()).hexdigest()

        # Ada from her browser: the token of the first run in her cookie (it grants nothing now).
        assert HTTP.get(f"{second.url}/api/classroom/me", headers=bearer(ada), timeout=10).status_code == 401
        ada_again = joined(second, "Ada", Cookie=f"lab_token={ada}")
        mine = world_view(second, ada_again)
        assert (
            next(c for c in mine["checkpoints"] if c["name"] == "fly_to_point")["done_at"] == met["done_at"]
        )
        assert next(q for q in mine["questions"] if q["id"] == "q1")["answer"] == "four nodes"
        after = students(second, teacher)
        assert after["ada"]["joined"] is True and after["bob"]["joined"] is False
        assert json.loads(owner.read_text())["token_sha256"] == hashlib.sha256(ada_again.encode()).hexdigest()

        # Cy's code is hers as her progress would be; Dan kept nothing, so his name is anyone's.
        refused = join(second, "Cy")
        assert refused.status_code == 409 and "progress or code" in refused.json()["detail"], refused.text
        assert code_of(second, joined(second, "Cy", Cookie=f"lab_token={cy}")) == CY_CODE
        assert join(second, "Dan").status_code == 201

        # Bob lost his cookie: the instructor releases his progress, and the next "Bob" takes it.
        def release(world: str, token: str = teacher) -> httpx.Response:
            return HTTP.post(f"{second.url}/api/classroom/checkpoints/{world}/release", headers=bearer(token))

        assert release("bob", ada_again).status_code == 403
        assert release("ada").status_code == 409  # joined now: hers
        assert release("nobody").status_code == 404
        assert release("Bob!").status_code == 422
        assert join(second, "Bob").status_code == 409
        freed = release("bob")
        assert freed.status_code == 200 and freed.json() == {"released": "bob", "student": "Bob"}
        bob_folder = tmp_path / "state" / PROGRESS_DIR / "bob"
        assert [p.name.startswith(f"{OWNER_FILE}.released-") for p in bob_folder.glob(f"{OWNER_FILE}.*")] == [
            True
        ]
        bob_again = joined(second, "Bob")
        assert (
            next(q for q in world_view(second, bob_again)["questions"] if q["id"] == "q1")["answer"]
            == "two nodes"
        )
    finally:
        second.stop()
