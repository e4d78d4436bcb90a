from server.msgs.generated.std_srvs import *  # noqa: F403
from server.msgs.generated.std_srvs import __all__ as __all__
