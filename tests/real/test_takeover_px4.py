"""A pilot or ground station always wins on PX4 SIH: the scenarios of tests/real/takeover.py (an
agent's call flying through MCP over HTTP while a second ground station switches the mode)."""

from __future__ import annotations

from pathlib import Path

import pytest

from tests.helpers.autopilots import Autopilot
from tests.helpers.timing import scaled
from tests.real.conftest import KeptAutopilot
from tests.real.takeover import (
    close_second_gcs,
    pilot_target_during_a_hold,
    px4_paused_by_a_second_gcs_mid_goto,
    run,
    run_formation,
    takeover_mid_goto,
    takeover_mid_takeoff_and_mission,
)
from tests.real.test_tour_px4 import PX4

pytestmark = [pytest.mark.real, pytest.mark.timeout(scaled(600))]


@pytest.fixture
def px4(px4_of_module: Autopilot, kept_px4: KeptAutopilot) -> Autopilot:
    """One autopilot for the single-drone scenarios (each ends on the ground, disarmed), with its second
    ground station's connection kept as long as it runs."""
    kept_px4.on_stop(close_second_gcs, px4_of_module.gcs)
    return px4_of_module


async def test_a_second_ground_station_switches_px4_to_return_mid_goto(px4, tmp_path: Path) -> None:
    rtl = {"custom_mode": 0, "px4_modes": (4, 5)}
    kw = {"switch": rtl, "from_mode": "AUTO.LOITER", "to_mode": "AUTO.RTL", "reported": "RETURN_TO_LAUNCH"}
    await run(tmp_path, PX4, px4, takeover_mid_goto, keep_second_gcs=True, **kw)


async def test_a_second_ground_station_pauses_a_px4_goto_in_hold(px4, tmp_path: Path) -> None:
    await run(tmp_path, PX4, px4, px4_paused_by_a_second_gcs_mid_goto, keep_second_gcs=True)


async def test_a_second_ground_station_repositions_a_holding_px4_in_hold(px4, tmp_path: Path) -> None:
    await run(tmp_path, PX4, px4, pilot_target_during_a_hold, keep_second_gcs=True)


async def test_a_second_ground_station_takes_px4_mid_takeoff_and_mid_mission(px4, tmp_path: Path) -> None:
    takeoff = (
        {"custom_mode": 0, "px4_modes": (4, 6)},
        "the autopilot switched from AUTO.TAKEOFF to AUTO.LAND",
    )
    mission = (
        {"custom_mode": 0, "px4_modes": (4, 3)},
        "the autopilot switched from AUTO.MISSION to AUTO.LOITER",
    )
    await run(
        tmp_path,
        PX4,
        px4,
        takeover_mid_takeoff_and_mission,
        keep_second_gcs=True,
        takeoff=takeoff,
        mission=mission,
    )


async def test_a_second_ground_station_takes_a_px4_mid_formation(
    launch, kept_px4: KeptAutopilot, tmp_path: Path
) -> None:
    kept_px4.stop()  # the single-drone scenarios are done: its CPU goes to these two
    rtl = {"custom_mode": 0, "px4_modes": (4, 5)}
    kw = {"switch": rtl, "from_mode": "AUTO.LOITER", "to_mode": "AUTO.RTL", "reported": "RETURN_TO_LAUNCH"}
    await run_formation(tmp_path, PX4, launch("px4", 2), **kw)
