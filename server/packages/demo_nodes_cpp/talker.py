"""talker as demo_nodes_cpp's: counting from 1, each line in single quotes, a history of 7."""

from __future__ import annotations

from server.packages.demo_nodes_py.talker import Talker as PyTalker


class Talker(PyTalker):
    FIRST = 1
    LINE = "Publishing: '{}'"
    DEPTH = 7
