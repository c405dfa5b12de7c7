"""Shared builders for the safety and formation unit tests."""

from __future__ import annotations

from typing import Any

from gateway.config import Settings
from gateway.fleet import geo
from gateway.fleet.policy.caller import Caller
from gateway.fleet.policy.safety import SafetyPolicy
from gateway.fleet.policy.safety_inputs import VehicleContext

HOME = (47.397742, 8.545594, 488.0)  # lat, lon, alt AMSL

AGENT = Caller(via="mcp", principal="agent-1", session="s1")
OPERATOR = Caller(via="rest", principal="operator-1", session="rest:operator-1")


def settings(**overrides: Any) -> Settings:
    return Settings(_env_file=None, **overrides)


def policy(**overrides: Any) -> SafetyPolicy:
    return SafetyPolicy(settings(**overrides))


def at(north_m: float, east_m: float, origin: tuple[float, float] = HOME[:2]) -> tuple[float, float]:
    """lat, lon of the point north/east metres from origin (default: home)."""
    return geo.offset_position(origin[0], origin[1], north_m, east_m)


def ctx(
    vehicle_id: str = "alpha",
    *,
    is_simulator: bool = True,
    armed: bool = True,
    in_air: bool = True,
    battery_pct: float | None = 80.0,
    home: tuple[float, float, float] | None = HOME,
    north_m: float = 0.0,
    east_m: float = 0.0,
    alt_rel_m: float = 20.0,
    position: bool = True,
) -> VehicleContext:
    pos = (*at(north_m, east_m), alt_rel_m) if position else None
    return VehicleContext(vehicle_id, is_simulator, armed, in_air, battery_pct, home, pos)


def square(north_m: float, east_m: float, half_m: float, origin: tuple[float, float] = HOME[:2]) -> dict:
    """A GeoJSON Polygon: a square of side 2*half_m centred north/east metres from origin."""
    corners = [(-1, -1), (-1, 1), (1, 1), (1, -1), (-1, -1)]
    ring = []
    for dn, de in corners:
        lat, lon = at(north_m + dn * half_m, east_m + de * half_m, origin)
        ring.append([lon, lat])
    return {"type": "Polygon", "coordinates": [ring]}


def ground(vehicle_id: str = "alpha", **kw: Any) -> VehicleContext:
    """A disarmed drone sitting at home."""
    kw.setdefault("battery_pct", 80.0)
    return ctx(vehicle_id, in_air=False, armed=False, alt_rel_m=0.0, **kw)
