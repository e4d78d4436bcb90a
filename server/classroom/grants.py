"""Who may do what: the instructor's grant, a student's grant to their own world, and revocation.

Every call carries a signed token (tokens.py). A student's token grants their world while that
world is still theirs: a removed world's token is revoked, and a world of the same name made
later has a token of its own. The instructor's grant reaches every world, but a call must name
the world it acts on.

With a class secret, tokens outlive a restart of the class server, but the revoked ones are not
kept: none needs to be. A student's token grants only a world of this run whose token it is, and
a join keeps the token it presents only when the world's owner record proves it the student's
(saved_students.py); removing a world removes that record with its progress and code, so a
removed world's token never grants again.
"""

from __future__ import annotations

from collections.abc import Mapping

from server.classroom.errors import NotYoursError, UnknownWorldError, WorldNotNamedError
from server.classroom.tokens import Grant, TokenSigner
from server.classroom.world import World


class Grants:
    """The tokens ``signer`` issues, the instructor's among them, and those revoked since."""

    def __init__(self, signer: TokenSigner | None = None) -> None:
        self.signer = signer or TokenSigner()
        self.instructor_token, self.instructor = self.signer.issue_instructor()
        self._revoked: set[str] = set()

    def issue(self, world: str, student: str, kept: str | None = None) -> tuple[str, Grant]:
        """A student's token for ``world``, and its grant: ``kept`` itself when it is a genuine
        token for ``world`` that is not revoked (a token its join proved its student's, by the
        world's owner record: after a restart of a class server with a class secret, the token
        their pages hold works again), else a new one."""
        if kept is not None:
            grant = self.signer.verify(kept)
            if (
                grant is not None
                and not grant.is_instructor
                and grant.world == world
                and grant.token_id not in self._revoked
            ):
                return kept, grant
        return self.signer.issue("student", world, student)

    def revoke(self, world: World) -> None:
        """``world``'s token grants nothing from now on."""
        self._revoked.add(world.token_id)

    def check(self, token: str, worlds: Mapping[str, World]) -> Grant | None:
        """The grant of a genuine, current token: a student's world must still be theirs."""
        grant = self.signer.verify(token)
        if grant is None or grant.token_id in self._revoked:
            return None
        if grant.is_instructor:
            return grant
        world = worlds.get(grant.world or "")
        return grant if world is not None and world.token_id == grant.token_id else None


def world_for(grant: Grant, asked: str | None, worlds: Mapping[str, World]) -> World:
    """The world a call acts on: a student's own (naming another is NotYoursError); the
    instructor's must be named."""
    if grant.is_instructor:
        if asked is None:
            raise WorldNotNamedError("name a world (the X-Lab-World header or ?world=)")
        name = asked
    elif asked is not None and asked != grant.world:
        raise NotYoursError(f"your token is for world {grant.world!r}, not {asked!r}")
    else:
        name = grant.world or ""
    world = worlds.get(name)
    if world is None:
        raise UnknownWorldError(f"no world named {name!r}")
    return world
