from server.bus import Node, Parameter

__all__ = ["Node", "Parameter"]
