"""Reading a vehicle's telemetry cache: values, their age, and the few derived facts every caller needs.

Two kinds of read: ``value`` takes whatever the cache holds (for trackers following a flight, which
judge staleness themselves), ``fresh`` only a value younger than the stale limit while the link is live
(for decisions: the safety policy never judges stale data as current).
"""

from __future__ import annotations

import math
from typing import TypeVar

from gateway.fleet.policy.safety_inputs import VehicleContext
from gateway.fleet.vehicles.protocols import VehicleView
from gateway.link.telemetry import Sample

T = TypeVar("T")


def sample(vehicle: VehicleView, name: str) -> Sample[object] | None:
    found: Sample[object] | None = getattr(vehicle.telemetry, name)
    return found


def value(found: Sample[T] | None) -> T | None:
    """A stream's cached value (None when never received), however old; typed by the cache's field it
    is read from (``value(vehicle.telemetry.armed)``)."""
    return None if found is None else found.value


def age_s(vehicle: VehicleView, name: str) -> float | None:
    found = sample(vehicle, name)
    return None if found is None else float(found.age_s)


def is_stale(vehicle: VehicleView, age: float, limit_s: float) -> bool:
    """A cached value is stale when older than ``limit_s``, and every value is while the link is lost
    (even one that arrived just after the last heartbeat)."""
    return age > limit_s or not vehicle.telemetry.live


def position(vehicle: VehicleView) -> tuple[float, float, float] | None:
    """(lat, lon, alt_rel_m) from the cache, or None."""
    pos = value(vehicle.telemetry.position)
    if pos is None:
        return None
    return float(pos.lat_deg), float(pos.lon_deg), float(pos.rel_alt_m)


def home(vehicle: VehicleView) -> tuple[float, float, float] | None:
    """(lat, lon, alt_amsl_m) of home from the cache, or None."""
    h = value(vehicle.telemetry.home)
    if h is None:
        return None
    return float(h.lat_deg), float(h.lon_deg), float(h.abs_alt_m)


def ground_speed(vehicle: VehicleView) -> float | None:
    v = value(vehicle.telemetry.velocity_ned)
    if v is None:
        return None
    return math.hypot(float(v.north_mps), float(v.east_mps))


def climb_rate(vehicle: VehicleView) -> float | None:
    v = value(vehicle.telemetry.velocity_ned)
    return None if v is None else -float(v.down_mps)


def is_landed(vehicle: VehicleView) -> bool:
    """On the ground as far as the cache says (the autopilot's dialect reads its landed state)."""
    return vehicle.on_ground(fresh=False) is True


def is_airborne(vehicle: VehicleView) -> bool:
    """In the air as far as the cache says (the autopilot's dialect reads its landed state)."""
    return vehicle.on_ground(fresh=False) is False


def is_landed_and_disarmed(vehicle: VehicleView) -> bool:
    return value(vehicle.telemetry.armed) is False and is_landed(vehicle)


def is_flying(vehicle: VehicleView) -> bool:
    """Armed and in the air, as far as the cache says."""
    return is_airborne(vehicle) and value(vehicle.telemetry.armed) is True


def vehicle_context(vehicle: VehicleView) -> VehicleContext:
    """What the safety policy judges, from fresh telemetry only (stale or missing values are None):
    the one builder, for every door (MCP, REST, console, cluster)."""
    fresh = vehicle.telemetry.fresh
    battery, h, pos = fresh("battery"), fresh("home"), fresh("position")
    return VehicleContext(
        vehicle_id=vehicle.id,
        is_simulator=bool(vehicle.is_simulator),
        armed=bool(fresh("armed")),
        in_air=vehicle.on_ground() is False,
        battery_pct=None if battery is None else battery.remaining_pct,
        home=None if h is None else (float(h.lat_deg), float(h.lon_deg), float(h.abs_alt_m)),
        position=None if pos is None else (float(pos.lat_deg), float(pos.lon_deg), float(pos.rel_alt_m)),
        origin=vehicle.origin,
    )
