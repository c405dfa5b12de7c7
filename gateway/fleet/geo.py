"""Geodesy helpers on the WGS-84 ellipsoid (pymap3d), and the one place altitude frames are converted.

Tools speak metres above home ("relative"); MAVSDK's goto speaks AMSL. Conversions happen here only.
"""

from __future__ import annotations

import math

from gateway.errors import InvalidArgument


def check_lat_lon(lat: float, lon: float) -> None:
    """Raise InvalidArgument unless lat/lon are finite and in range."""
    for name, value, limit in (("latitude", lat, 90.0), ("longitude", lon, 180.0)):
        if not isinstance(value, int | float) or isinstance(value, bool):
            raise InvalidArgument(f"{name} must be a number of degrees; got {value!r}")
        if not math.isfinite(value):
            raise InvalidArgument(f"{name} must be a finite number of degrees; got {value}")
        if not -limit <= value <= limit:
            swapped = name == "latitude" and abs(value) <= 180.0 and abs(lon) <= 90.0
            hint = "; latitude and longitude look swapped" if swapped else ""
            raise InvalidArgument(f"{name} {value} is outside -{limit:g}..{limit:g} degrees{hint}")


def check_finite(name: str, value: float) -> None:
    if not isinstance(value, int | float) or isinstance(value, bool) or not math.isfinite(value):
        raise InvalidArgument(f"{name} must be a finite number; got {value!r}")


def ned_offset(lat0: float, lon0: float, lat: float, lon: float) -> tuple[float, float]:
    """North and east metres from (lat0, lon0) to (lat, lon), on the ellipsoid's local tangent plane."""
    import pymap3d  # with numpy about 15 MiB: imported when a distance is first needed

    north, east, _ = pymap3d.geodetic2ned(lat, lon, 0.0, lat0, lon0, 0.0)
    return float(north), float(east)


def offset_position(lat0: float, lon0: float, north_m: float, east_m: float) -> tuple[float, float]:
    """The point north_m / east_m metres away from (lat0, lon0)."""
    import pymap3d

    lat, lon, _ = pymap3d.ned2geodetic(north_m, east_m, 0.0, lat0, lon0, 0.0)
    return float(lat), float(lon)


def horizontal_distance_m(lat1: float, lon1: float, lat2: float, lon2: float) -> float:
    north, east = ned_offset(lat1, lon1, lat2, lon2)
    return math.hypot(north, east)


def bearing_deg(lat1: float, lon1: float, lat2: float, lon2: float) -> float:
    """Initial bearing from point 1 to point 2, degrees clockwise from true north, 0..360."""
    north, east = ned_offset(lat1, lon1, lat2, lon2)
    return math.degrees(math.atan2(east, north)) % 360.0


def distance_3d_m(lat1: float, lon1: float, alt1_m: float, lat2: float, lon2: float, alt2_m: float) -> float:
    return math.hypot(horizontal_distance_m(lat1, lon1, lat2, lon2), alt2_m - alt1_m)


def relative_to_amsl(relative_alt_m: float, home_amsl_m: float) -> float:
    """Metres above home -> metres above mean sea level."""
    return home_amsl_m + relative_alt_m


def amsl_to_relative(amsl_m: float, home_amsl_m: float) -> float:
    """Metres above mean sea level -> metres above home."""
    return amsl_m - home_amsl_m
