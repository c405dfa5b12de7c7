"""A QGroundControl ``.plan``'s geofence and rally points, beside its mission items.

`split_plan` takes them out of a ``.plan`` (the mission items go on to `mission_files.parse_plan`, which
refuses a plan that still has them, so they are never dropped on the way): each geofence polygon or circle
becomes a zone of the drone's geofences (``keep_in`` for an inclusion, ``keep_out`` for an exclusion; a
circle as a 64-sided polygon around it, its centre and radius kept to be written back), checked like any
zone; rally points are kept as they are. `with_extras` writes them back into an exported ``.plan``.

QGroundControl's layout (plan version 1, geoFence version 2, rallyPoints version 2): a polygon is a list
of ``[lat, lon]`` vertices, not closed; a circle is ``{"center": [lat, lon], "radius": metres}``; a rally
point is ``[lat, lon, alt]`` (altitude above home).
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field

from gateway.errors import InvalidArgument
from gateway.fleet import geo
from gateway.util.json_types import JsonMapping, JsonObject, JsonValue

CIRCLE_SIDES = 64
MAX_FENCE_ZONES = 50
MAX_RALLY_POINTS = 50


@dataclass(frozen=True)
class FenceZone:
    """One zone of a plan's geofence, as a geofence zone takes it (GeoJSON: [lon, lat])."""

    name: str
    kind: str  # keep_in | keep_out
    geometry: JsonObject
    circle: tuple[float, float, float] | None = None  # centre lat, lon and radius (m) it was drawn as


@dataclass(frozen=True)
class PlanExtras:
    fence: list[FenceZone] = field(default_factory=list)
    rally: list[tuple[float, float, float]] = field(default_factory=list)

    def __bool__(self) -> bool:
        return bool(self.fence or self.rally)


def _number(value: JsonValue, where: str) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
        raise InvalidArgument(f"{where}: expected a number, got {json.dumps(value)[:40]}")
    return float(value)


def _lat_lon(pair: JsonValue, where: str) -> tuple[float, float]:
    if not isinstance(pair, list) or len(pair) < 2:
        raise InvalidArgument(f"{where}: expected [latitude, longitude], got {json.dumps(pair)[:60]}")
    lat, lon = _number(pair[0], f"{where} latitude"), _number(pair[1], f"{where} longitude")
    try:
        geo.check_lat_lon(lat, lon)
    except InvalidArgument as exc:
        raise InvalidArgument(f"{where}: {exc.message}") from None
    return lat, lon


def _kind(entry: JsonMapping, where: str) -> str:
    inclusion = entry.get("inclusion", True)
    if not isinstance(inclusion, bool):
        raise InvalidArgument(f"{where}: inclusion must be true or false; got {json.dumps(inclusion)[:20]}")
    return "keep_in" if inclusion else "keep_out"


def circle_ring(lat: float, lon: float, radius_m: float) -> list[JsonValue]:
    """A closed GeoJSON ring ([lon, lat]) of CIRCLE_SIDES vertices on the circle."""
    ring: list[JsonValue] = []
    for k in range(CIRCLE_SIDES):
        angle = 2 * math.pi * k / CIRCLE_SIDES
        plat, plon = geo.offset_position(lat, lon, radius_m * math.cos(angle), radius_m * math.sin(angle))
        ring.append([plon, plat])
    return [*ring, ring[0]]


def _fence(doc: JsonMapping, prefix: str) -> list[FenceZone]:
    fence = doc.get("geoFence")
    if fence is None:
        return []
    if not isinstance(fence, dict):
        raise InvalidArgument(f"the .plan's geoFence must be an object; got {json.dumps(fence)[:40]}")
    polygons, circles = fence.get("polygons") or [], fence.get("circles") or []
    if not isinstance(polygons, list) or not isinstance(circles, list):
        raise InvalidArgument("the .plan's geoFence polygons and circles must be lists")
    if len(polygons) + len(circles) > MAX_FENCE_ZONES:
        raise InvalidArgument(
            f"the .plan's geofence has {len(polygons) + len(circles)} zones; at most {MAX_FENCE_ZONES}"
        )
    zones = []
    for k, entry in enumerate(polygons, start=1):
        where = f"geofence polygon {k}"
        polygon = entry.get("polygon") if isinstance(entry, dict) else None
        if not isinstance(entry, dict) or not isinstance(polygon, list):
            raise InvalidArgument(f'{where}: expected an object with a "polygon" list of [lat, lon]')
        vertices = [_lat_lon(v, f"{where} vertex {i}") for i, v in enumerate(polygon, start=1)]
        if len(vertices) < 3:
            raise InvalidArgument(f"{where}: {len(vertices)} vertices; a polygon needs at least 3")
        ring: list[JsonValue] = [[lon, lat] for lat, lon in vertices]
        if ring[0] != ring[-1]:
            ring.append(ring[0])
        geometry: JsonObject = {"type": "Polygon", "coordinates": [ring]}
        zones.append(FenceZone(f"{prefix}-polygon-{k}", _kind(entry, where), geometry))
    for k, entry in enumerate(circles, start=1):
        where = f"geofence circle {k}"
        circle = entry.get("circle") if isinstance(entry, dict) else None
        if not isinstance(entry, dict) or not isinstance(circle, dict):
            raise InvalidArgument(f'{where}: expected an object with a "circle": {{center, radius}}')
        lat, lon = _lat_lon(circle.get("center"), f"{where} center")
        radius = _number(circle.get("radius"), f"{where} radius")
        if not 0 < radius <= 100_000:
            raise InvalidArgument(f"{where}: radius {radius} m; give 0 < radius <= 100000")
        geometry = {"type": "Polygon", "coordinates": [circle_ring(lat, lon, radius)]}
        zones.append(FenceZone(f"{prefix}-circle-{k}", _kind(entry, where), geometry, (lat, lon, radius)))
    return zones


