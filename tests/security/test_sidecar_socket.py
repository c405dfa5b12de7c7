"""A sidecar answers the gateway alone (``GATEWAY_SIDECAR_CONFINEMENT=socket``, the default): it serves gRPC
on a unix socket in a private directory, not on any TCP port; once the gateway is connected the socket's
path is gone, so another local process (``mavsdk_grpc.System``, a raw connect) is refused; a process of
another user cannot reach the socket even before; and a process that connected before the gateway sealed
it is found and the sidecar restarted. Agents are never told the sidecar's port or process."""

from __future__ import annotations

import asyncio
import os
import shutil
import socket
import subprocess
import sys
from pathlib import Path

import pytest

from gateway.config import Settings
from gateway.fleet.vehicles.registry import Registry
from gateway.link import confine
from gateway.link.proc_sockets import TCP_LISTEN, proc_net_rows, socket_inodes
from gateway.link.sidecar import Sidecar, SidecarState
from gateway.mcp.resources import state_json
from gateway.registry.spec import VehicleSpec
from gateway.registry.store import Store
from gateway.util.ports import free_udp_port
from tests.fakes import fake_gateway, spread, unit_settings
from tests.helpers import sim_process
from tests.helpers.timing import scaled
from tests.registry.heartbeat import HeartbeatVehicle
from tests.registry.procs import mavsdk_servers_of

WAIT_S = scaled(60.0)

#: another local process tries the sidecar as a client would: MAVSDK's System on the socket's address
_MAVSDK_CLIENT = """
import asyncio, sys
from mavsdk_grpc import System
async def main():
    system = System(mavsdk_server_address=sys.argv[1], port=int(sys.argv[2]))
    try:
        await asyncio.wait_for(system.connect(), float(sys.argv[3]))
    except Exception as exc:
        print("refused", type(exc).__name__)
        return
    print("CONNECTED")
asyncio.run(main())
"""

#: a raw connect to a unix socket's path: "connected", or the error's name
_RAW_CONNECT = """
import socket, sys
s = socket.socket(socket.AF_UNIX)
try:
    s.connect(sys.argv[1])
except OSError as exc:
    print("refused", type(exc).__name__)
else:
    print("CONNECTED")
"""


def _settings(tmp_path: Path, **kw: object) -> Settings:
    return Settings(  # type: ignore[call-arg]
        _env_file=None,
        database_url=f"sqlite+aiosqlite:///{tmp_path / 'gateway.db'}",
        sidecar_cache_dir=str(tmp_path / "cache"),
        **kw,
    )


def _exists(path: str) -> bool:
    return Path(path).exists()


def _tcp_listeners_of(pid: int) -> list[int]:
    ours = socket_inodes(pid)
    return [row.port for row in proc_net_rows("tcp") if row.state == TCP_LISTEN and row.inode in ours]


async def _another_process(*argv: str) -> str:
    proc = await asyncio.create_subprocess_exec(
        *argv, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, start_new_session=True
    )
    try:
        out, _ = await asyncio.wait_for(proc.communicate(), WAIT_S)
    finally:
        if proc.returncode is None:
            proc.kill()
            await proc.wait()
    return out.decode(errors="replace")


async def _serving(registry: Registry, vehicle_id: str) -> Sidecar:
    loop = asyncio.get_running_loop()
    deadline = loop.time() + WAIT_S
    vehicle = registry.get(vehicle_id)
    while True:
        car = vehicle.sidecar
        if car is not None and car.state == SidecarState.SERVING and vehicle.status()["state"] == "ready":
            return car
        if loop.time() > deadline:
            raise AssertionError(f"{vehicle_id} never got ready: {vehicle.status()}")
        await asyncio.sleep(0.1)


