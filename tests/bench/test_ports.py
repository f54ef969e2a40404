"""The tests' and load tools' servers get ports the kernel never gives an outgoing connection."""

from __future__ import annotations

import socket

from app.bench.ports import LOWEST_PORT, _ephemeral_low, free_loopback_port


def test_a_free_port_lies_below_the_ephemeral_range_and_can_be_bound():
    low = _ephemeral_low()
    ports = {free_loopback_port() for _ in range(20)}
    assert all(LOWEST_PORT <= port < low for port in ports), (ports, low)
    assert len(ports) > 10  # chosen at random, not the same one each time
    with socket.socket() as server:
        server.bind(("127.0.0.1", ports.pop()))


def test_a_port_something_listens_on_is_not_given():
    with socket.socket() as taken:
        taken.bind(("127.0.0.1", free_loopback_port()))
        taken.listen()
        busy = taken.getsockname()[1]
        assert all(free_loopback_port() != busy for _ in range(200))
