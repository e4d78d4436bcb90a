from node_runtime.msgs.generated.turtlesim import *  # noqa: F403
from node_runtime.msgs.generated.turtlesim import __all__ as __all__
