"""Every drone tool, a mission, the modes, the refusals and a formation on real ArduCopter SITL
(speed-up 5), through MCP over HTTP: see tests/real/tour.py."""

from __future__ import annotations

from pathlib import Path

import pytest

from tests.helpers.timing import scaled
from tests.real.tour import Profile, run_tour

pytestmark = [pytest.mark.real, pytest.mark.timeout(scaled(900))]

ARDUCOPTER = Profile(
    prefix="ap",
    autopilot="ardupilot",
    boot_s=120,
    ground_modes=(
        ("STABILIZE", "STABILIZE"),
        ("ALT_HOLD", "ALT_HOLD"),
        ("POSHOLD", "POSHOLD"),
        ("LAND", "LAND"),
        ("RTL", "RTL"),
        ("BRAKE", "BRAKE"),
        ("POSITION", "GUIDED"),
        ("GUIDED", "GUIDED"),
    ),
    air_modes=(
        ("BRAKE", "BRAKE"),
        ("LAND", "LAND"),
        ("RTL", "RTL"),
        ("SMART_RTL", "SMART_RTL"),
        ("LOITER", "GUIDED"),
        ("GUIDED", "GUIDED"),
    ),
    mission_modes=("MISSION", "AUTO"),
    air_refused=("STABILIZE", "ALT_HOLD", "CIRCLE"),  # CIRCLE reads the throttle: sinks without RC
    lacks="TAKEOFF",
    speed_param=("WPNAV_SPEED", 750.0),
    protected="ARMING_CHECK",
    param_refusals=(
        ("WPNAV_SPEED", 4000.0, "param_limit: WPNAV_SPEED 4000 cm/s (40 m/s)"),
        ("RTL_ALT_M", 300.0, "exceed the max_altitude_m limit"),  # 4.7's name (RTL_ALT before)
        ("LAND_SPD_MS", 5.0, "above the autopilot's range"),  # 4.7's name (LAND_SPEED before)
        ("RTL_CLIMB_MIN_M", 30.0, "is added by the autopilot to where the vehicle is"),
        ("CIRCLE_RADIUS_M", 1000.0, "a radius whose pattern reaches two radii (2000 m)"),
        ("WPNAV_RADIUS", 1e9, "param_range: WPNAV_RADIUS"),
        ("WPNAV_ACCEL", 1e7, "param_range: WPNAV_ACCEL"),
        ("LOIT_BRK_DELAY", 1e6, "param_range: LOIT_BRK_DELAY"),
        ("GPS1_TYPE", 0.0, "param_not_allowed"),
        ("EK3_SRC1_POSXY", 0.0, "param_not_allowed"),
        ("SERIAL0_PROTOCOL", 0.0, "param_not_allowed"),
    ),
    return_alt_param="RTL_ALT_M",  # 4.7: metres (RTL_ALT in centimetres before)
    hold_mode="GUIDED",
    mission_mode="AUTO",
    # GPS and home come ~20 s (simulated) before the EKF uses GPS: list_drones and REST say so; before
    # the first EKF_STATUS_REPORT arrives (the gateway asks for it among the rates) they say that instead
    boot_waits=(
        "waiting for the position estimate (no EKF status report yet)",
        "waiting for the position estimate (the EKF is not using GPS yet)",
    ),
)


async def test_every_drone_tool_mission_modes_and_formation_on_arducopter(launch, tmp_path: Path) -> None:
    await run_tour(tmp_path, ARDUCOPTER, launch("ardupilot", 3))
