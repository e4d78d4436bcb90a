"""The class secret (``--class-secret-file``): a class server given one signs with it, so the
instructor's token is the same at every start and a world worker derives it from the same file;
a student's token outlives a restart, and a removed world's token still grants nothing after
one. A file that cannot be a secret is refused, naming why, before anything starts."""

from __future__ import annotations

import os
import secrets
from pathlib import Path

import pytest
from support.app import App, instructor_token
from support.http import HTTP

from server.__main__ import main as server_main
from server.classroom.grants import Grants
from server.classroom.tokens import (
    MIN_SECRET_BYTES,
    ClassSecretError,
    TokenSigner,
    read_class_secret,
)
from server.classroom.tokens import instructor_token as derived_instructor_token
from server.classroom.worker_control import TOKEN_ENV
from server.world_worker import main as worker_main

CODE = "SECRET42"


def secret_file(path: Path, text: str | None = None) -> Path:
    path.write_text(secrets.token_hex(32) + "\n" if text is None else text)
    return path


# -- the secret and the tokens ---------------------------------------------------------------------
def test_the_same_secret_gives_the_same_instructors_token_to_every_signer_and_grants(tmp_path: Path) -> None:
    path = secret_file(tmp_path / "class-secret", "  " + "ab" * 32 + "\n\n")
    secret = read_class_secret(path)
    assert secret == b"ab" * 32  # surrounding whitespace is not the secret
    first, second = Grants(TokenSigner(read_class_secret(path))), Grants(TokenSigner(read_class_secret(path)))
    assert first.instructor_token == second.instructor_token == derived_instructor_token(secret)
    assert first.instructor.token_id == second.instructor.token_id
    # Each verifies the other's tokens: a student's too.
    token, grant = first.issue("ada", "Ada")
    assert second.signer.verify(token) == grant
    grant_of_instructor = second.check(first.instructor_token, {})
    assert grant_of_instructor is not None and grant_of_instructor.is_instructor
    # Another secret: another instructor's token, and none of the first class's tokens verify.
    other = Grants(TokenSigner(read_class_secret(secret_file(tmp_path / "other"))))
    assert other.instructor_token != first.instructor_token
    assert other.check(first.instructor_token, {}) is None and other.signer.verify(token) is None


def test_without_a_secret_every_start_has_a_token_of_its_own() -> None:
    assert Grants().instructor_token != Grants().instructor_token
    assert Grants().check(Grants().instructor_token, {}) is None


def test_a_kept_token_is_kept_only_when_genuine_for_that_world_and_not_revoked() -> None:
    grants = Grants(TokenSigner(b"s" * MIN_SECRET_BYTES))
    token, grant = grants.issue("ada", "Ada")
    assert grants.issue("ada", "Ada", kept=token) == (token, grant)
    for kept in (grants.instructor_token, grants.issue("bob", "Bob")[0], token + "x", "junk"):
        again, new = grants.issue("ada", "Ada", kept=kept)
        assert again != kept and new.world == "ada" and new.token_id != grant.token_id
    elsewhere, _ = Grants(TokenSigner(b"t" * MIN_SECRET_BYTES)).issue("ada", "Ada")
    assert grants.issue("ada", "Ada", kept=elsewhere)[0] != elsewhere

    class Removed:
        token_id = grant.token_id

    grants.revoke(Removed())  # type: ignore[arg-type]  # a World's token_id is all revoke reads
    assert grants.issue("ada", "Ada", kept=token)[0] != token


@pytest.mark.parametrize(
    ("make", "why"),
    [
        (lambda p: None, "does not exist: make one with openssl rand -hex 32"),
        (lambda p: p.mkdir(), "is not a regular file"),
        (lambda p: os.mkfifo(p), "is not a regular file"),
        (
            lambda p: p.write_text("x" * (MIN_SECRET_BYTES - 1) + "\n"),
            "holds 31 bytes of secret, fewer than 32",
        ),
        (lambda p: p.write_text(" \n\t\n"), "holds 0 bytes of secret, fewer than 32: make one with"),
        (lambda p: p.write_bytes(b"x" * 5000), "is larger than 4096 bytes"),
    ],
)
def test_a_file_that_is_no_secret_is_refused_naming_why(tmp_path: Path, make: object, why: str) -> None:
    path = tmp_path / "class-secret"
    make(path)  # type: ignore[operator]
    with pytest.raises(ClassSecretError) as refused:
        read_class_secret(path)
    message = str(refused.value)
    assert f"the class secret file {path} {why}" in message and "\n" not in message, message


