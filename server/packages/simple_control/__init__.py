"""The lab's simple_control package: the drone's keyboard manager (the handout's checkpoint 3)."""
