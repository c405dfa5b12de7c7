"""A compose-like network built from Linux network namespaces (Docker has no engine here).

Layout, mirroring deploy/docker-compose.yml:

    root namespace (the gateway) --veth-- [hub namespace: bridge] --veth-- drone-0 namespace
                                                                  --veth-- drone-1 namespace ...

Every address lives inside namespaces this module creates; the root namespace only gains one
veth end with the gateway's address. ``close()`` removes all of it, also after a failure.
"""

from __future__ import annotations

import fcntl
import os
import subprocess
import time
from dataclasses import dataclass, field

from tests.helpers.timing import scaled

SUBNET_PREFIX = "10.201.0"
GATEWAY_ADDRESS = f"{SUBNET_PREFIX}.2"
PREFIX_LEN = 24
SUBNET = f"{SUBNET_PREFIX}.0/{PREFIX_LEN}"

# --- the swarm, as deploy/docker-compose.yml runs it (tests/test_compose.py checks the file against this) --
DRONES = 5
DRONE_TCP_PORT = 5760
GATEWAY_PORT = 8765
HOME_LAT, HOME_LON, HOME_ALT_AMSL, HOME_HEADING = -35.363262, 149.165237, 584.0, 0.0
HOME_SPACING_M = 10.0
"""Drone i's home is i * HOME_SPACING_M east of drone 0's: each drone runs its own simulator process,
whose vehicle 0 sits at --home, so the homes are spread here, apart by more than the minimum separation."""


def drone_address(index: int) -> str:
    """Address of drone ``index`` (0-based) on the swarm network, as in docker-compose.yml."""
    return f"{SUBNET_PREFIX}.{10 + index}"


def drone_id(index: int) -> str:
    return f"drone-{index + 1}"


def drone_sysid(index: int) -> int:
    return index + 1


def drone_url(index: int) -> str:
    """How the gateway reaches drone ``index``: TCP to its address, as ArduPilot SITL listens."""
    return f"tcpout://{drone_address(index)}:{DRONE_TCP_PORT}"


def drone_home(index: int) -> str:
    """``--home`` of drone ``index``: LAT,LON,ALT_AMSL,HEADING (7 decimals: about a centimetre)."""
    from gateway.fleet import geo

    lat, lon = geo.offset_position(HOME_LAT, HOME_LON, 0.0, index * HOME_SPACING_M)
    return f"{lat:.7f},{lon:.7f},{HOME_ALT_AMSL:g},{HOME_HEADING:g}"


def drone_command(index: int, speedup: float = 1.0) -> list[str]:
    """The simulator command of drone ``index``, run inside its own namespace / container."""
    return [
        "fleet-gateway", "sim", "--count", "1",
        "--bind", drone_address(index), "--tcp-base-port", str(DRONE_TCP_PORT),
        "--sysid-base", str(drone_sysid(index)), f"--home={drone_home(index)}",
        "--seed", str(index + 1), "--speedup", f"{speedup:g}",
    ]  # fmt: skip


GATEWAY_ENV = {"GATEWAY_SIMULATORS_ONLY": "true"}
"""Gateway settings the compose file and the swarm test share (agents may fly simulators only)."""


def gateway_command(host: str = "0.0.0.0", port: int = GATEWAY_PORT) -> list[str]:
    return ["fleet-gateway", "serve", "--host", host, "--port", str(port)]


REGISTER_WAIT_S = 180
"""How long a registrar waits for the gateway's /readyz: compose engines that ignore ``depends_on:
condition: service_healthy`` (podman-compose) start it beside a gateway that is still starting."""


def register_command(index: int, api: str) -> list[str]:
    """Registers drone ``index`` with a gateway, once it is ready (the compose file's one-shot registrar)."""
    return [
        "fleet-gateway", "drones", "add", drone_id(index), drone_url(index),
        "--sysid", str(drone_sysid(index)), "--name", f"Drone {index + 1}", "--tag", "swarm",
        "--if-missing", "--api", api, "--wait", str(REGISTER_WAIT_S),
    ]  # fmt: skip


def can_create_namespaces() -> tuple[bool, str]:
    if os.geteuid() != 0:
        return False, "creating network namespaces needs root"
    probe = f"fgwprobe{os.getpid()}"
    result = subprocess.run(["ip", "netns", "add", probe], capture_output=True, text=True, check=False)
    if result.returncode != 0:
        return False, f"'ip netns add' failed: {result.stderr.strip()}"
    subprocess.run(["ip", "netns", "del", probe], check=False)
    return True, ""


