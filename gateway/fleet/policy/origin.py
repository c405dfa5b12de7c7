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

from dataclasses import dataclass
from datetime import datetime
from typing import Literal

from gateway.errors import InvalidArgument
from gateway.fleet import geo

OriginSource = Literal["first_home", "operator"]
ORIGIN_SOURCES: tuple[OriginSource, ...] = ("first_home", "operator")


@dataclass(frozen=True)
class Origin:
    """Where a vehicle's distance limit and zones count from, who set it and when."""

    vehicle_id: str
    lat: float
    lon: float
    alt_amsl_m: float
    source: OriginSource
    set_by: str
    set_at: datetime

    @property
    def point(self) -> tuple[float, float, float]:
        return (self.lat, self.lon, self.alt_amsl_m)

    def to_record(self) -> dict[str, object]:
        return {
            "vehicle_id": self.vehicle_id,
            "lat": self.lat,
            "lon": self.lon,
            "alt_amsl_m": self.alt_amsl_m,
            "source": self.source,
            "set_by": self.set_by,
            "set_at": self.set_at.isoformat(),
        }


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
