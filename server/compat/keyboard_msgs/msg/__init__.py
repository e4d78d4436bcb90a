from server.msgs import Key

__all__ = ["Key"]
