"""A JSON picture of the whole fleet at one instant, read from the telemetry caches (no vehicle is asked).

This is what the live event stream (:mod:`gateway.api.events`) sends a few times a second and what the
operator console draws: per drone its connection state, position, heading, altitude, battery, mode,
the current operation and flight, the last status texts and its lock; for the fleet the fleet lock
and the origin of the console's metric map (the first home position known, by drone id).

Values keep their age: a value older than the vehicle's stale limit (or any value while its link is
down) is sent with ``stale: true`` so the page shows it as last known, never as current.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from datetime import UTC, datetime
from typing import SupportsFloat, TypeVar

from gateway.errors import GatewayError
from gateway.fleet.policy.geofence import FLEET
from gateway.fleet.policy.operator_locks import Lock, LockBook
from gateway.fleet.vehicles.protocols import VehicleView
from gateway.link.telemetry import Sample, TelemetryCache
from gateway.runtime import Gateway
from gateway.util.json_types import JsonObject

STATUS_TEXTS_PER_DRONE = 5

T = TypeVar("T")


def _num(value: SupportsFloat | None, digits: int) -> float | None:
    if value is None:
        return None
    number = float(value)
    return round(number, digits) if math.isfinite(number) else None


def _sample(
    cache: TelemetryCache, sample: Sample[T] | None
) -> tuple[T, float, bool] | tuple[None, None, bool]:
    """(value, age_s, stale) of one cached stream; (None, None, True) when never received."""
    if sample is None:
        return None, None, True
    age = sample.age_s
    return sample.value, round(age, 2), age > cache.stale_after_s or not cache.live


def _position(cache: TelemetryCache) -> dict[str, object] | None:
    pos, age, stale = _sample(cache, cache.position)
    if pos is None:
        return None
    return {
        "lat": pos.lat_deg,
        "lon": pos.lon_deg,
        "alt_rel_m": _num(pos.rel_alt_m, 2),
        "alt_amsl_m": _num(pos.abs_alt_m, 2),
        "age_s": age,
        "stale": stale,
    }


def _home(cache: TelemetryCache) -> dict[str, object] | None:
    home, _age, _stale = _sample(cache, cache.home)
    if home is None:
        return None
    return {"lat": home.lat_deg, "lon": home.lon_deg, "alt_amsl_m": _num(home.abs_alt_m, 2)}


OperationOf = Callable[[str], JsonObject | None]


def _no_operation(vehicle_id: str) -> None:
    return None


def _operation_of(gateway: Gateway) -> OperationOf:
    """Each drone's latest operation: the Commander's (on a cluster node also the ones the owners of
    the other drones publish); none while the gateway starts or stops."""
    try:
        reader: OperationOf = gateway.commander.current_operation
    except GatewayError:
        return _no_operation
    return reader


def vehicle_view(vehicle: VehicleView, operation_of: OperationOf, locks: LockBook) -> dict[str, object]:
    cache = vehicle.telemetry
    value = cache.fresh
    battery, battery_age, battery_stale = _sample(cache, cache.battery)
    velocity = value("velocity_ned")
    gps = value("gps_info")
    progress = value("mission_progress")
    state = vehicle.state
    return {
        "id": vehicle.id,
        "name": vehicle.spec.name,
        "tags": list(vehicle.spec.tags),
        "state": str(getattr(state, "value", state)),
        "initialising": vehicle.initialising(),
        "last_error": vehicle.last_error,
        "locked": locks.reason_for(vehicle.id),  # fleet lock included: whether agents may command it
        "own_lock": _lock_view(locks.get(vehicle.id)),  # this drone's own lock (the one to unlock here)
        "taken_over": _lock_view(locks.takeover_for(vehicle.id)),  # a pilot or GCS took it: release here
        "is_simulator": vehicle.is_simulator,
        "autopilot": vehicle.autopilot,
        "position": _position(cache),
        "home": _home(cache),
        "heading_deg": _num(value("heading_deg"), 1),
        "ground_speed_mps": None if velocity is None else _num(velocity.ground_speed_mps, 2),
        "climb_mps": None if velocity is None else _num(-velocity.down_mps, 2),
        "battery_pct": None if battery is None else _num(battery.remaining_pct, 1),
        "battery_v": None if battery is None else _num(battery.voltage_v, 2),
        "battery_stale": battery_stale,
        "battery_age_s": battery_age,
        "flight_mode": value("flight_mode"),
        "armed": value("armed"),
        "in_air": value("in_air"),
        "landed_state": value("landed_state"),
        "gps": None if gps is None else {"satellites": gps.num_satellites, "fix": gps.fix_type},
        "mission": None
        if progress is None
        else {"current": progress.current, "total": progress.total, "finished": progress.finished},
        "operation": operation_of(vehicle.id),
        "flight_id": vehicle.current_flight_id,
        "status_texts": [
            {"t": item.t, "severity": item.severity, "text": item.text}
            for item in list(cache.status_texts)[-STATUS_TEXTS_PER_DRONE:]
        ],
    }


def _lock_view(lock: Lock | None) -> dict[str, object] | None:
    if lock is None:
        return None
    return {"reason": lock.reason, "by": lock.by, "locked_at": lock.locked_at.isoformat()}


def fleet_view(gateway: Gateway) -> dict[str, object]:
    """The fleet now; ``vehicles`` sorted by id, ``origin`` the first known home (None before any)."""
    registry = gateway.registry
    vehicles = sorted(registry.all(), key=lambda v: v.id) if registry is not None else []
    operation_of = _operation_of(gateway)
    views = [vehicle_view(v, operation_of, gateway.locks) for v in vehicles]
    homes = [v["home"] for v in views if isinstance(v["home"], dict)]
    origin = next(({"lat": home["lat"], "lon": home["lon"]} for home in homes), None)
    return {
        "t": datetime.now(UTC).isoformat(),
        "fleet_lock": _lock_view(gateway.locks.get(FLEET)),
        "origin": origin,
        "vehicles": views,
    }
