"""Signed tokens: what they grant, and that a changed, forged or foreign one grants nothing."""

from __future__ import annotations

import base64
import json

import pytest

from server.classroom import TokenSigner
from server.classroom.world import world_name


def test_a_token_carries_its_grant() -> None:
    signer = TokenSigner()
    token, issued = signer.issue("student", "ada", "Ada")
    grant = signer.verify(token)
    assert grant == issued
    assert (grant.role, grant.world, grant.name, grant.is_instructor) == ("student", "ada", "Ada", False)


def test_a_changed_payload_is_refused() -> None:
    signer = TokenSigner()
    token, _ = signer.issue("student", "ada", "Ada")
    payload, signature = token.split(".")
    body = json.loads(base64.urlsafe_b64decode(payload + "=" * (-len(payload) % 4)))
    body.update(r="instructor", w=None)  # a student making themselves the instructor
    forged = base64.urlsafe_b64encode(json.dumps(body).encode()).rstrip(b"=").decode()
    assert signer.verify(f"{forged}.{signature}") is None


def test_another_servers_token_is_refused() -> None:
    token, _ = TokenSigner().issue("instructor", None, "instructor")
    assert TokenSigner().verify(token) is None  # a new secret at every start


@pytest.mark.parametrize("junk", ["", ".", "a.b", "a.b.c", "x" * 600, "ééé.ééé", "e30.e30"])
def test_junk_is_refused_without_an_exception(junk: str) -> None:
    assert TokenSigner().verify(junk) is None


def test_a_signed_payload_of_the_wrong_shape_grants_nothing() -> None:
    signer = TokenSigner(b"k" * 32)
    payload = base64.urlsafe_b64encode(b'{"r":"student","w":null,"n":"x","i":"1"}').rstrip(b"=").decode()
    assert signer.verify(f"{payload}.{signer._sign(payload)}") is None  # a student with no world


@pytest.mark.parametrize(
    ("student", "world"),
    [
        ("Ada Lovelace", "ada_lovelace"),
        ("  bob ", "bob"),
        ("Zoë-2", "zo_2"),
        ("42", "s_42"),
        ("a" * 80, "a" * 32),
    ],
)
def test_world_names_are_ros_namespace_tokens(student: str, world: str) -> None:
    assert world_name(student) == world


@pytest.mark.parametrize("student", ["", "  ", "---", "ééé"])
def test_a_name_with_nothing_usable_is_refused(student: str) -> None:
    with pytest.raises(ValueError, match="at least one letter or digit"):
        world_name(student)
