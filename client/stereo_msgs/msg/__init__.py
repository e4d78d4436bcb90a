from server.msgs.generated.stereo_msgs import *  # noqa: F403
from server.msgs.generated.stereo_msgs import __all__ as __all__
