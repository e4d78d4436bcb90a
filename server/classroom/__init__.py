"""A class on one server: a world per student, signed tokens that scope every call, and the
instructor's controls."""

from .classroom import Classroom, World
from .errors import ClassroomError
from .tokens import Grant, TokenSigner

__all__ = ["Classroom", "ClassroomError", "Grant", "TokenSigner", "World"]
