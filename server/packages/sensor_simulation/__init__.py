"""The lab's sensor_simulation package: the barometer (the down-facing camera is not rebuilt)."""
