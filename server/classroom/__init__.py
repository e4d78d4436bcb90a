"""A class on one server: a world per student, signed tokens that scope every call, and the
instructor's controls; on a world worker, the worlds a class server placed there."""

from server.classroom.class_server import ClassServer
from server.classroom.errors import ClassroomError
from server.classroom.roles import Classroom  # the app's classroom, in either role
from server.classroom.tokens import Grant, TokenSigner
from server.classroom.worker_worlds import WorldWorker
from server.classroom.world import World

__all__ = ["ClassServer", "Classroom", "ClassroomError", "Grant", "TokenSigner", "World", "WorldWorker"]
