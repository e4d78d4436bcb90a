from node_runtime.msgs.generated.shape_msgs import *  # noqa: F403
from node_runtime.msgs.generated.shape_msgs import __all__ as __all__
