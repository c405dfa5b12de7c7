"""A pilot or ground station always wins: the real Gateway (Commander, policy, operations, store) over
fake drones whose HEARTBEAT mode the test switches as a pilot would (the fake reports the mode the last
command brought, like an autopilot does)."""

from __future__ import annotations

import asyncio
import contextlib
import time
from collections.abc import Callable
from pathlib import Path

import pytest

from gateway.errors import SafetyRefusal
from gateway.fleet.dialects import ARDUPILOT, PX4_DIALECT
from gateway.fleet.policy.takeover import likely_cause
from gateway.link.contract import ConnectionState, GroundCommand
from gateway.runtime import Gateway
from tests.fakes import FakeVehicle, fake, fake_gateway, position_value, spread, unit_settings
from tests.fleet._util import AGENT, OPERATOR, at
from tests.helpers.timing import scaled


async def until(check: Callable[[], object], what: str, within_s: float = 10.0) -> None:
    deadline = asyncio.get_running_loop().time() + scaled(within_s)
    while not check():
        if asyncio.get_running_loop().time() > deadline:
            raise AssertionError(f"timed out waiting for {what}")
        await asyncio.sleep(0.02)


async def flying_goto(gateway: Gateway, drone: str = "d1") -> str:
    """``drone`` in the air and on a long goto (slow), seen in GUIDED by the watch; the goto's id."""
    d = fake(gateway, drone)
    c = gateway.commander
    took = await c.takeoff(AGENT, drone, 10.0)
    assert (await c.wait(took.operation_id, 10)).status == "succeeded"
    d.speed = 2.0
    lat, lon = at(400, 0, d.home_ll)
    op = await c.goto(AGENT, drone, lat, lon, 10.0)
    ops = gateway.operations
    assert ops is not None
    await until(lambda: (e := ops.expected(drone)) is not None and e.seen, "the goto seen in GUIDED")
    return op.operation_id


def goto_target(gateway: Gateway, goto_id: str) -> tuple[float, float]:
    """Where the running goto ``goto_id`` flies to."""
    ops = gateway.operations
    assert ops is not None
    params = ops.get(goto_id).params
    return params["lat_deg"], params["lon_deg"]


def pilot_switch(d: FakeVehicle, mode: str, said: str | None = None) -> None:
    if said:
        d.telemetry.add_status_text("critical", said)
    d.set(flight_mode=mode)


async def test_a_pilot_switch_mid_goto_ends_it_locks_the_drone_and_an_operator_releases_it(
    gateway: Gateway,
) -> None:
    c = gateway.commander
    d1 = fake(gateway, "d1")
    goto_id = await flying_goto(gateway)
    waiter = asyncio.create_task(c.wait(goto_id, 60))
    await asyncio.sleep(0.3)
    assert not waiter.done()
    pilot_switch(d1, "LOITER")
    view = await asyncio.wait_for(waiter, scaled(5))  # the waiting call returns at once
    assert view.status == "interrupted"
    assert "from GUIDED to LOITER: a pilot or another ground station took control" in view.message
    arrival = await c.arrival(AGENT, "d1")
    assert arrival.status == "interrupted" and "GUIDED to LOITER" in arrival.message

    sent_before = len(d1.sent)
    with pytest.raises(SafetyRefusal) as refused:
        await c.move_relative(AGENT, "d1", 10.0, 0.0)
    assert refused.value.rule == "taken_over"
    assert "taken over in LOITER" in refused.value.message
    assert "DELETE /api/v1/vehicles/d1/takeover" in refused.value.message
    for attempt in (c.hold(AGENT, "d1"), c.land(AGENT, "d1"), c.set_mode(AGENT, "d1", "GUIDED")):
        with pytest.raises(SafetyRefusal):
            await attempt
    assert len(d1.sent) == sent_before  # nothing reached the drone: the pilot keeps LOITER
    assert d1.telemetry.flight_mode is not None and d1.telemetry.flight_mode.value == "LOITER"
    assert (await c.arrival(AGENT, "d1")).status == "interrupted"  # read tools still answer

    store = gateway.require_store()
    assert [t.scope for t in await store.list_takeovers()] == ["d1"]
    audit = await store.list_audit(vehicle_id="d1")
    row = next(r for r in audit if r.action == "takeover")
    assert row.source == "gateway" and row.principal == "autopilot" and row.operation_id == goto_id
    assert row.arguments["to_mode"] == "LOITER"
    assert "taken over" in (gateway.locks.reason_for("d1") or "")

    with pytest.raises(SafetyRefusal):  # agents cannot release
        await c.release(AGENT, "d1")
    released = await c.release(OPERATOR, "d1")
    assert released.was_locked and await store.list_takeovers() == []
    moved = await c.move_relative(AGENT, "d1", 5.0, 0.0)
    assert moved.status == "running"


