"""Unit tests of OperationManager and its trackers against a fake vehicle (telemetry set by the test)."""

from __future__ import annotations

import asyncio
from typing import Any

import pytest

from gateway.config import Settings
from gateway.errors import CommandFailed, NotFound
from gateway.fleet import geo
from gateway.fleet.operations.operation_state import Operation, OpStatus
from gateway.fleet.operations.operations import OperationManager
from gateway.fleet.operations.trackers import (
    GotoTracker,
    LandingTracker,
    MissionTracker,
    TakeoffTracker,
    YawTracker,
)
from gateway.link.telemetry import MissionProgressValue, VelocityNedValue
from tests.fakes import HOME, FakeVehicle, position_value
from tests.helpers.timing import eventually


def drone() -> FakeVehicle:
    """The shared fake drone; the tests set its telemetry by hand (no streaming, no registry)."""
    return FakeVehicle("d1")


def at(
    v: FakeVehicle, lat: float, lon: float, alt: float, armed: bool | None = None, in_air: bool | None = None
) -> None:
    v.set(position=position_value(lat, lon, alt))
    if armed is not None:
        v.set(armed=armed)
    if in_air is not None:
        v.set(in_air=in_air)


class FakeStore:
    def __init__(self) -> None:
        self.saved: list[Any] = []

    async def save_operation(self, record: Any) -> None:
        self.saved.append(record)


@pytest.fixture
def settings() -> Settings:
    return Settings(_env_file=None, mcp_wait_cap_s=5.0, arrival_tolerance_m=2.0)


async def _noop() -> None:
    return None


async def test_takeoff_succeeds_when_altitude_reached(settings: Settings) -> None:
    v = drone()
    mgr = OperationManager(settings)
    op = await mgr.start(v, TakeoffTracker(10.0), _noop, {"alt_m": 10.0})
    assert mgr.takeoff_in_progress("d1") is op
    at(v, HOME[0], HOME[1], 4.0, armed=True, in_air=True)
    await eventually(lambda: _true(0.3 < op.progress < 0.5), "takeoff progress at 4 of 10 m")
    assert op.status is OpStatus.running
    at(v, HOME[0], HOME[1], 9.8)
    await mgr.wait(op, cap_s=5.0)
    assert op.status is OpStatus.succeeded and op.progress == 1.0
    assert mgr.takeoff_in_progress("d1") is None
    await mgr.stop()


async def test_wait_cap_returns_running_and_reports_progress(settings: Settings) -> None:
    v = drone()
    at(v, HOME[0], HOME[1], 10.0, armed=True, in_air=True)
    mgr = OperationManager(settings)
    lat, lon = geo.offset_position(HOME[0], HOME[1], 100.0, 0.0)
    op = await mgr.start(v, GotoTracker(lat, lon, 10.0, 2.0, kind="goto"), _noop, {})
    seen: list[str] = []

    async def on_progress(o: Any) -> None:
        seen.append(o.message)

    async def fly() -> None:
        for north in (20.0, 50.0, 80.0):
            await asyncio.sleep(0.3)
            at(v, *geo.offset_position(HOME[0], HOME[1], north, 0.0), 10.0)

    flight = asyncio.create_task(fly())
    await mgr.wait(op, cap_s=1.5, on_progress=on_progress)
    await flight
    assert op.status is OpStatus.running
    assert op.eta_s is not None and op.progress > 0.5
    assert any("m to go" in m for m in seen)
    at(v, lat, lon, 10.5)
    await mgr.wait(op, cap_s=5.0)
    assert op.status is OpStatus.succeeded
    await mgr.stop()


