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
        ("CIRCLE", "CIRCLE"),
        ("LAND", "LAND"),
        ("RTL", "RTL"),
        ("SMART_RTL", "SMART_RTL"),
        ("LOITER", "GUIDED"),
        ("GUIDED", "GUIDED"),
    ),
    mission_modes=("MISSION", "AUTO"),
    air_refused=("STABILIZE", "ALT_HOLD"),
    lacks="TAKEOFF",
    speed_param=("WPNAV_SPEED", 750.0),
    protected="ARMING_CHECK",
    return_alt_param="RTL_ALT_M",  # 4.7: metres (RTL_ALT in centimetres before)
    hold_mode="GUIDED",
    mission_mode="AUTO",
    # GPS and home come ~20 s (simulated) before the EKF uses GPS: list_drones and REST say so
    boot_wait="waiting for the position estimate (the EKF is not using GPS yet)",
)


async def test_every_drone_tool_mission_modes_and_formation_on_arducopter(launch, tmp_path: Path) -> None:
    await run_tour(tmp_path, ARDUCOPTER, launch("ardupilot", 3))
