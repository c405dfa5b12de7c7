"""A flight's .tlog read by the field's own tools: pymavlink's `mavflightmodes` finds the modes the
autopilot flew (GUIDED, RTL: from the HEARTBEATs' custom mode) and `mavflighttime` the time in the air and
the distance (from GPS_RAW_INT). Flown on the simulator through MCP, the log fetched over REST: it is the
simulator's own frames as the relay received them (messages the 1 Hz reconstruction never writes, such
as ATTITUDE, at the simulator's rate), starting a few seconds before the arming."""

from __future__ import annotations

import asyncio
import re
import subprocess
import sys
from pathlib import Path
from typing import Any

import httpx
import pytest
from pymavlink import mavutil

from tests.helpers.timing import scaled
from tests.mcp.conftest import Stack, point_from, structured, wait_until_true

pytestmark = pytest.mark.asyncio(loop_scope="module")
DRONES = 1
TOOLS = Path(sys.executable).parent  # pymavlink installs its tools beside the interpreter


def _run(tool: str, log: Path) -> str:
    script = TOOLS / tool
    done = subprocess.run(
        [sys.executable, str(script), str(log)], capture_output=True, text=True, timeout=scaled(120)
    )
    assert done.returncode == 0, done.stderr
    return done.stdout


def _read(path: Path) -> tuple[list[tuple[str, bool]], int, set[int]]:
    """(mode, armed) of each HEARTBEAT, the number of ATTITUDEs and the system ids of every message."""
    log = mavutil.mavlink_connection(str(path), dialect="ardupilotmega")
    heartbeats, attitudes, senders = [], 0, set()
    while (msg := log.recv_match()) is not None:
        senders.add(msg.get_srcSystem())
        if msg.get_type() == "HEARTBEAT":
            heartbeats.append(
                (log.flightmode, bool(msg.base_mode & mavutil.mavlink.MAV_MODE_FLAG_SAFETY_ARMED))
            )
        elif msg.get_type() == "ATTITUDE":
            attitudes += 1
    return heartbeats, attitudes, senders


async def _flight(stack: Stack) -> dict[str, Any]:
    loop = asyncio.get_running_loop()
    deadline = loop.time() + scaled(90)
    while True:
        flights = (await stack.rest("/flights", vehicle_id="d1"))["items"]
        if flights and flights[0]["ended_at"] is not None:
            return flights[0]
        assert loop.time() < deadline, f"the flight was not closed: {flights}"
        await asyncio.sleep(0.5)


async def test_mavflightmodes_and_mavflighttime_read_the_flight(stack: Stack, tmp_path: Path) -> None:
    d = {"drone_id": "d1"}
    home = await stack.true_state("d1")
    far = point_from(home, 120, 0)
    async with stack.client("auto", name="tlog") as c:
        assert structured(await stack.call(c, "takeoff", {**d, "alt_m": 10}))["status"] == "succeeded"
        r = structured(
            await stack.call(c, "go_to_location", {**d, "lat_deg": far[0], "lon_deg": far[1], "alt_m": 10})
        )
        assert r["status"] == "succeeded", r
        await stack.call(c, "return_to_launch", {**d, "wait": False})
    await wait_until_true(stack, "d1", lambda s: not s["armed"], "landed and disarmed after RTL")
    flight = await _flight(stack)
    async with httpx.AsyncClient(base_url=stack.base_url, timeout=scaled(30)) as http:
        tlog = await http.get(f"/api/v1/flights/{flight['id']}/tlog")
    assert tlog.status_code == 200, tlog.text
    assert tlog.headers["x-tlog-source"] == "autopilot"
    log = tmp_path / "flight.tlog"
    log.write_bytes(tlog.content)

    modes = _run("mavflightmodes.py", log)
    seen = re.findall(r"MAV\.flightmode=(\S+)", modes)
    # the mode it stood in before the takeoff (the log starts before the arming), GUIDED, RTL
    assert seen[-2:] == ["GUIDED", "RTL"] and len(seen) <= 3, modes
    heartbeats, attitudes, senders = _read(log)
    assert all(not armed for mode, armed in heartbeats if mode not in ("GUIDED", "RTL")), heartbeats
    # the simulator's attitude rate (the reconstruction writes none)
    assert attitudes >= 2 * flight["duration_s"], (attitudes, flight["duration_s"])
    assert senders == {(await stack.rest("/vehicles/d1"))["status"]["sysid"]}, senders

    times = _run("mavflighttime.py", log)
    minutes, seconds = map(int, re.search(r"Total time in air: (\d+):(\d+)", times).groups())  # type: ignore[union-attr]
    distance = float(re.search(r"Total distance travelled: ([\d.]+) meters", times).group(1))  # type: ignore[union-attr]
    assert minutes * 60 + seconds > 0, times
    assert 150 <= distance <= 400, times  # 120 m out and back, as the autopilot's GPS saw it