async def test_another_ground_station_moving_the_target_in_the_same_mode_ends_the_goto(
    gateway: Gateway,
) -> None:
    """PX4 flies gotos in Hold, so QGroundControl's Pause (a reposition to where the drone is) leaves the
    mode as it was: the autopilot's own target (POSITION_TARGET_GLOBAL_INT) tells. Reports of the goto's
    own target change nothing."""
    d1 = fake(gateway, "d1")
    goto_id = await flying_goto(gateway)
    ops = gateway.operations
    assert ops is not None
    goto = ops.get(goto_id)
    lat, lon = goto_target(gateway, goto_id)
    loop = asyncio.get_running_loop()
    until_s = loop.time() + 3.0
    while loop.time() < until_s:  # its own target, reported well after the command: not a takeover
        d1.target = (lat, lon, time.monotonic())
        await asyncio.sleep(0.1)
    assert gateway.locks.takeover_for("d1") is None and not goto.finished
    waiter = asyncio.create_task(gateway.commander.wait(goto_id, 60))
    here = d1.telemetry.position
    assert here is not None

    def paused() -> bool:
        d1.target = (here.value.lat_deg, here.value.lon_deg, time.monotonic())
        return waiter.done()

    await until(paused, "the goto interrupted")
    view = waiter.result()
    assert view.status == "interrupted", view
    assert "left the gateway's target while staying in GUIDED" in view.message, view.message
    assert "another ground station repositioned or paused it" in view.message
    taken = gateway.locks.takeover_for("d1")
    assert taken is not None and "the autopilot left the gateway's target" in taken.reason


async def test_a_switch_whose_target_shows_before_its_heartbeat_is_named_as_the_mode_change(
    gateway: Gateway,
) -> None:
    """A second ground station's RETURN moves the autopilot's target at once (reported at 5 Hz) while the
    HEARTBEAT that shows the new mode comes up to a second later: the watch waits for a HEARTBEAT heard
    after the move, and the takeover names both modes, not a reposition."""
    d1 = fake(gateway, "d1")
    goto_id = await flying_goto(gateway)
    lat, lon = goto_target(gateway, goto_id)
    ops = gateway.operations
    assert ops is not None

    def flies_the_goto() -> bool:
        d1.target = (lat, lon, time.monotonic())
        return (e := ops.expected("d1")) is not None and e.target_adopted

    await until(flies_the_goto, "the autopilot reporting the goto's target")
    waiter = asyncio.create_task(gateway.commander.wait(goto_id, 60))
    d1.heartbeat_at = time.monotonic()  # the last HEARTBEAT, from before the switch
    home = d1.home_ll
    loop = asyncio.get_running_loop()
    until_s = loop.time() + 1.0
    while loop.time() < until_s:  # the return's target, reported while no newer HEARTBEAT came
        d1.target = (home[0], home[1], time.monotonic())
        await asyncio.sleep(0.05)
    pilot_switch(d1, "RTL")
    d1.heartbeat_at = None  # the HEARTBEAT showing RTL is heard

    def returned() -> bool:
        d1.target = (home[0], home[1], time.monotonic())
        return waiter.done()

    await until(returned, "the goto interrupted")
    view = waiter.result()
    assert view.status == "interrupted", view
    assert "the autopilot switched from GUIDED to RTL" in view.message, view.message


