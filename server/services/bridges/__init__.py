"""Bridges to the tools robotics people already use: Foxglove's WebSocket protocol and rosbridge v2."""
