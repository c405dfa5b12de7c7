"""The sidecars the Registry starts run from the loopback-only binary: their gRPC port refuses the host's
other addresses. (test_sidecar_confinement.py proves the binary; this proves the gateway uses it.)"""

from __future__ import annotations

import asyncio
import os
from pathlib import Path

from gateway.config import Settings
from gateway.fleet.vehicles.registry import Registry
from gateway.link import confine
from gateway.registry.spec import VehicleSpec
from gateway.registry.store import Store
from tests.helpers import sim_process
from tests.helpers.timing import scaled
from tests.registry.procs import mavsdk_servers_of
from tests.security.test_sidecar_confinement import _reachable, host_address  # noqa: F401 (fixture)

WAIT_S = scaled(60.0)


async def _serving_port(registry: Registry, vehicle_id: str) -> tuple[int, int]:
    loop = asyncio.get_running_loop()
    deadline = loop.time() + WAIT_S
    while True:
        sidecar = registry.get(vehicle_id).status()["sidecar"]
        if sidecar.get("grpc_port") and sidecar.get("pid"):
            return int(sidecar["grpc_port"]), int(sidecar["pid"])
        if loop.time() > deadline:
            raise AssertionError(f"the sidecar of {vehicle_id} never served: {sidecar}")
        await asyncio.sleep(0.1)


async def test_registry_sidecar_refuses_non_loopback(tmp_path: Path, host_address: str) -> None:  # noqa: F811
    settings = Settings(
        _env_file=None,
        database_url=f"sqlite+aiosqlite:///{tmp_path / 'gateway.db'}",
        sidecar_cache_dir=str(tmp_path / "cache"),
        sidecar_confinement="loopback",  # the default, socket, has no TCP port: test_sidecar_socket.py
    )
    async with sim_process(count=1) as sim:
        store = await Store.open(settings.database_url)
        registry = Registry(settings, store)
        try:
            await registry.start()
            await registry.add(VehicleSpec(id="alpha", url=sim.urls[0], expected_sysid=sim.sysids[0]))
            port, pid = await _serving_port(registry, "alpha")
            started_from = Path(os.readlink(f"/proc/{pid}/exe"))
            assert started_from.parent == tmp_path / "cache", started_from
            assert started_from != confine.bundled_mavsdk_server()
            assert await asyncio.to_thread(_reachable, "127.0.0.1", port)
            reachable_outside = await asyncio.to_thread(_reachable, host_address, port)
            assert not reachable_outside, f"sidecar gRPC port {port} answered on {host_address}"
        finally:
            await registry.stop()
            await store.close()
    assert mavsdk_servers_of() == []


async def test_unconfinable_binary_fails_closed(tmp_path: Path) -> None:
    """A mavsdk_server build the gateway cannot confine is never started as is: the vehicle is failed."""
    fake = tmp_path / "mavsdk_server"
    # an x86-64 ELF header, but not the build whose listen-address code the gateway knows
    fake.write_bytes(b"\x7fELF\x02\x01\x01" + bytes(11) + (62).to_bytes(2, "little") + bytes(64))
    fake.chmod(0o755)
    settings = Settings(
        _env_file=None,
        database_url=f"sqlite+aiosqlite:///{tmp_path / 'gateway.db'}",
        mavsdk_server_path=str(fake),
        sidecar_cache_dir=str(tmp_path / "cache"),
    )
    store = await Store.open(settings.database_url)
    registry = Registry(settings, store)
    try:
        await registry.start()
        await registry.add(VehicleSpec(id="alpha", url="udpin://127.0.0.1:14999"))
        loop = asyncio.get_running_loop()
        deadline = loop.time() + WAIT_S
        while (status := registry.get("alpha").status())["sidecar"]["state"] != "failed":
            assert loop.time() < deadline, status
            await asyncio.sleep(0.05)
        assert "expected gRPC listen-address code" in str(status["last_error"]), status
        assert status["sidecar"]["pid"] is None and mavsdk_servers_of() == []
    finally:
        await registry.stop()
        await store.close()