async def test_a_target_from_before_the_goto_handed_over_late_is_not_a_takeover(gateway: Gateway) -> None:
    """A loaded link or gateway can hand over the autopilot's reports long after they were said: a target
    far from the goto's, heard well after the send but before the autopilot was ever seen flying the
    goto's own target, is the previous one, not another ground station's."""
    d1 = fake(gateway, "d1")
    goto_id = await flying_goto(gateway)
    ops = gateway.operations
    assert ops is not None
    goto = ops.get(goto_id)
    here = d1.telemetry.position
    assert here is not None
    loop = asyncio.get_running_loop()
    until_s = loop.time() + 3.0
    while loop.time() < until_s:  # the previous target, reported late and again and again
        d1.target = (here.value.lat_deg, here.value.lon_deg, time.monotonic())
        await asyncio.sleep(0.1)
    assert gateway.locks.takeover_for("d1") is None and not goto.finished


async def test_a_goto_target_flown_only_between_two_watch_ticks_then_replaced_is_a_takeover(
    gateway: Gateway,
) -> None:
    """Another ground station can replace the goto's target within a second of the send, before the
    watch ever saw the autopilot report the goto's own target as its latest: a report of it among the
    recent ones is enough to know the autopilot flew this leg, so the move away is a takeover."""
    d1 = fake(gateway, "d1")
    goto_id = await flying_goto(gateway)
    ops = gateway.operations
    assert ops is not None
    goto = ops.get(goto_id)
    d1.target_history.append((goto.params["lat_deg"], goto.params["lon_deg"], time.monotonic()))
    waiter = asyncio.create_task(gateway.commander.wait(goto_id, 60))
    here = d1.telemetry.position
    assert here is not None

    def replaced() -> bool:
        d1.target = (here.value.lat_deg, here.value.lon_deg, time.monotonic())
        return waiter.done()

    await until(replaced, "the goto interrupted")
    assert waiter.result().status == "interrupted", waiter.result()
    assert gateway.locks.takeover_for("d1") is not None


async def reports_for(d: FakeVehicle, lat: float, lon: float, seconds: float) -> None:
    """The autopilot reports (lat, lon) as its target at 5 Hz for ``seconds``."""
    loop = asyncio.get_running_loop()
    until_s = loop.time() + seconds
    while loop.time() < until_s:
        d.target = (lat, lon, time.monotonic())
        await asyncio.sleep(0.2)


async def test_a_pilot_moving_the_target_of_a_hold_in_the_same_mode_is_a_takeover(gateway: Gateway) -> None:
    """The agent held the drone (GUIDED): the autopilot reports the hold's own target and nothing
    happens; a pilot's SET_POSITION_TARGET_GLOBAL_INT elsewhere, still in GUIDED, is a takeover and the
    agent's next move is refused."""
    c = gateway.commander
    d1 = fake(gateway, "d1")
    took = await c.takeoff(AGENT, "d1", 10.0)
    assert (await c.wait(took.operation_id, 10)).status == "succeeded"
    await c.hold(AGENT, "d1")
    held = d1.commanded
    assert held is not None
    await reports_for(d1, held[0], held[1], 2.5)  # its own target, well after the command: no takeover
    assert gateway.locks.takeover_for("d1") is None
    elsewhere = at(250, 0, held[:2])
    await until(lambda: _reported(d1, *elsewhere) and gateway.locks.takeover_for("d1") is not None,
                "the hold taken over")  # fmt: skip
    taken = gateway.locks.takeover_for("d1")
    assert taken is not None and "the autopilot left the gateway's target" in taken.reason
    with pytest.raises(SafetyRefusal) as refused:
        await c.move_relative(AGENT, "d1", 10.0, 0.0)
    assert refused.value.rule == "taken_over"


