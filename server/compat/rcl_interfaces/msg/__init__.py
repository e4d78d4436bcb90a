from server.msgs import Log

__all__ = ["Log"]
