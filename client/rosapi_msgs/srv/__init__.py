from node_runtime.msgs.generated.rosapi_msgs import *  # noqa: F403
from node_runtime.msgs.generated.rosapi_msgs import __all__ as __all__
