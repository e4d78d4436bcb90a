"""A class on one server: a world per student, signed tokens that scope every call, and the
instructor's controls; on a world worker, the worlds a class server placed there."""

from .class_server import ClassServer
from .errors import ClassroomError
from .tokens import Grant, TokenSigner
from .worker_worlds import WorldWorker
from .world import World

Classroom = ClassServer | WorldWorker  # the app's classroom, in either role

__all__ = ["ClassServer", "Classroom", "ClassroomError", "Grant", "TokenSigner", "World", "WorldWorker"]
