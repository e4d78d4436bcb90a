from node_runtime.msgs.generated.geometry_msgs import *  # noqa: F403
from node_runtime.msgs.generated.geometry_msgs import __all__ as __all__