async def test_new_command_supersedes_and_failed_send_keeps_current(settings: Settings) -> None:
    v = drone()
    at(v, HOME[0], HOME[1], 10.0, armed=True, in_air=True)
    store = FakeStore()
    mgr = OperationManager(settings, store)
    first = await mgr.start(v, GotoTracker(HOME[0] + 0.001, HOME[1], 10.0, 2.0), _noop, {})

    async def rejected() -> None:
        raise CommandFailed("denied")

    with pytest.raises(CommandFailed):
        await mgr.start(v, GotoTracker(HOME[0], HOME[1] + 0.001, 10.0, 2.0), rejected, {})
    assert mgr.running("d1") is first
    second = await mgr.start(v, GotoTracker(HOME[0], HOME[1] + 0.001, 10.0, 2.0), _noop, {})
    assert first.status is OpStatus.superseded and second.id in first.message
    held = await mgr.supersede("d1", "hold_position")
    assert held is second and second.status is OpStatus.superseded
    await mgr.stop()


async def test_cancelled_waiter_leaves_operation_running(settings: Settings) -> None:
    v = drone()
    at(v, HOME[0], HOME[1], 10.0, armed=True, in_air=True)
    mgr = OperationManager(settings)
    op = await mgr.start(v, GotoTracker(HOME[0] + 0.001, HOME[1], 10.0, 2.0), _noop, {})
    waiter = asyncio.create_task(mgr.wait(op, cap_s=30))
    await asyncio.sleep(0.3)
    waiter.cancel()
    with pytest.raises(asyncio.CancelledError):
        await waiter
    await asyncio.sleep(0.3)
    assert op.status is OpStatus.running
    at(v, HOME[0] + 0.001, HOME[1], 10.0)
    await mgr.wait(op, cap_s=5)
    assert op.status is OpStatus.succeeded
    await mgr.stop()


async def test_goto_fails_when_vehicle_lands(settings: Settings) -> None:
    v = drone()
    at(v, HOME[0], HOME[1], 10.0, armed=True, in_air=True)
    mgr = OperationManager(settings)
    op = await mgr.start(v, GotoTracker(HOME[0] + 0.01, HOME[1], 10.0, 2.0), _noop, {})
    at(v, HOME[0], HOME[1], 0.0, armed=False, in_air=False)
    await mgr.wait(op, cap_s=5)
    assert op.status is OpStatus.failed and "landed" in op.message


async def test_land_yaw_and_mission_trackers(settings: Settings) -> None:
    v = drone()
    at(v, HOME[0], HOME[1], 10.0, armed=True, in_air=True)
    mgr = OperationManager(settings)
    land = await mgr.start(v, LandingTracker(kind="land"), _noop, {})
    await asyncio.sleep(0.3)
    assert land.status is OpStatus.running
    at(v, HOME[0], HOME[1], 0.0, armed=False, in_air=False)
    await mgr.wait(land, cap_s=5)
    assert land.status is OpStatus.succeeded

    at(v, HOME[0], HOME[1], 10.0, armed=True, in_air=True)
    v.set(heading_deg=350.0)
    yaw = await mgr.start(v, YawTracker(90.0), _noop, {})
    await asyncio.sleep(0.3)
    assert yaw.status is OpStatus.running
    v.set(heading_deg=88.0)
    await mgr.wait(yaw, cap_s=5)
    assert yaw.status is OpStatus.succeeded

    v.set(mission_progress=MissionProgressValue(2, 4))
    mission = await mgr.start(v, MissionTracker(), _noop, {})
    await eventually(lambda: _true(mission.message == "item 2 of 4"), "mission progress item 2 of 4")
    assert mission.status is OpStatus.running
    v.mission_done = True
    await streaming_until_done(v, mission)
    assert mission.status is OpStatus.succeeded
    await mgr.stop()


async def test_stop_interrupts_and_store_records_every_state(settings: Settings) -> None:
    v = drone()
    at(v, HOME[0], HOME[1], 10.0, armed=True, in_air=True)
    store = FakeStore()
    mgr = OperationManager(settings, store)
    op = await mgr.start(v, GotoTracker(HOME[0] + 0.01, HOME[1], 10.0, 2.0), _noop, {"x": 1})
    await mgr.stop()
    assert op.status is OpStatus.interrupted
    assert next(r.status for r in store.saved if r.id == op.id) == "running"
    assert store.saved[-1].status == "interrupted" and store.saved[-1].finished_at is not None
    with pytest.raises(NotFound):
        mgr.get("nope")


