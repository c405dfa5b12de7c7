"""Every drone tool, a mission (and one PX4 rejects), the modes, the refusals and a short formation on
real PX4 SIH (lockstep, faster than real time), through MCP over HTTP: see tests/real/tour.py."""

from __future__ import annotations

from pathlib import Path

import pytest

from tests.helpers.timing import scaled
from tests.real.tour import Profile, run_tour

pytestmark = [pytest.mark.real, pytest.mark.timeout(scaled(900))]

#: The fixtures read this. Two PX4s at 1.5 take the CPU three took at 1 (a fifth of a core each at real
#: time): at 2, three took about one core between them and in a full run (2 workers, 2 cores, the takeover
#: file beside it with its PX4 at 3) the tour's last boot check lost px3's link (its disarm timed out).
#: Alone on this machine, three at 1 took 239 s (the formation 67 s of it).
PX4_SPEED_FACTOR = 1.5

PX4 = Profile(
    prefix="px",
    autopilot="px4",
    boot_s=120,
    ground_modes=(
        ("AUTO.LOITER", "HOLD"),
        ("POSITION", "HOLD"),
        ("RTL", "RETURN_TO_LAUNCH"),
        ("LAND", "LAND"),
        ("GUIDED", "HOLD"),
    ),
    air_modes=(
        ("LAND", "LAND"),
        ("RTL", "RETURN_TO_LAUNCH"),
        ("AUTO.RTL", "RETURN_TO_LAUNCH"),
        ("TAKEOFF", "TAKEOFF"),
        ("LOITER", "HOLD"),
        ("GUIDED", "HOLD"),
        ("AUTO.LAND", "LAND"),
        ("AUTO.TAKEOFF", "TAKEOFF"),
    ),
    mission_modes=("MISSION", "AUTO.MISSION"),
    air_refused=(),
    lacks="SMART_RTL",
    speed_param=("MPC_XY_VEL_MAX", 8.0),
    protected="COM_ARM_WO_GPS",
    param_refusals=(
        ("MPC_XY_VEL_MAX", 20.0, "param_limit: MPC_XY_VEL_MAX 20 m/s would let the autopilot exceed"),
        ("RTL_RETURN_ALT", 130.0, "exceed the max_altitude_m limit of 120 m"),
        ("MPC_Z_VEL_MAX_UP", 6.0, "max_vertical_speed_mps"),
        ("EKF2_GPS_CTRL", 0.0, "param_not_allowed"),
        ("SYS_AUTOSTART", 0.0, "param_not_allowed"),
    ),
    return_alt_param="RTL_RETURN_ALT",
    hold_mode="HOLD",
    mission_mode="MISSION",
    acceptance_param="NAV_ACC_RAD",  # 10 m by default: PX4 turns that far before a waypoint
)


async def test_every_drone_tool_mission_modes_and_formation_on_px4(launch, tmp_path: Path) -> None:
    await run_tour(tmp_path, PX4, launch("px4", 2))
