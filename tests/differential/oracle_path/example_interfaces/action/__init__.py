"""example_interfaces.action.Fibonacci, as test_msgs defines it field for field (../README.md)."""

from test_msgs.action import Fibonacci

__all__ = ["Fibonacci"]
