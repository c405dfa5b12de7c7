"""Settings judged by their effect on real ArduCopter SITL (4.7), through MCP over HTTP and the gateway's
REST: RTL_CLIMB_MIN_M, which ArduCopter adds to the altitude RTL starts from, is refused above 0 and
nothing reaches the autopilot; CIRCLE, which reads the pilot's throttle and sinks without RC, is refused
in the air; and the distance limit counts from the first home, not from the home ArduCopter sets again
at every arming. The distance limit is lowered to 60 m so the flight stays short."""

from __future__ import annotations

from pathlib import Path

import pytest

from gateway.fleet import geo
from tests.helpers.autopilots import Autopilot
from tests.helpers.timing import scaled
from tests.real.test_tour_ardupilot import ARDUCOPTER
from tests.real.tour import distance, gateway_over

pytestmark = [pytest.mark.real, pytest.mark.timeout(scaled(600))]

LIMIT_M = 60.0


async def test_arducopter_climb_min_circle_and_the_origin_by_their_effect(
    arducopter: Autopilot, tmp_path: Path
) -> None:
    async with gateway_over(tmp_path, ARDUCOPTER, [arducopter], max_distance_m=LIMIT_M) as (t, _settings):
        d = t.ids[0]
        # RTL_CLIMB_MIN_M: added to the altitude RTL starts from; nothing above 0 is written
        before = (await t.ok("get_parameter", drone_id=d, name="RTL_CLIMB_MIN_M"))["value"]
        text = await t.refused("set_parameter", "param_limit", "is added by the autopilot", "accepted: 0 m",
                               drone_id=d, name="RTL_CLIMB_MIN_M", value=30)  # fmt: skip
        assert "it would go to 150 m, beyond the max_altitude_m limit of 120 m" in text, text
        assert (await t.ok("get_parameter", drone_id=d, name="RTL_CLIMB_MIN_M"))["value"] == before == 0
        assert (await t.ok("set_parameter", drone_id=d, name="RTL_CLIMB_MIN_M", value=0))["value"] == 0
        await t.refused("set_parameter", "param_range", "accepted: 5 to 1000 cm",
                        drone_id=d, name="WPNAV_RADIUS", value=1e9)  # fmt: skip

        first_home = await t.ok("get_home_position", drone_id=d)
        op = await t.finish(await t.ok("takeoff", drone_id=d, alt_m=10), 90)
        assert op["status"] == "succeeded", op

        # CIRCLE in the air: refused, the autopilot stays in GUIDED at its altitude
        await t.refused("set_flight_mode", "mode_deny_in_air", "mode CIRCLE reads the pilot's throttle",
                        drone_id=d, mode="CIRCLE")  # fmt: skip
        assert (await t.ok("get_flight_mode", drone_id=d))["value"] == "GUIDED"

        # land 45 m out, take off again: ArduCopter moves home there at arming, the origin stays
        lat, lon = geo.offset_position(first_home["lat_deg"], first_home["lon_deg"], 45, 0)
        op = await t.finish(await t.ok("go_to_location", drone_id=d, lat_deg=lat, lon_deg=lon, alt_m=10), 90)
        assert op["status"] == "succeeded", op
        assert (await t.finish(await t.ok("land", drone_id=d), 120))["status"] == "succeeded"
        await t.until("get_armed", lambda r: r["value"] is False, 60, "disarmed", drone_id=d)
        op = await t.finish(await t.ok("takeoff", drone_id=d, alt_m=10), 90)
        assert op["status"] == "succeeded", op
        new_home = await t.ok("get_home_position", drone_id=d)
        moved = distance(new_home, first_home["lat_deg"], first_home["lon_deg"])
        assert moved > 40, (first_home, new_home)  # ArduCopter set home again at arming
        origin = await t.rest("GET", f"/vehicles/{d}/origin")
        assert origin["source"] == "first_home", origin
        assert abs(origin["origin"]["lat"] - first_home["lat_deg"]) < 1e-6, (origin, first_home)

        # 30 m on: 30 m from the new home, 75 m from the first: refused, the drone stays
        here = await t.position(d)
        lat, lon = geo.offset_position(new_home["lat_deg"], new_home["lon_deg"], 30, 0)
        text = await t.refused("go_to_location", "max_distance", "from its origin (the first home",
                               drone_id=d, lat_deg=lat, lon_deg=lon, alt_m=10)  # fmt: skip
        assert "beyond the limit of 60 m" in text, text
        assert distance(await t.position(d), here["lat_deg"], here["lon_deg"]) < 3.0
        print(f"\nFIGURE ardupilot: home moved {moved:.1f} m at arming; the goto {text.split(':')[2][:60]}")

        # back home with RTL (it returns to the new home, within the limit), down and disarmed
        op = await t.finish(await t.ok("return_to_launch", drone_id=d), 180)
        assert op["status"] == "succeeded", op
