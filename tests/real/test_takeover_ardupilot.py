"""A pilot or ground station always wins on ArduCopter SITL: the scenarios of tests/real/takeover.py (an
agent's call flying through MCP over HTTP while a second ground station switches the mode)."""

from __future__ import annotations

from pathlib import Path

import pytest

from tests.helpers.autopilots import Autopilot
from tests.helpers.timing import scaled
from tests.real.conftest import KeptAutopilot
from tests.real.takeover import (
    arducopter_sent_elsewhere_by_a_second_gcs_mid_goto,
    close_second_gcs,
    pilot_target_during_a_hold,
    run,
    run_formation,
    takeover_mid_goto,
    takeover_mid_takeoff_and_mission,
)
from tests.real.test_tour_ardupilot import ARDUCOPTER

pytestmark = [pytest.mark.real, pytest.mark.timeout(scaled(600))]


@pytest.fixture
def arducopter(arducopter_of_module: Autopilot, kept_arducopter: KeptAutopilot) -> Autopilot:
    """One autopilot for the single-drone scenarios (each ends on the ground, disarmed), with its second
    ground station's connection kept as long as it runs."""
    kept_arducopter.on_stop(close_second_gcs, arducopter_of_module.gcs)
    return arducopter_of_module


async def test_a_second_ground_station_switches_arducopter_to_loiter_mid_goto(
    arducopter, tmp_path: Path
) -> None:
    loiter = {"switch": {"custom_mode": 5}, "from_mode": "GUIDED", "to_mode": "LOITER", "reported": "LOITER"}
    await run(tmp_path, ARDUCOPTER, arducopter, takeover_mid_goto, keep_second_gcs=True, **loiter)


async def test_a_second_ground_station_sends_an_arducopter_elsewhere_in_guided(
    arducopter, tmp_path: Path
) -> None:
    await run(
        tmp_path,
        ARDUCOPTER,
        arducopter,
        arducopter_sent_elsewhere_by_a_second_gcs_mid_goto,
        keep_second_gcs=True,
    )


async def test_a_second_ground_station_sends_a_holding_arducopter_elsewhere_in_guided(
    arducopter, tmp_path: Path
) -> None:
    await run(tmp_path, ARDUCOPTER, arducopter, pilot_target_during_a_hold, keep_second_gcs=True)


async def test_a_second_ground_station_takes_arducopter_mid_takeoff_and_mid_mission(
    arducopter, tmp_path: Path
) -> None:
    takeoff = ({"custom_mode": 5}, "the autopilot switched from GUIDED to LOITER")
    mission = ({"custom_mode": 6}, "the autopilot switched from AUTO to RTL")
    await run(
        tmp_path,
        ARDUCOPTER,
        arducopter,
        takeover_mid_takeoff_and_mission,
        keep_second_gcs=True,
        takeoff=takeoff,
        mission=mission,
    )


async def test_a_second_ground_station_takes_an_arducopter_mid_formation(
    launch, kept_arducopter: KeptAutopilot, tmp_path: Path
) -> None:
    kept_arducopter.stop()  # the single-drone scenarios are done: its CPU goes to these two
    kw = {"switch": {"custom_mode": 5}, "from_mode": "GUIDED", "to_mode": "LOITER", "reported": "LOITER"}
    await run_formation(tmp_path, ARDUCOPTER, launch("ardupilot", 2), **kw)
