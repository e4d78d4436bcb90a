"""The combined launch of this project: both halves of Lab 2 in one graph."""