async def test_recover_marks_operations_of_a_previous_process_interrupted(tmp_path: Any) -> None:
    from datetime import UTC, datetime

    from gateway.registry.store import OperationRecord, Store

    store = await Store.open(f"sqlite+aiosqlite:///{tmp_path / 'ops.db'}")
    try:
        now = datetime.now(UTC)
        await store.save_operation(
            OperationRecord(
                id="old1", vehicle_id="d1", kind="goto", status="running", created_at=now, updated_at=now
            )
        )
        mgr = OperationManager(Settings(_env_file=None), store)
        assert await mgr.recover() == 1
        record = await store.get_operation("old1")
        assert (
            record.status == "interrupted"
            and record.finished_at is not None
            and "restarted" in record.message
        )
        assert await mgr.recover() == 0
    finally:
        await store.close()


async def _true(condition: bool) -> bool:
    return condition


async def streaming_until_done(v: FakeVehicle, op: Operation) -> None:
    """Keep the fake's telemetry fresh (a stream would) until the operation ends (a finished mission is
    watched for FINISH_SETTLE_S before it counts as done)."""
    await eventually(lambda: _fresh(v, op), "the operation ends", within_s=20.0)


async def _fresh(v: FakeVehicle, op: Operation) -> bool:
    for name in ("position", "armed", "in_air", "velocity_ned"):
        sample = getattr(v.telemetry, name)
        if sample is not None:
            v.set(**{name: sample.value})
    return op.finished


