"""An action whose COMMAND_ACK MAVSDK gave up on (its retries spent: a starved autopilot answers late)
counts as run only once the autopilot shows its effect in what it reported after the action was sent: a
arm, disarm or kill by the armed state, a goto or hold by the target the autopilot reports. The real Vehicle
over a link whose calls time out (no sidecar)."""

from __future__ import annotations

import asyncio
import time
from collections.abc import Awaitable
from types import SimpleNamespace
from typing import Any

import pytest

from gateway.config import Settings
from gateway.errors import CommandFailed
from gateway.fleet import geo
from gateway.fleet.vehicles import waits
from gateway.fleet.vehicles.vehicle import Vehicle
from gateway.link.rawlink import MAV_AUTOPILOT_PX4
from gateway.registry.spec import VehicleSpec

HOME = (47.397742, 8.545594)


def timed_out_vehicle(monkeypatch: pytest.MonkeyPatch) -> Vehicle:
    """A PX4 vehicle whose every command's ACK is lost (MAVSDK's TIMEOUT) after a short while."""
    monkeypatch.setattr(waits, "UNACKED_WAIT_S", 1.0)
    v = Vehicle(VehicleSpec(id="px", url="udpin://127.0.0.1:14540"), Settings(_env_file=None))
    v.link.facts.autopilot = MAV_AUTOPILOT_PX4

    async def lost(_what: str, aw: Awaitable[Any], timeout_s: float = 10.0) -> Any:
        await aw
        await asyncio.sleep(0.05)
        raise CommandFailed("disarm on drone 'px' failed: Timeout (TIMEOUT)", result="TIMEOUT")

    async def sent(*_args: object) -> None:
        return None

    action = SimpleNamespace(arm=sent, disarm=sent, kill=sent, goto_location=sent)
    monkeypatch.setattr(v.link, "call", lost)
    session = SimpleNamespace(action=action)
    monkeypatch.setattr(v.link, "require_session", lambda: session)
    monkeypatch.setattr(type(v.link), "system", property(lambda _link: session))
    return v


async def later(delay_s: float, do: Any) -> None:
    await asyncio.sleep(delay_s)
    do()


async def test_a_disarm_whose_ack_is_lost_counts_once_a_later_report_says_disarmed(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    v = timed_out_vehicle(monkeypatch)
    v.telemetry.put("armed", True)
    reported = asyncio.create_task(later(0.3, lambda: v.telemetry.put("armed", False)))
    await v.disarm()  # no CommandFailed: the autopilot says disarmed after the call
    await reported


async def test_a_lost_ack_with_no_effect_shown_still_fails(monkeypatch: pytest.MonkeyPatch) -> None:
    v = timed_out_vehicle(monkeypatch)
    v.telemetry.put("armed", False)  # heard before the kill was sent: not its effect
    v.telemetry.put("armed", True)
    with pytest.raises(CommandFailed, match="TIMEOUT"):
        await v.kill()
    v.telemetry.put("armed", False)
    stale = v.telemetry.armed
    assert stale is not None
    object.__setattr__(stale, "received_at", time.monotonic() - 60)  # disarmed, but said before the call
    with pytest.raises(CommandFailed, match="TIMEOUT"):
        await v.disarm()


async def test_a_goto_whose_ack_is_lost_counts_once_the_autopilot_reports_its_target(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    v = timed_out_vehicle(monkeypatch)
    v.telemetry.put("home", SimpleNamespace(lat_deg=HOME[0], lon_deg=HOME[1], abs_alt_m=488.0, rel_alt_m=0.0))
    monkeypatch.setattr(v, "require_ready", lambda: None)
    lat, lon = geo.offset_position(HOME[0], HOME[1], 100.0, 0.0)
    elsewhere = geo.offset_position(HOME[0], HOME[1], 0.0, 100.0)

    def report(where: tuple[float, float]) -> None:
        v._target = (where[0], where[1], time.monotonic())
        v._targets.append(v._target)

    with pytest.raises(CommandFailed, match="TIMEOUT"):  # it reports another target: not run
        await asyncio.gather(v.goto(lat, lon, 20.0), later(0.2, lambda: report(elsewhere)))
    await asyncio.gather(v.goto(lat, lon, 20.0), later(0.2, lambda: report((lat, lon))))


async def test_an_arm_whose_ack_is_lost_counts_once_a_later_report_says_armed(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    v = timed_out_vehicle(monkeypatch)
    v.telemetry.put("armed", False)
    deadline = asyncio.get_running_loop().time() + 10
    with pytest.raises(CommandFailed, match="TIMEOUT"):  # still disarmed: not run
        await v.arming.arm_by(deadline, ready=True, notify=None)
    reported = asyncio.create_task(later(0.3, lambda: v.telemetry.put("armed", True)))
    assert await v.arming.arm_by(deadline, ready=True, notify=None) is True
    await reported


def takeoff_ready(v: Vehicle, monkeypatch: pytest.MonkeyPatch) -> None:
    """Initialised, parameters fetched, armed already: only the takeoff command's ACK is lost."""

    async def ready(*_args: object) -> bool:
        return True

    async def no_arm_sent(*_args: object, **_kwargs: object) -> bool:
        return False

    async def fetched() -> None:
        return None

    lose_acks = v.link.call

    async def only_the_takeoffs_ack_lost(what: str, aw: Awaitable[Any], timeout_s: float = 10.0) -> Any:
        return await (lose_acks(what, aw, timeout_s) if what == "takeoff" else aw)

    monkeypatch.setattr(v.link, "call", only_the_takeoffs_ack_lost)
    monkeypatch.setattr(v, "wait_initialised", ready)
    monkeypatch.setattr(v.params, "not_fetching", fetched)
    monkeypatch.setattr(v.arming, "arm_by", no_arm_sent)
    session = v.link.require_session()
    session.action.set_takeoff_altitude = session.action.takeoff = session.action.arm
    v.telemetry.put("landed_state", "ON_GROUND")
    v.telemetry.put("armed", True)


async def test_a_takeoff_whose_ack_is_lost_counts_once_px4_shows_its_takeoff_mode(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """A starved PX4 showed AUTO.TAKEOFF while still on the ground when MAVSDK gave up on the ACK: the
    takeoff ran. Staying in the mode it was in (AUTO.LOITER, also one a takeoff ends in) shows nothing."""
    v = timed_out_vehicle(monkeypatch)
    takeoff_ready(v, monkeypatch)
    v.telemetry.put("flight_mode", "AUTO.LOITER")
    heard_again = asyncio.create_task(later(0.2, lambda: v.telemetry.put("flight_mode", "AUTO.LOITER")))
    with pytest.raises(CommandFailed, match="TIMEOUT"):
        await v.takeoff(10.0)
    await heard_again
    switched = asyncio.create_task(later(0.3, lambda: v.telemetry.put("flight_mode", "AUTO.TAKEOFF")))
    await v.takeoff(10.0)  # no CommandFailed: the autopilot switched to its takeoff mode after the call
    await switched
    assert v.on_ground() is True


async def test_a_takeoff_whose_ack_is_lost_counts_once_the_drone_is_in_the_air(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    v = timed_out_vehicle(monkeypatch)
    takeoff_ready(v, monkeypatch)
    v.telemetry.put("flight_mode", "AUTO.TAKEOFF")  # in it before the call: not its effect
    lifted = asyncio.create_task(later(0.3, lambda: v.telemetry.put("landed_state", "TAKING_OFF")))
    await v.takeoff(10.0)
    await lifted
