from server.msgs import Time

__all__ = ["Time"]
