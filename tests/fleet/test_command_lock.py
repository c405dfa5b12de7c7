"""Every command to one drone goes under its command lock, and the takeoff guard is one rule for every
verb: the real Gateway (Commander, policy, operations, store) over the one fake drone.

A command is held in the middle of being sent with the fake's ``barrier`` (the takeoff waits there
until the test releases it), so what the lock does is seen without timing anything."""

from __future__ import annotations

import asyncio

import pytest

from gateway.errors import SafetyRefusal
from gateway.fleet.missions.mission import MissionItem
from gateway.fleet.policy.caller import Caller
from gateway.runtime import Gateway
from tests.fakes import FakeVehicle, fake
from tests.fleet._util import AGENT, OPERATOR
from tests.helpers.timing import scaled


def commands(vehicle: FakeVehicle) -> list[str]:
    """The commands that reached the drone's link, in order (sent or still being sent)."""
    return [name for _t, name, _args in vehicle.log]


async def let_others_run() -> None:
    """Let every task that is ready run until it waits on something (a lock, the barrier)."""
    for _ in range(5):
        await asyncio.sleep(0)


async def takeoff_held_mid_send(
    gateway: Gateway, caller: Caller
) -> tuple[asyncio.Task[object], asyncio.Barrier]:
    """d1's takeoff, stopped while its command is being sent (inside the command lock)."""
    d1 = fake(gateway, "d1")
    barrier = d1.barrier = asyncio.Barrier(2)
    task: asyncio.Task[object] = asyncio.create_task(gateway.commander.takeoff(caller, "d1", 60.0))
    loop = asyncio.get_running_loop()
    deadline = loop.time() + scaled(10)
    while "takeoff" not in commands(d1):
        assert loop.time() < deadline, "the takeoff never reached the drone"
        await asyncio.sleep(0.01)
    assert gateway.commander.operations.command_lock("d1").locked()
    return task, barrier


async def release(gateway: Gateway, barrier: asyncio.Barrier) -> None:
    fake(gateway, "d1").barrier = None
    await asyncio.wait_for(barrier.wait(), scaled(5))


async def test_an_operator_hold_waits_for_the_command_being_sent_and_then_has_the_last_word(
    gateway: Gateway,
) -> None:
    commander = gateway.commander
    takeoff, barrier = await takeoff_held_mid_send(gateway, OPERATOR)
    hold = asyncio.create_task(commander.hold(OPERATOR, "d1", "operator hold"))
    await let_others_run()
    assert commands(fake(gateway, "d1")) == ["takeoff"], "the hold overtook a command still being sent"
    # another drone's commands do not wait for d1's
    await asyncio.wait_for(commander.set_speed(OPERATOR, "d2", 5.0), scaled(5))
    assert not takeoff.done() and not hold.done()

    await release(gateway, barrier)
    started = await asyncio.wait_for(takeoff, scaled(5))
    held = await asyncio.wait_for(hold, scaled(5))
    assert commands(fake(gateway, "d1")) == ["takeoff", "hold"]
    assert held.superseded_operation == started.operation_id  # type: ignore[attr-defined]
    assert commander.operation(started.operation_id).status == "superseded"  # type: ignore[attr-defined]


async def test_an_agent_command_racing_a_takeoff_still_being_sent_is_refused_inside_the_lock(
    gateway: Gateway,
) -> None:
    """set_speed asked while the takeoff command is on its way: no operation exists yet, so only the
    guard run inside the lock, after the takeoff was sent, can refuse it."""
    takeoff, barrier = await takeoff_held_mid_send(gateway, AGENT)
    speed = asyncio.create_task(gateway.commander.set_speed(AGENT, "d1", 5.0))
    await let_others_run()
    assert not speed.done() and commands(fake(gateway, "d1")) == ["takeoff"]

    await release(gateway, barrier)
    await asyncio.wait_for(takeoff, scaled(5))
    with pytest.raises(
        SafetyRefusal, match=r"takeoff_in_progress: d1 is still taking off.*set_max_speed was not sent"
    ):
        await asyncio.wait_for(speed, scaled(5))
    assert commands(fake(gateway, "d1")) == ["takeoff"]


async def test_kill_never_waits_for_a_command_being_sent(gateway: Gateway) -> None:
    commander = gateway.commander
    d1 = fake(gateway, "d1")
    d1.arm_delay_s = 3600.0  # an arming the autopilot keeps refusing: the takeoff's send lasts and lasts
    takeoff = asyncio.create_task(commander.takeoff(OPERATOR, "d1", 20.0))
    lock = commander.operations.command_lock("d1")
    await let_others_run()
    assert lock.locked()
    try:
        killed = await asyncio.wait_for(commander.kill(OPERATOR, "d1", confirmed=True), scaled(5))
        assert killed.action == "kill" and commands(d1) == ["kill"]
        assert lock.locked() and not takeoff.done()
    finally:
        takeoff.cancel()
        await asyncio.gather(takeoff, return_exceptions=True)
    assert not lock.locked()


async def test_during_a_takeoff_agents_may_only_hold_land_or_return(gateway: Gateway) -> None:
    """The takeoff guard's one rule: every agent command that acts on the drone waits for the climb,
    except the safety actions (hold, land, RTL, kill, disarm)."""
    commander = gateway.commander
    d1 = fake(gateway, "d1")
    d1.speed = 2.0  # a slow climb: every call below lands inside it
    started = await commander.takeoff(AGENT, "d1", 60.0)
    wp = MissionItem(lat=d1.home_ll[0] + 2e-4, lon=d1.home_ll[1], alt_rel_m=20)
    refused = {
        "set_max_speed": commander.set_speed(AGENT, "d1", 5.0),
        "set_parameter WPNAV_SPEED": commander.set_param(AGENT, "d1", "WPNAV_SPEED", 500.0),
        "set_flight_mode GUIDED": commander.set_mode(AGENT, "d1", "GUIDED"),
        "set_flight_mode MISSION": commander.set_mode(AGENT, "d1", "AUTO"),
        "upload_mission": commander.upload_mission(AGENT, "d1", [wp]),
        "clear_mission": commander.clear_mission(AGENT, "d1"),
        "arm_drone": commander.arm(AGENT, "d1"),
        "set_yaw": commander.set_yaw(AGENT, "d1", 90.0),
    }
    for action, call in refused.items():
        with pytest.raises(SafetyRefusal, match=f"takeoff_in_progress: .*; {action} was not sent"):
            await call
    assert commands(d1) == ["takeoff"]
    assert commander.operation(started.operation_id).status == "running"

    # an operator may change how the drone flies mid-climb; an agent's RTL (a safety action) ends it
    await commander.set_speed(OPERATOR, "d1", 5.0)
    returning = await commander.set_mode(AGENT, "d1", "RTL")
    assert returning.superseded_operation == started.operation_id
    assert commands(d1) == ["takeoff", "speed", "mode"]
