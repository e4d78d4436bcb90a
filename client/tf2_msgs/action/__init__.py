from server.msgs.generated.tf2_msgs import *  # noqa: F403
from server.msgs.generated.tf2_msgs import __all__ as __all__