def _reported(d: FakeVehicle, lat: float, lon: float) -> bool:
    d.target = (lat, lon, time.monotonic())
    return True


@pytest.mark.parametrize("watched", [True, False], ids=["watched", "arrived-before-the-watch-looked"])
async def test_a_pilot_moving_the_target_after_a_goto_arrived_is_a_takeover(
    gateway: Gateway, watched: bool
) -> None:
    """A goto that arrived leaves the drone at its target in GUIDED: a move of the autopilot's target
    away from it is a takeover as during the goto. The same when the goto arrived before the watch
    looked at it (it cannot look while the drone's command lock is held: a loaded gateway, a short leg)."""
    c = gateway.commander
    d1 = fake(gateway, "d1")
    took = await c.takeoff(AGENT, "d1", 10.0)
    assert (await c.wait(took.operation_id, 10)).status == "succeeded"
    assert gateway.operations is not None
    lat, lon = at(30, 0, d1.home_ll)
    op = await c.goto(AGENT, "d1", lat, lon, 10.0)
    async with contextlib.nullcontext() if watched else gateway.operations.command_lock("d1"):
        await reports_for(d1, lat, lon, 0.4)
        assert (await c.wait(op.operation_id, 10)).status == "succeeded"
    await reports_for(d1, lat, lon, 2.0)
    assert gateway.locks.takeover_for("d1") is None
    elsewhere = at(200, 100, d1.home_ll)
    await until(lambda: _reported(d1, *elsewhere) and gateway.locks.takeover_for("d1") is not None,
                "the arrived goto taken over")  # fmt: skip


async def test_the_target_of_a_hold_before_its_report_is_not_a_takeover(gateway: Gateway) -> None:
    """Right after a hold the autopilot can still report the goto it replaced: never a takeover, however
    long that report is handed over late, until it has reported the hold's own target."""
    d1 = fake(gateway, "d1")
    goto_id = await flying_goto(gateway)
    goto = gateway.operations.get(goto_id) if gateway.operations else None
    assert goto is not None
    await gateway.commander.hold(AGENT, "d1")
    await reports_for(d1, goto.params["lat_deg"], goto.params["lon_deg"], 2.5)
    assert gateway.locks.takeover_for("d1") is None


async def test_a_ground_stations_command_on_the_relay_is_a_takeover_one_before_the_gateways_is_not(
    gateway: Gateway,
) -> None:
    d1 = fake(gateway, "d1")
    before = time.monotonic()
    goto_id = await flying_goto(gateway)
    d1.ground_commands.append(GroundCommand(250, "MISSION_SET_CURRENT", before))  # before the goto
    await asyncio.sleep(0.6)  # several polls of the watch
    assert gateway.locks.takeover_for("d1") is None
    waiter = asyncio.create_task(gateway.commander.wait(goto_id, 60))
    d1.ground_commands.append(GroundCommand(250, "COMMAND_LONG MAV_CMD_DO_CHANGE_SPEED", time.monotonic()))
    view = await asyncio.wait_for(waiter, scaled(5))
    assert view.status == "interrupted", view
    assert "ground station system 250 sent COMMAND_LONG MAV_CMD_DO_CHANGE_SPEED" in view.message, view.message
    taken = gateway.locks.takeover_for("d1")
    assert taken is not None and "taken over in GUIDED" in taken.reason


async def test_a_failsafe_is_named_in_the_autopilots_words(gateway: Gateway) -> None:
    d1 = fake(gateway, "d1")
    goto_id = await flying_goto(gateway)
    pilot_switch(d1, "RTL", said="Battery Failsafe")
    view = await gateway.commander.wait(goto_id, 10)
    assert view.status == "interrupted"
    assert "from GUIDED to RTL: battery failsafe (autopilot says: 'Battery Failsafe')" in view.message


