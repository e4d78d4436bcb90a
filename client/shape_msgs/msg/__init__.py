from server.msgs.generated.shape_msgs import *  # noqa: F403
from server.msgs.generated.shape_msgs import __all__ as __all__
