"""Settings judged by their effect on real PX4 SIH, through MCP over HTTP and the gateway's REST: an
allowlisted parameter outside PX4's own range is refused with nothing written, its pilot modes are not
offered, and the distance limit counts from the first home, not from the home PX4 sets again at arming.
The distance limit is lowered to 60 m so the flight stays short."""

from __future__ import annotations

from pathlib import Path

import pytest

from gateway.fleet import geo
from tests.helpers.autopilots import Autopilot
from tests.helpers.timing import scaled
from tests.real.test_tour_px4 import PX4
from tests.real.tour import distance, gateway_over

pytestmark = [pytest.mark.real, pytest.mark.timeout(scaled(600))]


async def test_px4_parameter_range_pilot_modes_and_the_origin_by_their_effect(
    px4: Autopilot, tmp_path: Path
) -> None:
    async with gateway_over(tmp_path, PX4, [px4], max_distance_m=60.0) as (t, _settings):
        d = t.ids[0]
        before = (await t.ok("get_parameter", drone_id=d, name="NAV_ACC_RAD"))["value"]
        await t.refused("set_parameter", "param_range", "accepted: 0.05 to 200 m",
                        drone_id=d, name="NAV_ACC_RAD", value=5000)  # fmt: skip
        assert (await t.ok("get_parameter", drone_id=d, name="NAV_ACC_RAD"))["value"] == before
        for pilot_mode in ("POSCTL", "ALTCTL"):
            await t.refused("set_flight_mode", "is not a mode of drone", drone_id=d, mode=pilot_mode)

        first_home = await t.ok("get_home_position", drone_id=d)
        op = await t.finish(await t.ok("takeoff", drone_id=d, alt_m=10), 90)
        assert op["status"] == "succeeded", op
        lat, lon = geo.offset_position(first_home["lat_deg"], first_home["lon_deg"], 45, 0)
        op = await t.finish(await t.ok("go_to_location", drone_id=d, lat_deg=lat, lon_deg=lon, alt_m=10), 120)
        assert op["status"] == "succeeded", op
        assert (await t.finish(await t.ok("land", drone_id=d), 120))["status"] == "succeeded"
        await t.until("get_armed", lambda r: r["value"] is False, 60, "disarmed", drone_id=d)
        op = await t.finish(await t.ok("takeoff", drone_id=d, alt_m=10), 90)
        assert op["status"] == "succeeded", op
        new_home = await t.ok("get_home_position", drone_id=d)
        moved = distance(new_home, first_home["lat_deg"], first_home["lon_deg"])
        assert moved > 40, (first_home, new_home)  # PX4 set home again at arming
        here = await t.position(d)
        lat, lon = geo.offset_position(new_home["lat_deg"], new_home["lon_deg"], 30, 0)
        text = await t.refused("go_to_location", "max_distance", "from its origin (the first home",
                               drone_id=d, lat_deg=lat, lon_deg=lon, alt_m=10)  # fmt: skip
        assert distance(await t.position(d), here["lat_deg"], here["lon_deg"]) < 3.0
        print(f"\nFIGURE px4: home moved {moved:.1f} m at arming; the goto {text.split(':')[2][:60]}")
        assert (await t.finish(await t.ok("land", drone_id=d), 120))["status"] == "succeeded"
