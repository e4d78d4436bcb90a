"""The lab's flightcontroller package: position, velocity and angle controllers as nodes."""
