from node_runtime.msgs.generated.type_description_interfaces import *  # noqa: F403
from node_runtime.msgs.generated.type_description_interfaces import __all__ as __all__
