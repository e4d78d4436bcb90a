from node_runtime.msgs.generated.stereo_msgs import *  # noqa: F403
from node_runtime.msgs.generated.stereo_msgs import __all__ as __all__