def _ip(*args: str, netns: str | None = None) -> None:
    cmd = ["ip", *(("-n", netns) if netns else ()), *args]
    result = subprocess.run(cmd, capture_output=True, text=True, check=False)
    if result.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)} failed: {result.stderr.strip()}")


LOCK_PATH = (
    "/run/lock/fleet-gateway-swarm.lock" if os.path.isdir("/run/lock") else "/tmp/fleet-gateway-swarm.lock"
)


def _acquire_lock(timeout_s: float) -> int:
    fd = os.open(LOCK_PATH, os.O_RDWR | os.O_CREAT, 0o600)
    deadline = time.monotonic() + scaled(timeout_s)
    while True:
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            return fd
        except BlockingIOError:
            if time.monotonic() > deadline:
                os.close(fd)
                held = f"{scaled(timeout_s):.0f} s"
                raise TimeoutError(f"another swarm network held {LOCK_PATH} for {held}") from None
            time.sleep(0.2)


@dataclass
class SwarmNetwork:
    """``drones`` namespaces on one bridge, reachable from the root namespace at GATEWAY_ADDRESS."""

    drones: int
    tag: str = field(default_factory=lambda: f"{os.getpid() % 100000:05d}")
    namespaces: list[str] = field(default_factory=list)
    _root_veth: str | None = None
    _lock_fd: int | None = None

    @property
    def hub(self) -> str:
        return f"fgw{self.tag}hub"

    def drone_namespace(self, index: int) -> str:
        return f"fgw{self.tag}d{index}"

    def exec_prefix(self, index: int) -> list[str]:
        """Command prefix that runs a program inside drone ``index``'s namespace."""
        return ["ip", "netns", "exec", self.drone_namespace(index)]

    def open(self, lock_timeout_s: float = 600.0) -> SwarmNetwork:
        """Build the network. Its addresses are fixed (as in compose), so only one swarm network may
        exist on this machine at a time: wait for an exclusive lock held until ``close()``, so that
        parallel test workers or two test runs on one machine take turns instead of clashing."""
        self._lock_fd = _acquire_lock(lock_timeout_s)
        try:
            self._build()
        except BaseException:
            self.close()
            raise
        return self

    def _build(self) -> None:
        _ip("netns", "add", self.hub)
        self.namespaces.append(self.hub)
        _ip("link", "add", "br0", "type", "bridge", netns=self.hub)
        _ip("link", "set", "br0", "up", netns=self.hub)
        _ip("link", "set", "lo", "up", netns=self.hub)
        # gateway side: one veth end stays in the root namespace
        self._root_veth = f"fgw{self.tag}gw"
        self._attach(self._root_veth, None, GATEWAY_ADDRESS)
        for index in range(self.drones):
            namespace = self.drone_namespace(index)
            _ip("netns", "add", namespace)
            self.namespaces.append(namespace)
            _ip("link", "set", "lo", "up", netns=namespace)
            self._attach(f"fgw{self.tag}v{index}", namespace, drone_address(index))

    def _attach(self, name: str, namespace: str | None, address: str) -> None:
        """A veth pair: ``name`` (in ``namespace``, or root) <-> ``name``p enslaved to the hub bridge."""
        peer = f"{name}p"
        _ip("link", "add", name, "type", "veth", "peer", "name", peer)
        _ip("link", "set", peer, "netns", self.hub)
        _ip("link", "set", peer, "master", "br0", netns=self.hub)
        _ip("link", "set", peer, "up", netns=self.hub)
        if namespace:
            _ip("link", "set", name, "netns", namespace)
        _ip("addr", "add", f"{address}/{PREFIX_LEN}", "dev", name, netns=namespace)
        _ip("link", "set", name, "up", netns=namespace)

    def close(self) -> None:
        if self._root_veth:
            subprocess.run(["ip", "link", "del", self._root_veth], capture_output=True, check=False)
            self._root_veth = None
        for namespace in reversed(self.namespaces):
            subprocess.run(["ip", "netns", "del", namespace], capture_output=True, check=False)
        self.namespaces.clear()
        if self._lock_fd is not None:
            os.close(self._lock_fd)  # releases the flock
            self._lock_fd = None

    def __enter__(self) -> SwarmNetwork:
        return self.open()

    def __exit__(self, *exc: object) -> None:
        self.close()
