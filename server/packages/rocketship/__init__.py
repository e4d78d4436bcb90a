"""The lab's rocketship package: countdown, main controller, engine, and the keyboard manager."""