async def test_the_gateways_own_commands_are_never_a_takeover(gateway: Gateway) -> None:
    c = gateway.commander
    goto_id = await flying_goto(gateway)
    mode = await c.set_mode(AGENT, "d1", "BRAKE")  # the gateway's own mode change supersedes the goto
    assert mode.superseded_operation == goto_id
    await asyncio.sleep(0.6)  # several polls of the watch
    landing = await c.land(AGENT, "d1")
    assert (await c.wait(landing.operation_id, 20)).status == "succeeded"
    assert gateway.locks.takeover_for("d1") is None
    ops = gateway.operations
    assert ops is not None and (await c.wait(goto_id, 1)).status == "superseded"


async def test_an_operator_still_commands_a_taken_over_drone_and_a_restart_keeps_the_lock(
    tmp_path: Path,
) -> None:
    settings = unit_settings(tmp_path, mcp_wait_cap_s=10.0)
    async with fake_gateway(settings, spread(1)) as gateway:
        d1 = fake(gateway, "d1")
        goto_id = await flying_goto(gateway)
        pilot_switch(d1, "LOITER")
        assert (await gateway.commander.wait(goto_id, 10)).status == "interrupted"
        rtl = await gateway.commander.return_to_launch(OPERATOR, "d1")  # operators stay allowed
        assert rtl.status == "running"
    async with fake_gateway(settings, spread(1)) as gateway:
        taken = gateway.locks.takeover_for("d1")
        assert taken is not None and "LOITER" in taken.reason
        with pytest.raises(SafetyRefusal):
            await gateway.commander.takeoff(AGENT, "d1", 10.0)


async def test_a_formation_with_a_taken_over_drone_stops_and_holds_the_others(tmp_path: Path) -> None:
    async with fake_gateway(unit_settings(tmp_path, mcp_wait_cap_s=10.0), spread(3)) as gateway:
        c = gateway.commander
        rise = await c.fleet_takeoff(AGENT, ["d1", "d2", "d3"], 10.0)
        assert (await c.wait_fleet(rise.operation_id, 20)).status == "succeeded"
        drones = [fake(gateway, d) for d in ("d1", "d2", "d3")]
        for d in drones:
            d.speed = 2.0
        lat, lon = at(300, 0)
        formed = await c.formation_goto(AGENT, ["d1", "d2", "d3"], "line", 15.0, lat, lon)
        ops = gateway.operations
        assert ops is not None
        await until(
            lambda: all(
                (e := ops.expected(d.id)) is not None and e.seen and e.kind == "formation" for d in drones
            ),
            "every drone on its formation leg",
        )
        held_before = [sum(1 for s in d.sent if s[0] == "hold") for d in drones]
        pilot_switch(drones[1], "POSHOLD")
        view = await c.wait_fleet(formed.operation_id, 20)
        assert view.status == "aborted"
        members = {m["drone_id"]: m for m in view.drones}
        assert members["d2"]["status"] == "interrupted" and "GUIDED to POSHOLD" in members["d2"]["message"]
        assert members["d1"]["status"] == "held" and members["d3"]["status"] == "held"
        held_after = [sum(1 for s in d.sent if s[0] == "hold") for d in drones]
        assert held_after[1] == held_before[1]  # the taken-over drone heard nothing
        assert held_after[0] > held_before[0] and held_after[2] > held_before[2]
        assert gateway.locks.takeover_for("d2") is not None


async def test_a_fleet_command_names_a_taken_over_drone_as_taken_over_even_while_its_link_is_down(
    tmp_path: Path,
) -> None:
    """The pilot's word first, as for one drone: the agent learns who has the drone, not only that its
    link dropped meanwhile (it would retry once the link is back)."""
    async with fake_gateway(unit_settings(tmp_path, mcp_wait_cap_s=10.0), spread(2)) as gateway:
        c = gateway.commander
        rise = await c.fleet_takeoff(AGENT, ["d1", "d2"], 10.0)
        assert (await c.wait_fleet(rise.operation_id, 20)).status == "succeeded"
        d2 = fake(gateway, "d2")
        pilot_switch(d2, "POSHOLD")
        await until(lambda: gateway.locks.takeover_for("d2") is not None, "the takeover seen")
        d2.state = ConnectionState.CONNECTING
        for attempt in (c.fleet_hold, c.fleet_land):
            with pytest.raises(SafetyRefusal) as refused:
                await attempt(AGENT, ["d2"])
            assert refused.value.rule == "taken_over", refused.value.message
            assert "POSHOLD" in refused.value.message
        with pytest.raises(SafetyRefusal) as refused:
            await c.fleet_takeoff(AGENT, ["d2"], 12.0)
        assert refused.value.rule == "taken_over", refused.value.message


