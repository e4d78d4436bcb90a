from server.msgs.generated.action_tutorials_interfaces import *  # noqa: F403
from server.msgs.generated.action_tutorials_interfaces import __all__ as __all__