def test_the_class_server_refuses_a_bad_secret_file_in_one_line_and_starts_nothing(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    monkeypatch.chdir(tmp_path)
    short = secret_file(tmp_path / "short", "too short\n")
    before = sorted(tmp_path.iterdir())
    code = server_main(["--classroom", "--launch", "rocket", "--class-secret-file", str(short)])
    err = capsys.readouterr().err
    assert code == 2
    assert err.strip().splitlines() == [
        f"error: the class secret file {short} holds 9 bytes of secret, fewer than 32: make one with "
        'openssl rand -hex 32 > FILE, or python -c "import secrets; print(secrets.token_hex(32))" > FILE'
    ]
    assert sorted(tmp_path.iterdir()) == before  # no state, no workspaces: nothing started
    # Without --classroom there is no class for it.
    with pytest.raises(SystemExit) as usage:
        server_main(["--class-secret-file", str(short)])
    assert usage.value.code == 2 and "--class-secret-file needs --classroom" in capsys.readouterr().err


def test_a_world_worker_takes_exactly_one_of_the_token_and_the_secret_file(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    connect = ["--connect", "tcp/127.0.0.1:9"]  # never reached: each is refused before
    good = secret_file(tmp_path / "class-secret")
    monkeypatch.delenv(TOKEN_ENV, raising=False)
    assert worker_main(connect) == 2
    assert f"set {TOKEN_ENV} to the instructor's token" in capsys.readouterr().err
    monkeypatch.setenv(TOKEN_ENV, "a-token")
    assert worker_main([*connect, "--class-secret-file", str(good)]) == 2
    assert f"both {TOKEN_ENV} and --class-secret-file are given: use one" in capsys.readouterr().err
    monkeypatch.delenv(TOKEN_ENV)
    missing = tmp_path / "missing"
    assert worker_main([*connect, "--class-secret-file", str(missing)]) == 2
    assert capsys.readouterr().err.startswith(f"error: the class secret file {missing} does not exist")


# -- a real class server, started twice with one secret --------------------------------------------
def test_a_restart_keeps_the_instructors_and_a_students_token_and_a_removed_worlds_stays_dead(
    tmp_path: Path,
) -> None:
    path = secret_file(tmp_path / "class-secret")
    args = ("--classroom", "--class-code", CODE, "--launch", "rocket", "--no-foxglove", "--workers", "0",
            "--class-secret-file", str(path), "--state-dir", str(tmp_path / "state"),
            "--workspaces-dir", str(tmp_path / "workspaces"))  # fmt: skip

    def start(run: str) -> App:
        (tmp_path / run).mkdir()
        return App(tmp_path / run, *args)

    def me(app: App, token: str) -> int:
        return HTTP.get(
            f"{app.url}/api/classroom/me", headers={"Authorization": f"Bearer {token}"}, timeout=10
        ).status_code

    def join(app: App, name: str, token: str | None = None) -> str:
        headers = {"Authorization": f"Bearer {token}"} if token else {}
        joined = HTTP.post(f"{app.url}/api/classroom/join", json={"name": name, "code": CODE}, headers=headers,
                           timeout=60)  # fmt: skip
        assert joined.status_code == 201, joined.text
        return str(joined.json()["token"])

    app = start("first")
    try:
        instructor = instructor_token(app.log_tail(10**6))
        assert instructor == derived_instructor_token(read_class_secret(path))
        ada, bob = join(app, "Ada"), join(app, "Bob")
        removed = HTTP.delete(f"{app.url}/api/classroom/worlds/bob", timeout=30,
                              headers={"Authorization": f"Bearer {instructor}"})  # fmt: skip
        assert removed.status_code == 200, removed.text
        assert (me(app, ada), me(app, bob), me(app, instructor)) == (200, 401, 200)
    finally:
        app.stop()

    app = start("second")
    try:
        assert instructor_token(app.log_tail(10**6)) == instructor  # the same link, the same login
        assert me(app, instructor) == 200
        assert me(app, ada) == 401  # genuine, but Ada has no world in this run yet
        assert me(app, bob) == 401
        # Ada joins again from her browser (its cookie, or a bearer): her token is hers again.
        assert join(app, "Ada", ada) == ada
        assert me(app, ada) == 200
        # Bob's world was removed: his old token, shown at a join, is not kept, and grants nothing.
        bob_again = join(app, "Bob", bob)
        assert bob_again != bob
        assert (me(app, bob), me(app, bob_again)) == (401, 200)
    finally:
        app.stop()
