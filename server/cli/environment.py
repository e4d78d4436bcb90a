"""What ``ros2lab`` reads from its environment, in a module of its own so the command can read it
before it imports anything heavier (its HTTP client, the verbs' modules)."""

from __future__ import annotations

DEFAULT_URL = "http://127.0.0.1:8000"
URL_ENV = "TELEOP_URL"
TOKEN_ENV = "ROS2LAB_TOKEN"  # a lab behind --token, or a student's world on a class server
