from server.bus import Parameter

__all__ = ["Parameter"]
