from node_runtime.msgs.generated.action_tutorials_interfaces import *  # noqa: F403
from node_runtime.msgs.generated.action_tutorials_interfaces import __all__ as __all__
