from node_runtime.msgs.generated.std_srvs import *  # noqa: F403
from node_runtime.msgs.generated.std_srvs import __all__ as __all__