def test_each_dialect_names_the_modes_its_commands_bring() -> None:
    assert ARDUPILOT.commanded_modes("goto") == {"GUIDED"}
    assert ARDUPILOT.commanded_modes("mission") == {"AUTO"}
    assert PX4_DIALECT.commanded_modes("goto") == {"AUTO.LOITER"}
    assert "AUTO.LOITER" not in PX4_DIALECT.commanded_modes("mission")
    assert "AUTO.LOITER" in PX4_DIALECT.commanded_modes("mission", done=True)
    assert PX4_DIALECT.native_mode((3 << 16) | (0 << 24)) == "POSCTL"
    assert PX4_DIALECT.native_mode((4 << 16) | (5 << 24)) == "AUTO.RTL"
    assert ARDUPILOT.native_mode(5) == "LOITER"


def test_the_cause_comes_from_what_the_autopilot_said() -> None:
    assert likely_cause("LOITER", []) == ("a pilot or another ground station took control", None)
    assert likely_cause("RTL", ["Radio Failsafe - Continuing Auto"])[0] == "radio (RC) failsafe"
    assert likely_cause("LAND", ["EKF variance"])[0] == "EKF / navigation failsafe"
    assert "failsafe" in likely_cause("RTL", [])[0]


async def test_after_a_restart_monitor_and_arrival_tell_what_the_flying_drone_does(tmp_path: Path) -> None:
    settings = unit_settings(tmp_path, mcp_wait_cap_s=10.0)
    async with fake_gateway(settings, spread(1)) as gateway:
        goto_id = await flying_goto(gateway)
    flying = spread(1)
    lat, lon = at(100, 0, flying[0].home_ll)
    flying[0].set(armed=True, in_air=True, landed_state="IN_AIR", flight_mode="GUIDED",
                  position=position_value(lat, lon, 10.0))  # fmt: skip
    async with fake_gateway(settings, flying) as gateway:
        view = await gateway.commander.monitor(AGENT, "d1")
        assert view.operation_id == goto_id and view.status == "interrupted", view
        assert (
            "while the operation was running; now: mode GUIDED, in the air at 10.0 m above home"
            in view.message
        )
        assert "m from the goto's target" in view.message
        arrival = await gateway.commander.arrival(AGENT, "d1")
        assert arrival.operation_id == goto_id and arrival.status == "interrupted" and not arrival.arrived
        assert arrival.distance_m is not None and arrival.distance_m > 250
        # the mode watch is armed again for it: a pilot's later switch is a takeover as before
        ops = gateway.operations
        assert ops is not None
        await until(lambda: (e := ops.expected("d1")) is not None and e.seen, "the watch armed again")
        pilot_switch(fake(gateway, "d1"), "LOITER")
        await until(lambda: gateway.locks.takeover_for("d1") is not None, "the takeover after the restart")
        taken = gateway.locks.takeover_for("d1")
        assert taken is not None and "left GUIDED" in taken.reason, taken
        with pytest.raises(SafetyRefusal):
            await gateway.commander.move_relative(AGENT, "d1", 10.0, 0.0)


