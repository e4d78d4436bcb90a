"""rclpy's Future: a result that arrives later; ``add_done_callback`` runs once it does."""

from server.bus import Future

__all__ = ["Future"]
