"""One naming scheme for every tool's arguments and results (docs/tools.md, "Names").

A small model reads a name and guesses the rest: measured with a 1.5B model, ``takeoff(altitude_m)`` next
to ``fleet_takeoff(alt_m)`` and ``latitude_deg`` in inputs next to ``lat_deg`` in outputs led to wrong
argument names, and ``down_m`` (NED, + descends) was written as ``down_m=10`` for "10 m higher". So one
name per quantity, the unit in the name, and relative moves counted up, as people say them."""

from __future__ import annotations

#: name -> what it means; rendered into docs/tools.md by scripts/gen_tools_doc.py
NAMES: dict[str, str] = {
    "lat_deg, lon_deg": "latitude and longitude in degrees (WGS84); every position, in arguments and results",
    "alt_m": "altitude in metres above home (the launch point); every altitude a tool takes or reports",
    "alt_amsl_m": 'altitude in metres above mean sea level (results; `alt_frame="amsl"` makes an `alt_m` '
    "argument mean this)",
    "north_m, east_m, up_m": "a relative move in metres from where the drone is (negative: south, west, "
    "down); `south_m`, `west_m` say it as a request does (`west_m=40` is `east_m=-40`)",
    "center_lat_deg, center_lon_deg": "the point a formation is centred on",
    "target_lat_deg, target_lon_deg, target_alt_m": "where one drone of a fleet operation is sent",
    "climb_mps": "vertical speed in m/s (negative: descending); `north_mps`, `east_mps` the horizontal parts",
    "drone_id, drone_ids": "drone ids as `list_drones` gives them; case does not matter (`Alpha` is `alpha`)",
}

UNITS = "Other names carry their unit: `_m` metres, `_deg` degrees, `_s` seconds, `_pct` percent, `_mps` m/s."

#: names of other schemes, with the name to use instead: none of them may appear in a tool's schema
RETIRED: dict[str, str] = {
    "latitude_deg": "lat_deg",
    "longitude_deg": "lon_deg",
    "latitude": "lat_deg",
    "longitude": "lon_deg",
    "lat": "lat_deg",
    "lon": "lon_deg",
    "altitude_m": "alt_m",
    "altitude": "alt_m",
    "rel_alt_m": "alt_m",
    "abs_alt_m": "alt_amsl_m",
    "down_m": "up_m",
    "down_mps": "climb_mps",
    "center_lat": "center_lat_deg",
    "center_lon": "center_lon_deg",
    "target_lat": "target_lat_deg",
    "target_lon": "target_lon_deg",
}


def retired_names(schema: object, path: str = "") -> list[str]:
    """Every property name in a JSON schema (nested objects, arrays, $defs) that the scheme retired, as
    'path: name -> use instead'."""
    found: list[str] = []
    if isinstance(schema, dict):
        for key, sub in schema.items():
            if key == "properties" and isinstance(sub, dict):
                for name, prop in sub.items():
                    if name in RETIRED:
                        found.append(f"{path}{name} -> {RETIRED[name]}")
                    found += retired_names(prop, f"{path}{name}.")
            else:
                found += retired_names(sub, path)
    elif isinstance(schema, list):
        for item in schema:
            found += retired_names(item, path)
    return found


def retired_keys(data: object, path: str = "") -> list[str]:
    """The same check over a result's data (dict keys at any depth)."""
    found: list[str] = []
    if isinstance(data, dict):
        for key, sub in data.items():
            if key in RETIRED:
                found.append(f"{path}{key} -> {RETIRED[key]}")
            found += retired_keys(sub, f"{path}{key}.")
    elif isinstance(data, list):
        for item in data:
            found += retired_keys(item, path)
    return found
