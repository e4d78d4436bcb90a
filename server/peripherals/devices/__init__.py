"""Devices the app attaches to the bus: the browser keyboard, the 3D display."""