async def test_a_drone_found_flying_in_a_mode_the_gateway_did_not_command_is_watched_in_it(
    tmp_path: Path,
) -> None:
    """Found in LOITER after a restart whose last command was a goto (GUIDED): judged by LOITER; the
    gateway's own next command replaces that watch, a pilot's switch away from LOITER is a takeover."""
    settings = unit_settings(tmp_path, mcp_wait_cap_s=10.0)
    async with fake_gateway(settings, spread(1)) as gateway:
        await flying_goto(gateway)
    flying = spread(1)
    flying[0].set(armed=True, in_air=True, landed_state="IN_AIR", flight_mode="LOITER",
                  position=position_value(*flying[0].home_ll, 10.0))  # fmt: skip
    async with fake_gateway(settings, flying) as gateway:
        ops = gateway.operations
        assert ops is not None
        await until(lambda: ops.expected("d1") is not None, "the watch armed")
        exp = ops.expected("d1")
        assert exp is not None and exp.modes == {"LOITER"} and exp.kind == "found flying in LOITER"
        pilot_switch(fake(gateway, "d1"), "ALT_HOLD")
        await until(lambda: gateway.locks.takeover_for("d1") is not None, "the takeover")


async def test_a_pilot_switch_right_after_a_goto_in_the_same_mode_is_a_takeover(gateway: Gateway) -> None:
    """A goto sent while the drone already flies GUIDED brings no mode change to see: a pilot's switch
    before the watch first looks is still a takeover."""
    c = gateway.commander
    d1 = fake(gateway, "d1")
    took = await c.takeoff(AGENT, "d1", 10.0)
    assert (await c.wait(took.operation_id, 10)).status == "succeeded"
    d1.speed = 2.0
    lat, lon = at(400, 0, d1.home_ll)
    op = await c.goto(AGENT, "d1", lat, lon, 10.0)
    pilot_switch(d1, "BRAKE")  # before the watch's first poll
    view = await asyncio.wait_for(c.wait(op.operation_id, 60), scaled(5))
    assert view.status == "interrupted"
    assert "GUIDED to BRAKE" in view.message
    with pytest.raises(SafetyRefusal) as refused:
        await c.move_relative(AGENT, "d1", 10.0, 0.0)
    assert refused.value.rule == "taken_over"


async def test_a_drone_landing_while_its_takeover_is_stored_ends_the_goto_interrupted(
    gateway: Gateway, monkeypatch: pytest.MonkeyPatch
) -> None:
    """ArduCopter's LOITER without RC throttle sinks: after a pilot's switch the drone may be down before
    the takeover's lock is in the database (a busy disk). The goto still ends `interrupted` naming the
    switch, never `failed` for the landing the switch caused."""
    d1 = fake(gateway, "d1")
    goto_id = await flying_goto(gateway)
    store = gateway.require_store()
    storing, stored = asyncio.Event(), asyncio.Event()
    save_takeover = store.save_takeover

    async def slow_save_takeover(*args: object, **kwargs: object) -> None:
        storing.set()
        await stored.wait()
        await save_takeover(*args, **kwargs)  # type: ignore[arg-type]

    monkeypatch.setattr(store, "save_takeover", slow_save_takeover)
    ops = gateway.operations
    assert ops is not None
    tracker = ops.tracker(goto_id)
    assert tracker is not None
    polls = 0
    poll = tracker.poll

    async def counted(vehicle: object) -> object:
        nonlocal polls
        polls += 1
        return await poll(vehicle)  # type: ignore[arg-type]

    monkeypatch.setattr(tracker, "poll", counted)
    waiter = asyncio.create_task(gateway.commander.wait(goto_id, 60))
    pilot_switch(d1, "LOITER")
    await asyncio.wait_for(storing.wait(), scaled(5))
    d1.set(in_air=False, landed_state="ON_GROUND")  # down, still armed, the lock not yet stored
    landed_at = polls
    await until(lambda: polls >= landed_at + 3 or waiter.done(), "the goto's monitor seeing it landed")
    assert not waiter.done(), waiter.result()  # ended before its takeover was stored: as failed
    stored.set()
    view = await asyncio.wait_for(waiter, scaled(5))
    assert view.status == "interrupted", view
    assert "from GUIDED to LOITER: a pilot or another ground station took control" in view.message
    assert [t.scope for t in await store.list_takeovers()] == ["d1"]