async def test_a_running_sidecar_refuses_every_local_process_but_the_gateway(tmp_path: Path) -> None:
    settings = _settings(tmp_path)
    assert settings.sidecar_confinement == "socket"  # the default
    async with sim_process(count=1) as sim:
        store = await Store.open(settings.database_url)
        registry = Registry(settings, store)
        try:
            await registry.start()
            await registry.add(VehicleSpec(id="alpha", url=sim.urls[0], expected_sysid=sim.sysids[0]))
            car = await _serving(registry, "alpha")
            pid, port = car.pid, car.grpc_port
            assert pid is not None and port is not None
            started_from = Path(os.readlink(f"/proc/{pid}/exe"))
            assert started_from.parent == tmp_path / "cache", started_from
            assert confine.is_confined(await asyncio.to_thread(started_from.read_bytes), "socket")
            assert _tcp_listeners_of(pid) == [], "the sidecar listens on a TCP port"
            address = car.grpc_address
            socket_path = address.removeprefix("unix:") + f":{port}"
            assert not _exists(socket_path) and not _exists(os.path.dirname(socket_path))

            # another local process, as a MAVSDK client and as a raw connect: refused
            client = (sys.executable, "-c", _MAVSDK_CLIENT)
            for host in (address, "127.0.0.1"):
                said = await _another_process(*client, host, str(port), "3")
                assert said.startswith("refused"), (host, said)
            said = await _another_process(sys.executable, "-c", _RAW_CONNECT, socket_path)
            assert said.startswith("refused"), said

            # the gateway's own session still works through its one connection
            vehicle = registry.get("alpha")
            assert vehicle.telemetry.fresh("position") is not None
            assert car.pid == pid and car.info.restarts == 0
        finally:
            await registry.stop()
            await store.close()
    assert mavsdk_servers_of() == []


def _as_another_user() -> list[str]:
    """The command prefix that runs a process as ``nobody``; skips when this process cannot."""
    setpriv = shutil.which("setpriv")
    if os.geteuid() != 0 or setpriv is None:
        pytest.skip("running a process as another user needs root and setpriv (util-linux)")
    return [setpriv, "--reuid=65534", "--regid=65534", "--clear-groups", "--"]


async def test_another_user_cannot_reach_the_socket_and_an_early_intruder_restarts_the_sidecar(
    tmp_path: Path,
) -> None:
    """Before the gateway seals it the socket is in a directory only the gateway's user may enter:
    another user is refused. A process of the gateway's own user that connected in that moment is found
    when the gateway seals the socket: the sidecar is restarted (on a new socket) and says why."""
    other_user = _as_another_user()
    udp = free_udp_port()
    car = Sidecar("intruded", f"udpin://127.0.0.1:{udp}", _settings(tmp_path))
    try:
        async with HeartbeatVehicle(udp, sysid=6):
            car.start()
            assert await car.wait_serving(WAIT_S), car.status()
            port, first_pid, directory = car.grpc_port, car.pid, car.info.socket_dir
            assert port is not None and directory is not None
            assert directory.stat().st_mode & 0o777 == 0o700
            socket_path = str(directory / confine.SOCKET_NAME.format(port=port))
            said = await _another_process(*other_user, sys.executable, "-c", _RAW_CONNECT, socket_path)
            assert said.strip() == "refused PermissionError", said

            with socket.socket(socket.AF_UNIX) as intruder:  # the gateway's user, before the seal
                intruder.connect(socket_path)
                with socket.socket(socket.AF_UNIX) as gateway_side:  # stands for the gateway's channel
                    gateway_side.connect(socket_path)
                    wrong = car.seal()
                assert wrong is not None and "holds 2 connections" in wrong, wrong
                assert not _exists(socket_path)
            loop = asyncio.get_running_loop()
            deadline = loop.time() + WAIT_S
            while not (car.state == SidecarState.SERVING and car.pid not in (None, first_pid)):
                assert loop.time() < deadline, car.status()
                await asyncio.sleep(0.05)
            assert car.grpc_port != port
    finally:
        await car.stop()
    assert mavsdk_servers_of() == []


async def test_agents_are_never_told_the_sidecars_port_or_process(tmp_path: Path) -> None:
    async with fake_gateway(unit_settings(tmp_path), spread(1)) as gateway:
        state = state_json(gateway.commander, "d1")
        sidecar = state["status"]["sidecar"]
        assert "pid" not in sidecar and "grpc_port" not in sidecar, sidecar
        assert sidecar["state"] == "stopped"
