"""The gateway's process never imports grpcio: its link to mavsdk_server speaks grpclib with
mavsdk_grpc's ``*_pb2`` messages (`gateway.link.mavsdk_system`), and mavsdk_grpc's plugin wrappers,
whose ``*_pb2_grpc`` modules import grpcio, stay unloaded. A fresh interpreter builds the gateway's
app, starts it, registers one drone of the simulator and waits for its session to be ready, reads a
parameter through it, then writes its ``sys.modules``; the test process itself has grpcio loaded
(its helpers import mavsdk_grpc), so the check runs in the child."""

from __future__ import annotations

import asyncio
import json
import sys
from pathlib import Path

from tests.helpers import sim_process
from tests.helpers.timing import scaled

ROOT = Path(__file__).resolve().parents[2]

CHILD = r"""
import asyncio, json, sys

async def main(url, database_url, out, within_s):
    from gateway.app import create_app
    from gateway.config import Settings
    from gateway.registry.spec import VehicleSpec

    app = create_app(Settings(database_url=database_url))
    gateway = app.state.gateway
    await gateway.start()
    try:
        vehicle = await gateway.registry.add(VehicleSpec(id="d1", url=url))
        state = await vehicle.wait_for_state("ready", within_s=within_s)
        value = await vehicle.get_param("SYSID_THISMAV")
    finally:
        await gateway.stop()
    with open(out, "w") as fh:
        json.dump({"state": state.value, "param": list(value), "modules": sorted(sys.modules)}, fh)

asyncio.run(main(sys.argv[1], sys.argv[2], sys.argv[3], float(sys.argv[4])))
"""


async def test_a_gateway_with_a_drone_session_has_no_grpcio_loaded(tmp_path: Path) -> None:
    out = tmp_path / "modules.json"
    database_url = f"sqlite+aiosqlite:///{tmp_path / 'fleet.db'}"
    async with sim_process(1, speedup=5.0) as sim:
        child = await asyncio.create_subprocess_exec(
            sys.executable, "-c", CHILD, sim.urls[0], database_url, str(out), str(scaled(90)),
            cwd=tmp_path, env={"PATH": "/usr/bin:/bin", "PYTHONPATH": str(ROOT)},
            stdout=asyncio.subprocess.DEVNULL, stderr=asyncio.subprocess.PIPE,
        )  # fmt: skip
        try:
            _, stderr = await asyncio.wait_for(child.communicate(), scaled(180))
        finally:
            if child.returncode is None:
                child.kill()
                await child.wait()
    assert child.returncode == 0, stderr.decode(errors="replace")[-3000:]
    report = json.loads(out.read_text())
    assert report["state"] == "ready" and report["param"] == [1, "int"]
    modules = report["modules"]
    assert "grpclib.client" in modules and "mavsdk_grpc.telemetry_pb2" in modules  # the link ran
    assert [m for m in modules if m == "grpc" or m.startswith("grpc.")] == [], "the gateway imported grpcio"
    wrappers = [m for m in modules if m.startswith("mavsdk_grpc.") and not m.endswith("_pb2")]
    assert wrappers in ([], ["mavsdk_grpc.bin"]), "the gateway imported mavsdk_grpc's plugin wrappers"
