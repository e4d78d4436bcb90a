from server.msgs.generated.keyboard_msgs import *  # noqa: F403
from server.msgs.generated.keyboard_msgs import __all__ as __all__
