"""The Fall 2025 lab's kinematic simulator."""
