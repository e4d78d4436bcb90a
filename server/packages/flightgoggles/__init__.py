"""The quadrotor's rotor physics as a node (after FlightGoggles' uav_dynamics)."""
