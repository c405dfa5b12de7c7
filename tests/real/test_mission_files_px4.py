"""A QGroundControl .plan written for PX4 (takeoff, DO_CHANGE_SPEED, waypoints, DO_SET_ROI_LOCATION, RTL) on
real PX4 SIH through the gateway: accepted by PUT .../mission, exported again, flown to the end with
initiate_mission; the flight's .tlog holds the track."""

from __future__ import annotations

from pathlib import Path

import httpx
import pytest

from gateway.fleet.missions import mission_files
from tests.helpers.timing import scaled
from tests.real.test_tour_px4 import PX4
from tests.real.tour import gateway_over
from tests.real.waits import closed_flight, tlog_points

pytestmark = [pytest.mark.real, pytest.mark.timeout(scaled(900))]

PLAN = (Path(__file__).resolve().parents[1] / "data" / "missions" / "px4_survey.plan").read_text()


async def test_a_px4_plan_file_flies_to_the_end(launch, tmp_path: Path) -> None:
    async with gateway_over(tmp_path, PX4, launch("px4", 1)) as (t, _settings):
        d = t.ids[0]
        async with httpx.AsyncClient(base_url=f"{t.base_url}/api/v1", timeout=scaled(60)) as http:
            put = await http.put(
                f"/vehicles/{d}/mission", content=PLAN, headers={"content-type": "application/json"}
            )
            assert put.status_code == 200, put.text
            sent = mission_files.parse(PLAN).items
            for fmt in ("plan", "waypoints"):
                exported = await http.get(f"/vehicles/{d}/mission", params={"format": fmt})
                assert exported.status_code == 200, exported.text
                back = mission_files.parse(exported.text).items
                assert [i.command for i in back] == [i.command for i in sent]
                waypoints = [(round(i.x, 5), round(i.y, 5), i.z) for i in back if i.command == 16]
                assert waypoints == [(round(i.x, 5), round(i.y, 5), i.z) for i in sent if i.command == 16]

            op = await t.ok("initiate_mission", drone_id=d, wait=False)
            op = await t.finish(op, 600)
            assert op["status"] == "succeeded" and op["kind"] == "mission", op

            flight = await closed_flight(http, d, 300)
            tlog = await http.get(f"/flights/{flight['id']}/tlog")
            assert tlog.status_code == 200

    path = tmp_path / "flight.tlog"
    path.write_bytes(tlog.content)
    points = tlog_points(path, "common")
    assert len(points) >= 20
    assert max(p[0] for p in points) == pytest.approx(47.3981, abs=1.5e-4)  # the northern waypoints
    # the north-east waypoint (item 5, 20 m) is in the track; the highest point is PX4's RTL climb (30 m)
    assert any(
        abs(lat - 47.3981) < 1e-4 and abs(lon - 8.5461) < 1.5e-4 and abs(alt - 20) < 3
        for lat, lon, alt in points
    )
