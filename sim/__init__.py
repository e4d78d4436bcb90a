"""Pure simulation and control code: numpy and the standard library only, no I/O, no clock."""