def _rally(doc: JsonMapping) -> list[tuple[float, float, float]]:
    rally = doc.get("rallyPoints")
    if rally is None:
        return []
    points = rally.get("points") if isinstance(rally, dict) else None
    if not isinstance(points, list):
        raise InvalidArgument('the .plan\'s rallyPoints must be an object with a "points" list')
    if len(points) > MAX_RALLY_POINTS:
        raise InvalidArgument(f"the .plan has {len(points)} rally points; at most {MAX_RALLY_POINTS}")
    kept = []
    for k, point in enumerate(points, start=1):
        where = f"rally point {k}"
        if not isinstance(point, list) or len(point) != 3:
            raise InvalidArgument(f"{where}: expected [lat, lon, alt], got {json.dumps(point)[:60]}")
        lat, lon = _lat_lon(point, where)
        kept.append((lat, lon, _number(point[2], f"{where} altitude")))
    return kept


def _outer_rings(geometry: JsonMapping) -> list[JsonValue]:
    """The outer ring of a GeoJSON Polygon, or of each polygon of a MultiPolygon."""
    coordinates = geometry.get("coordinates")
    if not isinstance(coordinates, list):
        return []
    if geometry.get("type") == "Polygon":
        return coordinates[:1]
    return [polygon[0] for polygon in coordinates if isinstance(polygon, list) and polygon]


def _lon_lat(ring: JsonValue, where: str) -> list[tuple[float, float]]:
    """A GeoJSON ring's vertices, (longitude, latitude), an altitude dropped."""
    vertices = ring if isinstance(ring, list) else []
    return [
        (_number(point[0], f"{where} longitude"), _number(point[1], f"{where} latitude"))
        for point in vertices
        if isinstance(point, list) and len(point) >= 2
    ]


def split_plan(text: str, prefix: str) -> tuple[str, PlanExtras]:
    """The plan without its geofence and rally points, and those (zone names begin with ``prefix``).
    Text that is no JSON object is returned as it is (the mission parser says what is wrong with it)."""
    try:
        doc = json.loads(text)
    except (json.JSONDecodeError, RecursionError):
        return text, PlanExtras()
    if not isinstance(doc, dict):
        return text, PlanExtras()
    extras = PlanExtras(_fence(doc, prefix), _rally(doc))
    if not extras:
        return text, extras
    doc["geoFence"] = {"circles": [], "polygons": [], "version": 2}
    doc["rallyPoints"] = {"points": [], "version": 2}
    return json.dumps(doc), extras


def with_extras(plan: str, fence: list[FenceZone], rally: list[tuple[float, float, float]]) -> str:
    """An exported ``.plan`` with the drone's zones as its geofence and the kept rally points."""
    doc = json.loads(plan)
    polygons, circles = [], []
    for zone in fence:
        inclusion = zone.kind == "keep_in"
        if zone.circle is not None:
            lat, lon, radius = zone.circle
            circles.append(
                {"circle": {"center": [lat, lon], "radius": radius}, "inclusion": inclusion, "version": 1}
            )
            continue
        for ring in _outer_rings(zone.geometry):
            vertices = [[lat, lon] for lon, lat in _lon_lat(ring, zone.name)]
            if len(vertices) > 1 and vertices[0] == vertices[-1]:
                vertices.pop()
            polygons.append({"inclusion": inclusion, "polygon": vertices, "version": 1})
    doc["geoFence"] = {"circles": circles, "polygons": polygons, "version": 2}
    doc["rallyPoints"] = {"points": [list(p) for p in rally], "version": 2}
    return json.dumps(doc, indent=2) + "\n"
