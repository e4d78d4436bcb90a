class ExternalShutdownException(Exception):
    """Raised by rclpy when the context shuts down from outside; here the app stops nodes itself."""
