from server.bus import RosTime as Time

__all__ = ["Time"]
