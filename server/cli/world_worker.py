"""``ros2lab world-worker``: not a client verb. This process hosts worlds for a class server
itself (server/world_worker.py), so it is the one verb besides ``run`` that imports the server."""

from __future__ import annotations


def main(argv: list[str]) -> int:
    from server.world_worker import main as worker_main

    return worker_main(argv)
