"""CLI contract, bad input, UDP output, the demo command, and in-process units of the simulator."""

from __future__ import annotations

import asyncio
import os
import signal
import subprocess
import sys

import httpx
import pytest

from gateway.sim import SimFleet
from gateway.sim.control import ControlServer, SimControl
from gateway.sim.fleet import parse_home
from gateway.sim.params import ParamError, ParamTable
from gateway.util.ports import free_udp_port
from tests.helpers import mavsdk_system, sim_process
from tests.helpers.timing import scaled
from tests.sim.flying import SPEEDUP, set_rates, wait_for


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["--count", "0"], "count must be at least 1"),
        (["--speedup", "-2"], "must be a positive number"),
        (["--home", "1,2,3"], "LAT,LON,ALT_AMSL,HEADING"),
        (["--home", "95,2,3,4"], "out of range"),
        (["--count", "3", "--sysid-base", "254"], "do not fit in 1..255"),
        (["--tcp-base-port", "70000"], "port must be 0..65535"),
    ],
)
def test_cli_rejects_bad_input_with_a_clear_message(args: list[str], message: str) -> None:
    result = subprocess.run(
        [sys.executable, "-m", "gateway.cli", "sim", *args],
        capture_output=True,
        text=True,
        timeout=scaled(60),
    )
    assert result.returncode == 2
    assert message in result.stderr


def test_parse_home_and_param_table_units() -> None:
    assert parse_home("-35.1, 149.2, 584, 370") == (-35.1, 149.2, 584.0, 10.0)
    table = ParamTable("4.7", {"MAV_SYSID": 9})
    assert len(table) == 1354 and table.get("MAV_SYSID") == 9
    assert table.set("DISARM_DELAY", 3.7).value == 4  # INT8: stored as ArduPilot's integer cast
    assert table.set("WPNAV_SPEED", 0.1).value == pytest.approx(0.1, rel=1e-6)
    with pytest.raises(ParamError, match="unknown parameter"):
        table.set("SYSID_THISMAV", 3)
    with pytest.raises(ParamError, match="finite"):
        table.set("WPNAV_SPEED", float("nan"))
    old = ParamTable("4.6")
    assert old.find("SYSID_THISMAV") and old.find("SR0_POSITION") and old.find("MAV_SYSID") is None
    with pytest.raises(ParamError, match="unknown firmware"):
        ParamTable("4.5")


async def test_in_process_fleet_and_control_api_errors() -> None:
    async with SimFleet(2, tcp_base_port=0, speedup=SPEEDUP, seed=3) as fleet:
        server = ControlServer(fleet)
        await server.start()
        try:
            async with SimControl(server.url) as control:
                states = await control.vehicles()
                assert [s["sysid"] for s in states] == [1, 2]
                assert (await control.set_packet_loss(1, 25))["packet_loss_pct"] == 25
                assert (await control.gps_loss(0))["gps_ok"] is False
                with pytest.raises(httpx.HTTPStatusError) as bad:
                    await control.set_battery(0, 150)
                assert "0..100" in bad.value.response.json()["error"]
                with pytest.raises(httpx.HTTPStatusError) as missing:
                    await control.state(7)
                assert missing.value.response.status_code == 404
                with pytest.raises(httpx.HTTPStatusError) as unknown:
                    await control.set_param(0, "NO_SUCH", 1)
                assert "unknown parameter" in unknown.value.response.json()["error"]
                assert fleet[0].battery.remaining_pct == 100.0  # the refused request changed nothing
        finally:
            await server.stop()


async def test_udp_output_link_flies_with_mavsdk() -> None:
    port = free_udp_port()
    async with sim_process(1, speedup=SPEEDUP, extra_args=["--udp-base-port", str(port)]) as sim:
        assert sim.udp_urls == [f"udpin://127.0.0.1:{port}"]
        async with mavsdk_system(sim.udp_urls[0]) as drone:
            await set_rates(drone)
            await wait_for(drone.telemetry.health(), lambda h: h.is_global_position_ok)


async def test_sim_prints_three_vehicles_and_stops_on_sigint() -> None:
    """`fleet-gateway sim --count 3` (what `make demo` used to start alone; it now runs the gateway too)."""
    proc = await asyncio.create_subprocess_exec(
        sys.executable, "-m", "gateway.cli", "sim", "--count", "3", "--tcp-base-port", "0", "--speedup", "5",
        stdout=asyncio.subprocess.PIPE, stderr=asyncio.subprocess.DEVNULL, start_new_session=True,
    )  # fmt: skip
    try:
        lines: list[str] = []
        while "ready" not in lines:
            raw = await asyncio.wait_for(proc.stdout.readline(), scaled(30))
            assert raw, "demo exited early"
            lines.append(raw.decode().strip())
        vehicles = [line for line in lines if line.startswith("vehicle ")]
        assert len(vehicles) == 3 and all("tcpout://127.0.0.1:" in v for v in vehicles)
        os.killpg(proc.pid, signal.SIGINT)
        assert await asyncio.wait_for(proc.wait(), scaled(15)) == 0
    finally:
        if proc.returncode is None:
            os.killpg(proc.pid, signal.SIGKILL)
            await proc.wait()
