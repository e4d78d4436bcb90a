"""The lab's checkpoints, checked as a student works: declared checks over the lab's events, each
world's progress kept across resets, and the signed report a student hands in (docs/checkpoints.md)."""
