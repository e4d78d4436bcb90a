from server.msgs.generated.turtlesim import *  # noqa: F403
from server.msgs.generated.turtlesim import __all__ as __all__
