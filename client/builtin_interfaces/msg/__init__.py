from node_runtime.msgs.generated.builtin_interfaces import *  # noqa: F403
from node_runtime.msgs.generated.builtin_interfaces import __all__ as __all__
