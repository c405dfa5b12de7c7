"""Ready means armable: a drone is not "ready" while its autopilot still lacks a position estimate, and
an arming refusal comes back with the autopilot's own words, never a bare FAILED (simulator; the same
sequence on real ArduCopter is in tests/real)."""

from __future__ import annotations

import contextlib
from collections.abc import AsyncIterator

import pytest

from gateway.errors import CommandFailed, InvalidArgument
from gateway.fleet.vehicles.registry import Registry
from gateway.fleet.vehicles.vehicle import ConnectionState, Vehicle
from gateway.registry.spec import VehicleSpec
from gateway.registry.store import Store
from tests.helpers.sim import sim_process
from tests.registry.conftest import WAIT_S, fast_settings, wait_until

SPEEDUP = 5.0  # the simulated boot (origin at 20 s, EKF using GPS at 41.6 s) takes ~8 s of wall time


@contextlib.asynccontextmanager
async def one_simulated_drone(
    store: Store, registries: list[Registry], drone_id: str
) -> AsyncIterator[Vehicle]:
    """A simulated drone registered in a started registry (stopped by the ``registries`` fixture)."""
    async with sim_process(1, speedup=SPEEDUP) as sim:
        reg = Registry(fast_settings(), store)
        registries.append(reg)
        await reg.start()
        yield await reg.add(VehicleSpec(id=drone_id, url=sim.urls[0]))


async def test_arming_while_initialising_waits_for_the_position_estimate_and_arms(store, registries) -> None:
    async with one_simulated_drone(store, registries, "ap1") as v:
        seen: list[str] = []

        def initialising() -> bool:
            waiting = v.status()["initialising"]  # what REST and list_drones show
            if waiting and waiting not in seen:
                seen.append(waiting)
            return waiting is not None and "position estimate" in waiting

        # GPS and home are there long before the EKF uses GPS: that span is "initialising", not ready
        await wait_until(
            initialising, within_s=WAIT_S, what="initialising: waiting for the position estimate"
        )
        assert seen[-1] == "waiting for the position estimate (the EKF is not using GPS yet)", seen
        # arming a drone that is still initialising waits for it (capped), then arms: never a bare FAILED
        await v.arm()
        assert v.state == ConnectionState.READY and v.status()["initialising"] is None
        await wait_until(lambda: v.telemetry.fresh("armed") is True, what="armed")
        await v.disarm()
        await wait_until(lambda: v.telemetry.fresh("armed") is False, what="disarmed")


async def test_an_arming_refusal_carries_the_autopilots_words(store, registries) -> None:
    async with one_simulated_drone(store, registries, "ap2") as v:
        await v.wait_for_state(ConnectionState.READY, within_s=WAIT_S)
        await v.set_param("BATT_LOW_VOLT", 30.0)  # above the battery's voltage: arming checks refuse
        with pytest.raises(CommandFailed) as refused:
            await v.arm()
        message = refused.value.message
        assert message.startswith("drone 'ap2' refused to arm: autopilot says 'Arm: Battery 1 low voltage"), (
            message
        )
        assert "GPS FIX_3D" in message or "GPS RTK" in message, message
        assert v.telemetry.fresh("armed") is False


async def test_refusals_carry_the_autopilots_words_or_what_the_drone_was_doing(store, registries) -> None:
    """Every refused command says why: the autopilot's texts, or (when it gave none) the drone's state;
    never a bare "Failed (FAILED)". Arming at once after "ready" succeeds."""
    async with one_simulated_drone(store, registries, "ap3") as v:
        await v.wait_for_state(ConnectionState.READY, within_s=WAIT_S)
        with pytest.raises(CommandFailed, match=r"drone 'ap3' has no mission to start; upload one first"):
            await v.start_mission()
        # out of the parameter's range: the autopilot clamps silently; the gateway refuses and restores
        with pytest.raises(InvalidArgument, match=r"FENCE_ENABLE cannot hold 1000: drone 'ap3' stored -24"):
            await v.set_param("FENCE_ENABLE", 1000)
        assert await v.get_param("FENCE_ENABLE") == (0, "int")
        with pytest.raises(InvalidArgument, match=r"RTL_ALT is a 32-bit integer"):
            await v.set_param("RTL_ALT", 1e12)

        await v.arm()  # at once after "ready"
        await wait_until(lambda: v.telemetry.fresh("armed") is True, what="armed")
        with pytest.raises(CommandFailed) as refused:  # AUTO without a mission, armed
            await v.set_flight_mode("MISSION")
        assert "autopilot says: 'Mode change to AUTO failed: init failed'" in refused.value.message

        await v.takeoff(10)
        await wait_until(lambda: v.telemetry.fresh("in_air") is True, what="in the air")
        with pytest.raises(CommandFailed) as silent:  # ArduCopter refuses a disarm in flight without a word
            await v.disarm()
        assert silent.value.message == (
            "disarm on drone 'ap3' failed: Failed (FAILED) "
            "(the autopilot gave no reason; it is mode GUIDED, armed, in the air)"
        )
        await v.land()
        await wait_until(lambda: v.telemetry.fresh("armed") is False, what="landed and disarmed")