async def test_a_flight_that_ends_in_a_crash_is_a_failure_in_the_autopilots_words(settings: Settings) -> None:
    """A disarm in the air, a fall, a landing the mission did not plan, a crash or failsafe the autopilot
    reported: the operation fails saying so, even when the autopilot calls the mission finished."""
    mgr = OperationManager(settings)

    v = drone()  # disarmed in the air
    at(v, HOME[0], HOME[1], 30.0, armed=True, in_air=True)
    v.set(mission_progress=MissionProgressValue(3, 4))
    mission = await mgr.start(v, MissionTracker(), _noop, {})
    await eventually(lambda: _true(mission.message == "item 3 of 4"), "the mission runs")
    v.telemetry.add_status_text("critical", "Disarming: motors stopped")
    at(v, HOME[0], HOME[1], 25.0, armed=False)
    v.mission_done = True
    await mgr.wait(mission, cap_s=5)
    assert mission.status is OpStatus.failed
    assert mission.message.startswith("the motors were disarmed in the air (last seen 30.0 m above home)")
    assert "the autopilot said: Disarming: motors stopped" in mission.message

    v = drone()  # finished, then falls: never "succeeded"
    at(v, HOME[0], HOME[1], 30.0, armed=True, in_air=True)
    v.set(mission_progress=MissionProgressValue(4, 4))
    mission = await mgr.start(v, MissionTracker(), _noop, {})
    await eventually(lambda: _true(mission.message == "item 4 of 4"), "the mission runs")
    v.mission_done = True
    await eventually(lambda: _true("checking the drone flies on" in mission.message), "finished, watched")
    v.set(velocity_ned=VelocityNedValue(0.0, 0.0, 14.0))
    await streaming_until_done(v, mission)
    assert mission.status is OpStatus.failed and mission.message.startswith(
        "the drone is falling at 14.0 m/s"
    )

    v = drone()  # came down without a landing item
    at(v, HOME[0], HOME[1], 30.0, armed=True, in_air=True)
    mission = await mgr.start(v, MissionTracker(lands=False), _noop, {})
    await eventually(lambda: _true(mission.message.startswith("item")), "the mission runs")
    at(v, HOME[0], HOME[1], 0.0, armed=True, in_air=False)
    await mgr.wait(mission, cap_s=5)
    assert (
        mission.status is OpStatus.failed and "came down, which the operation did not plan" in mission.message
    )

    v = drone()  # a mission that lands lands; a finished one that flies on succeeds
    at(v, HOME[0], HOME[1], 30.0, armed=True, in_air=True)
    mission = await mgr.start(v, MissionTracker(lands=True), _noop, {})
    await eventually(lambda: _true(mission.message.startswith("item")), "the mission runs")
    at(v, HOME[0], HOME[1], 0.0, armed=False, in_air=False)
    v.mission_done = True
    await streaming_until_done(v, mission)
    assert mission.status is OpStatus.succeeded, mission.message

    v = drone()  # a finished mission the autopilot then holds (PX4 switches to Hold) succeeds
    at(v, HOME[0], HOME[1], 30.0, armed=True, in_air=True)
    v.set(flight_mode="AUTO.MISSION", mission_progress=MissionProgressValue(3, 3))
    mission = await mgr.start(v, MissionTracker(), _noop, {})
    await eventually(lambda: _true(mission.message == "item 3 of 3"), "the mission runs")
    v.set(flight_mode="AUTO.LOITER")
    v.mission_done = True
    await streaming_until_done(v, mission)
    assert mission.status is OpStatus.succeeded, mission.message

    v = drone()  # a landing's own disarm heard before its landed state is no disarm in the air
    at(v, HOME[0], HOME[1], 10.0, armed=True, in_air=True)
    land = await mgr.start(v, LandingTracker(kind="land"), _noop, {})
    await eventually(lambda: _true("above home" in land.message), "the landing runs")
    at(v, HOME[0], HOME[1], 0.4, armed=False, in_air=True)
    await eventually(lambda: _true("0.4 m above home" in land.message), "a poll after the disarm")
    assert not land.finished, land.message  # that poll saw the disarm before the landed state
    at(v, HOME[0], HOME[1], 0.0, armed=False, in_air=False)
    await streaming_until_done(v, land)
    assert land.status is OpStatus.succeeded, land.message

    v = drone()  # a crash the autopilot reports during a landing
    at(v, HOME[0], HOME[1], 10.0, armed=True, in_air=True)
    land = await mgr.start(v, LandingTracker(kind="return_to_launch"), _noop, {})
    await eventually(lambda: _true("above home" in land.message), "the return runs")
    v.telemetry.add_status_text("critical", "Crash: Disarming")
    await mgr.wait(land, cap_s=5)
    assert land.status is OpStatus.failed
    assert land.message == "the autopilot reported a crash or failsafe; the autopilot said: Crash: Disarming"


async def test_an_answer_that_waited_through_interruptions_says_so(settings: Settings) -> None:
    """The sidecar restarted twice during a goto: the final answer says so (it explains the wait)."""
    from gateway.link.contract import ConnectionState

    v = drone()
    at(v, HOME[0], HOME[1], 10.0, armed=True, in_air=True)
    mgr = OperationManager(settings)
    lat, lon = geo.offset_position(HOME[0], HOME[1], 60.0, 0.0)
    op = await mgr.start(v, GotoTracker(lat, lon, 10.0, 2.0, kind="goto"), _noop, {})
    for _ in range(2):
        v.state = ConnectionState.CONNECTING
        await eventually(lambda: _true(op.message.startswith("connection interrupted")), "interrupted")
        v.state = ConnectionState.READY
        await eventually(lambda: _true(not op.message.startswith("connection interrupted")), "resumed")
    at(v, lat, lon, 10.0)
    await mgr.wait(op, cap_s=5.0)
    assert op.status is OpStatus.succeeded
    assert "interrupted twice while it ran: connecting; connecting" in op.message, op.message
    await mgr.stop()
