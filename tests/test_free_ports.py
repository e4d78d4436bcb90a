"""The tests' loopback ports: a port handed out lately is not handed out again, though it is free
again as soon as the picker lets it go (a test that picked its bridges' ports, then started an App
that picked its own, once got one port twice: "address already in use")."""

from __future__ import annotations

import socket

from support.app import free_ports


def test_five_hundred_picks_in_a_row_are_all_different_and_all_free() -> None:
    # From the ports between 20000 and the ephemeral range (12,768 on Linux's default; an xdist
    # worker has a slice of them), 500 independent picks repeat one about ten times or more (the
    # birthday bound); none may.
    picked = [port for _ in range(250) for port in free_ports(2)]
    assert len(set(picked)) == len(picked) == 500
    for port in picked[-5:]:  # each is free: a server could bind it now
        with socket.socket() as sock:
            sock.bind(("127.0.0.1", port))
