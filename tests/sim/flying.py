"""Small MAVSDK helpers for the simulator tests (waiting on streams, preparing a flight)."""

from __future__ import annotations

import asyncio
import math
from collections.abc import AsyncIterator, Callable
from typing import TypeVar

from mavsdk_grpc import System
from mavsdk_grpc.action import ActionError

from tests.helpers.timing import scaled

T = TypeVar("T")

# Simulated time runs this much faster than wall time in these tests (boot to flyable: ~2 s).
SPEEDUP = 30.0

# What the gateway caches; ArduPilot streams nothing until asked (reference section 7).
RATES = {
    "position": 5.0,
    "home": 1.0,
    "in_air": 2.0,
    "landed_state": 2.0,
    "health": 1.0,
    "gps_info": 1.0,
    "battery": 1.0,
    "attitude_euler": 4.0,
    "velocity_ned": 5.0,
    "rc_status": 1.0,
}


async def set_rates(drone: System) -> None:
    for name, hz in RATES.items():
        await getattr(drone.telemetry, f"set_rate_{name}")(hz)


async def wait_for(stream: AsyncIterator[T], predicate: Callable[[T], bool], timeout_s: float = 60.0) -> T:
    """First item of a MAVSDK stream that satisfies predicate (waits, never asserts a duration)."""

    async def scan() -> T:
        async for item in stream:
            if predicate(item):
                return item
        raise AssertionError("stream ended")

    return await asyncio.wait_for(scan(), scaled(timeout_s))


async def ready_to_fly(drone: System) -> None:
    """Rates, then LOITER (a GPS mode, switched while disarmed), then wait until armable there."""
    await set_rates(drone)
    await wait_for(drone.telemetry.health(), lambda h: h.is_global_position_ok and h.is_home_position_ok)
    await drone.action.hold()  # DO_SET_MODE LOITER: is_armable now waits for the EKF position
    await wait_for(drone.telemetry.health(), lambda h: h.is_armable)


async def arm(drone: System, within_s: float = 15.0) -> None:
    """Arm as a ground station must on ArduCopter: its pre-arm bit is re-evaluated about once a second,
    so right after a mode change it can still say armable while arming is refused ("Need Position
    Estimate"); a refusal is retried until the (scaled) deadline, and the last one raised."""
    deadline = asyncio.get_running_loop().time() + scaled(within_s)
    while True:
        try:
            await drone.action.arm()
            return
        except ActionError:
            if asyncio.get_running_loop().time() > deadline:
                raise
            await asyncio.sleep(0.2)


async def take_off(drone: System, alt_m: float = 10.0) -> None:
    await drone.action.set_takeoff_altitude(alt_m)
    await arm(drone)
    await drone.action.takeoff()
    await wait_for(drone.telemetry.position(), lambda p: p.relative_altitude_m > alt_m - 1.0)


def distance_m(lat1: float, lon1: float, lat2: float, lon2: float) -> float:
    north = (lat2 - lat1) * 111319.49
    east = (lon2 - lon1) * 111319.49 * math.cos(math.radians(lat1))
    return math.hypot(north, east)


def offset(lat: float, lon: float, north_m: float, east_m: float) -> tuple[float, float]:
    return lat + north_m / 111319.49, lon + east_m / (111319.49 * math.cos(math.radians(lat)))
