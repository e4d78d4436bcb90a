from server.bus import Future

__all__ = ["Future"]
