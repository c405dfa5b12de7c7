"""A vehicle's origin: the point its distance limit and geofence checks count from.

ArduPilot sets home again at every arming (`AP_Arming::arm` -> `Copter::set_home_to_current_location`),
so a limit counted from home walks with the drone: land 950 m out, take off again, and a goto the limit
refused a minute earlier flies (measured on SITL: 1,899 m from the first home against a 1,000 m limit).
The origin is fixed per vehicle instead: the first home the vehicle reported, kept in the registry
(table ``vehicle_origins``) across restarts, and moved only by an operator over REST
(``PUT /api/v1/vehicles/{id}/origin``, audited). Until a vehicle has reported a home there is no origin,
and the policy refuses to move it (``home_unknown``).

Altitudes stay metres above the autopilot's home, the frame every command is sent in.
"""

from __future__ import annotations

from datetime import datetime

from pydantic import BaseModel, Field

from gateway.errors import InvalidArgument
from gateway.fleet import geo
from gateway.registry.records import ORIGIN_SOURCES, Origin, OriginSource

__all__ = ["ORIGIN_SOURCES", "Origin", "OriginSource", "OriginView", "checked_point", "origin_view"]

Point = tuple[float, float, float]


class OriginView(BaseModel):
    """A vehicle's origin as the doors show it, beside the autopilot's current home."""

    vehicle_id: str
    origin: dict[str, float] | None = Field(description="lat, lon, alt_amsl_m; null until a home came.")
    source: OriginSource | None = None
    set_by: str | None = None
    set_at: datetime | None = None
    home: dict[str, float] | None = Field(None, description="The autopilot's current home.")
    home_from_origin_m: float | None = Field(None, description="How far the autopilot's home is from it.")


def _point(lat: float, lon: float, alt: float) -> dict[str, float]:
    return {"lat": lat, "lon": lon, "alt_amsl_m": alt}


def origin_view(vehicle_id: str, origin: Origin | Point | None, home: Point | None) -> OriginView:
    """The origin (stored, with who set it; or the point in force) and how far the home is from it."""
    current = None
    out = OriginView(vehicle_id=vehicle_id, origin=None)
    if isinstance(origin, Origin):
        current = origin.point
        out.source, out.set_by, out.set_at = origin.source, origin.set_by, origin.set_at
    elif origin is not None:
        current = origin
    if current is not None:
        out.origin = _point(*current)
    if home is not None:
        out.home = _point(*home)
        if current is not None:
            out.home_from_origin_m = round(
                geo.horizontal_distance_m(current[0], current[1], home[0], home[1]), 2
            )
    return out


def checked_point(lat: object, lon: object, alt_amsl_m: object) -> tuple[float, float, float]:
    """An operator's new origin: finite numbers, a real latitude and longitude; InvalidArgument naming
    the argument otherwise."""
    values: list[float] = []
    for name, value in (("lat", lat), ("lon", lon), ("alt_amsl_m", alt_amsl_m)):
        if isinstance(value, bool) or not isinstance(value, int | float):
            raise InvalidArgument(f"origin {name} must be a number; got {value!r}")
        geo.check_finite(f"origin {name}", float(value))
        values.append(float(value))
    geo.check_lat_lon(values[0], values[1])
    if not -500.0 <= values[2] <= 9000.0:
        raise InvalidArgument(f"origin alt_amsl_m must be -500..9000 m; got {values[2]:g}")
    return values[0], values[1], values[2]
