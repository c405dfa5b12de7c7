"""The namespace network itself: drones reach nothing but the swarm network, the gateway reaches each."""

from __future__ import annotations

import socket
import subprocess
import sys
import time

import pytest

from tests.helpers.timing import scaled
from tests.swarm.topology import GATEWAY_ADDRESS, SwarmNetwork, can_create_namespaces, drone_address

pytestmark = pytest.mark.swarm

_possible, _why = can_create_namespaces()


@pytest.mark.skipif(not _possible, reason=f"network namespaces unavailable: {_why}")
def test_gateway_reaches_every_drone_namespace_and_cleanup_is_complete(process_reaper: list) -> None:
    listener = (
        "import socket,sys;s=socket.socket();s.setsockopt(socket.SOL_SOCKET,socket.SO_REUSEADDR,1);"
        "s.bind((sys.argv[1],5760));s.listen();print('up',flush=True);c,a=s.accept();"
        "c.sendall(a[0].encode());c.close()"
    )
    net = SwarmNetwork(drones=2)
    with net:
        names = set(subprocess.run(["ip", "netns", "list"], capture_output=True, text=True).stdout.split())
        assert {net.hub, net.drone_namespace(0), net.drone_namespace(1)} <= names
        for index in range(2):
            proc = subprocess.Popen(
                [*net.exec_prefix(index), sys.executable, "-c", listener, drone_address(index)],
                stdout=subprocess.PIPE,
                text=True,
            )
            process_reaper.append(proc)
            assert proc.stdout is not None and proc.stdout.readline().strip() == "up"
            deadline = time.monotonic() + scaled(10)
            while True:
                try:
                    conn = socket.create_connection((drone_address(index), 5760), timeout=scaled(2))
                    break
                except OSError:
                    if time.monotonic() > deadline:
                        raise
                    time.sleep(0.1)
            with conn:
                # the drone sees the gateway's swarm address, as a drone on a real network would
                assert conn.recv(64).decode() == GATEWAY_ADDRESS
        # a drone namespace has no route to anything but its own network
        route = subprocess.run(
            [*net.exec_prefix(0), "ip", "route", "get", "192.0.2.1"], capture_output=True, text=True
        )
        assert route.returncode != 0
    names = set(subprocess.run(["ip", "netns", "list"], capture_output=True, text=True).stdout.split())
    assert not any(name.startswith(f"fgw{net.tag}") for name in names)
    links = subprocess.run(["ip", "-o", "link"], capture_output=True, text=True).stdout
    assert f"fgw{net.tag}" not in links
