"""A flight's .tlog on real ArduCopter SITL is the autopilot's own stream: flown through the gateway
(takeoff, a 100 m leg, RTL), exported over REST and read by pymavlink's own tools. `mavflightmodes` finds
the modes ArduCopter flew in the order it flew them, `mavflighttime` the time in the air and the
distance, and the log holds what the 1 Hz reconstruction never wrote (ATTITUDE, SYS_STATUS at the
autopilot's rate, the autopilot's STATUSTEXTs), every frame from the drone's system id."""

from __future__ import annotations

import re
import subprocess
import sys
from collections import Counter
from pathlib import Path

import httpx
import pytest
from pymavlink import mavutil

from gateway.fleet import geo
from tests.helpers.timing import scaled
from tests.real.test_tour_ardupilot import ARDUCOPTER
from tests.real.tour import gateway_over
from tests.real.waits import closed_flight

pytestmark = [pytest.mark.real, pytest.mark.timeout(scaled(600))]
TOOLS = Path(sys.executable).parent  # pymavlink installs its tools beside the interpreter
LEG_M = 100.0


def _run(tool: str, log: Path) -> str:
    done = subprocess.run(
        [sys.executable, str(TOOLS / tool), str(log)], capture_output=True, text=True, timeout=scaled(120)
    )
    assert done.returncode == 0, done.stderr
    return done.stdout


async def test_the_tlog_is_the_autopilots_stream_and_the_fields_tools_read_it(launch, tmp_path: Path) -> None:
    async with gateway_over(tmp_path, ARDUCOPTER, launch("ardupilot", 1)) as (t, _settings):
        d = t.ids[0]
        sysid = (await t.rest("GET", f"/vehicles/{d}"))["status"]["sysid"]
        home = await t.position(d)
        op = await t.ok("takeoff", drone_id=d, alt_m=10)
        assert (await t.finish(op, 90))["status"] == "succeeded", op
        lat, lon = geo.offset_position(home["lat_deg"], home["lon_deg"], LEG_M, 0)
        op = await t.ok("go_to_location", drone_id=d, lat_deg=lat, lon_deg=lon, alt_m=10)
        assert (await t.finish(op, 120))["status"] == "succeeded", op
        await t.ok("return_to_launch", drone_id=d, wait=False)
        async with httpx.AsyncClient(base_url=f"{t.base_url}/api/v1", timeout=scaled(60)) as http:
            flight = await closed_flight(http, d, 240)  # RTL lands and disarms: the flight ends
            tlog = await http.get(f"/flights/{flight['id']}/tlog")
    assert tlog.status_code == 200, tlog.text
    assert tlog.headers["x-tlog-source"] == "autopilot" and tlog.headers["x-tlog-cut"] == "false"
    path = tmp_path / "flight.tlog"
    path.write_bytes(tlog.content)

    # the modes ArduCopter flew, in order: the takeoff's GUIDED, then RTL to the end
    modes = re.findall(r"MAV\.flightmode=(\S+)", _run("mavflightmodes.py", path))
    flown = [m for i, m in enumerate(modes) if i == 0 or m != modes[i - 1]]
    assert "GUIDED" in flown and flown[-1] == "RTL", modes
    assert flown.index("GUIDED") < len(flown) - 1, modes

    times = _run("mavflighttime.py", path)
    minutes, seconds = map(int, re.search(r"Total time in air: (\d+):(\d+)", times).groups())  # type: ignore[union-attr]
    distance = float(re.search(r"Total distance travelled: ([\d.]+) meters", times).group(1))  # type: ignore[union-attr]
    assert 0 < minutes * 60 + seconds <= flight["duration_s"], times
    assert 1.6 * LEG_M <= distance <= 3 * LEG_M, times  # out and back, as the autopilot's GPS saw it

    # the autopilot's own messages at its own rates, from its system id (frames from the drone only)
    log = mavutil.mavlink_connection(str(path), dialect="ardupilotmega")
    counts: Counter[str] = Counter()
    senders: set[int] = set()
    texts: list[str] = []
    while (msg := log.recv_match()) is not None:
        counts[msg.get_type()] += 1
        if msg.get_type() == "BAD_DATA":
            continue
        senders.add(msg.get_srcSystem())
        if msg.get_type() == "STATUSTEXT":
            texts.append(msg.text)
    assert senders == {sysid}, senders
    assert counts["BAD_DATA"] == 0
    duration = flight["duration_s"]
    for name in ("ATTITUDE", "SYS_STATUS", "GPS_RAW_INT", "GLOBAL_POSITION_INT"):
        assert counts[name] >= duration, (name, counts, duration)  # at least 1 Hz over the whole flight
    print(f"\n{sum(counts.values())} messages in {duration:.1f} s of flight: {dict(counts.most_common(8))}")
    assert texts, counts  # ArduCopter's own words (arming, mode changes...)
