from node_runtime.msgs.generated.rcl_interfaces import *  # noqa: F403
from node_runtime.msgs.generated.rcl_interfaces import __all__ as __all__
