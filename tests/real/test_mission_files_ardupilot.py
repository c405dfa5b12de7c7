"""A ground station's mission file on real ArduCopter SITL, through the gateway: ArduPilot's own autotest
mission (CANGPSCopterMission, QGC WPL 110: altitude-0 and 0, 0 items, CONDITION_YAW, LOITER_TIME, DO_JUMP,
RTL) is accepted by PUT .../mission, exported again as WPL and .plan, started with initiate_mission and
flown to the end; the flight's .tlog (the autopilot's own frames) opens in pymavlink with the whole track."""

from __future__ import annotations

from pathlib import Path

import httpx
import pytest

from gateway.fleet.missions import mission_files
from tests.helpers.timing import scaled
from tests.real.test_tour_ardupilot import ARDUCOPTER
from tests.real.tour import gateway_over
from tests.real.waits import closed_flight, tlog_points

pytestmark = [pytest.mark.real, pytest.mark.timeout(scaled(900))]

MISSION = (Path(__file__).resolve().parents[1] / "data" / "missions" / "CANGPSCopterMission.txt").read_text()


async def test_the_autotest_mission_file_flies_to_the_end_and_logs_as_tlog(launch, tmp_path: Path) -> None:
    async with gateway_over(tmp_path, ARDUCOPTER, launch("ardupilot", 1)) as (t, _settings):
        d = t.ids[0]
        async with httpx.AsyncClient(base_url=f"{t.base_url}/api/v1", timeout=scaled(60)) as http:
            put = await http.put(
                f"/vehicles/{d}/mission", content=MISSION, headers={"content-type": "text/plain"}
            )
            assert put.status_code == 200, put.text
            assert put.json()["message"] == "12 items uploaded from the mission file"

            sent = mission_files.parse(MISSION).items
            wpl = await http.get(f"/vehicles/{d}/mission", params={"format": "waypoints"})
            assert wpl.status_code == 200 and wpl.text.startswith("QGC WPL 110")
            plan = await http.get(f"/vehicles/{d}/mission", params={"format": "plan"})
            assert plan.status_code == 200 and plan.json()["fileType"] == "Plan"
            # ArduPilot stores a command that is not a position without a frame (it answers 0): positions
            # come back with their frame and place, everything with its command and parameters
            for exported in (wpl.text, plan.text):
                back = mission_files.parse(exported).items
                assert [i.command for i in back] == [i.command for i in sent]
                for got, want in zip(back, sent, strict=True):
                    assert (got.param1, got.param2) == (want.param1, want.param2)
                    if want.command in (16, 19, 22):
                        assert (got.frame, round(got.x, 5), round(got.y, 5), got.z) == (
                            want.frame, round(want.x, 5), round(want.y, 5), want.z,
                        )  # fmt: skip

            op = await t.ok("initiate_mission", drone_id=d, wait=False)
            op = await t.finish(op, 600)
            assert op["status"] == "succeeded" and op["kind"] == "mission", op

            # the last item is RTL: the drone comes home, lands and disarms, which closes the flight
            flight = await closed_flight(http, d, 300)
            tlog = await http.get(f"/flights/{flight['id']}/tlog")
            assert tlog.status_code == 200
            track = (await http.get(f"/flights/{flight['id']}/track.geojson")).json()

    path = tmp_path / "flight.tlog"
    path.write_bytes(tlog.content)
    points = tlog_points(path, "ardupilotmega")
    # the autopilot's own GLOBAL_POSITION_INTs: at its rate, more than the 1 Hz track's samples
    assert tlog.headers["x-tlog-source"] == "autopilot"
    assert len(points) > track["properties"]["sample_count"] >= 20
    # the whole track: the mission's southern leg (-35.365361), its 40 m waypoint, and home again
    assert min(p[0] for p in points) == pytest.approx(-35.365361, abs=2e-4)
    assert max(p[2] for p in points) == pytest.approx(40.0, abs=4.0)
    assert points[-1][2] < 2.0
