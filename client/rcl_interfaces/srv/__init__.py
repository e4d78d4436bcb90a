from server.msgs.generated.rcl_interfaces import *  # noqa: F403
from server.msgs.generated.rcl_interfaces import __all__ as __all__
