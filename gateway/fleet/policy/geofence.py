"""Keep-in / keep-out geofence zones (GeoJSON Polygon / MultiPolygon), tested on a local metric plane.

Each zone is projected once onto the local tangent plane around its own bounding-box centre
(`gateway.fleet.geo.ned_offset`); points and straight legs are projected onto the same plane when tested.
Zones are meant to be small (a few km): over that size the flat-plane approximation and the straight leg
drift apart by more than a metre.

Semantics:
- keep-in: a target must lie inside (or on the edge of) every keep-in zone that applies to the vehicle
  (a MultiPolygon counts as one zone: inside any of its parts); a leg that starts inside a keep-in zone
  must stay inside it all the way.
- keep-out: a target inside or on the edge of a keep-out zone is refused, and so is a leg whose straight
  path touches one. A leg that starts inside a keep-out zone (e.g. the zone was added while flying) may
  leave it, but not re-enter it.
"""

from __future__ import annotations

import json
import math
from collections.abc import Iterable, Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Literal

from gateway.errors import InvalidArgument
from gateway.fleet import geo
from gateway.util.json_types import JsonMapping, JsonObject, JsonValue

if TYPE_CHECKING:  # shapely (and numpy under it, about 18 MiB) is imported when a zone is first made
    from shapely.geometry import Point, Polygon
    from shapely.geometry.base import BaseGeometry

ZoneKind = Literal["keep_in", "keep_out"]
ZONE_KINDS: tuple[ZoneKind, ...] = ("keep_in", "keep_out")
FLEET = "*"


@dataclass(frozen=True)
class Violation:
    """One geofence breach: which zone, what kind of breach, and how deep (metres)."""

    zone: str
    kind: ZoneKind
    breach: Literal["target", "path"]
    metres: float


@dataclass(frozen=True)
class Zone:
    """One keep-in or keep-out area. ``scope`` is a vehicle id or ``"*"`` for the whole fleet."""

    name: str
    kind: ZoneKind
    scope: str
    geojson: JsonObject
    origin: tuple[float, float] = field(repr=False)
    local: BaseGeometry = field(repr=False)

    @classmethod
    def from_geojson(cls, name: str, kind: str, geometry: JsonValue, scope: str = FLEET) -> Zone:
        if kind not in ZONE_KINDS:
            raise InvalidArgument(f"geofence kind must be one of {list(ZONE_KINDS)}; got {kind!r}")
        if not isinstance(name, str) or not name.strip():
            raise InvalidArgument("geofence zone needs a non-empty name")
        if not isinstance(scope, str) or not scope:
            raise InvalidArgument("geofence scope must be a vehicle id or '*'")
        if not isinstance(geometry, dict) or geometry.get("type") not in ("Polygon", "MultiPolygon"):
            got = geometry.get("type") if isinstance(geometry, dict) else type(geometry).__name__
            raise InvalidArgument(
                f"geofence '{name}' must be a GeoJSON Polygon or MultiPolygon geometry; got {got!r}"
            )
        import shapely
        from shapely.geometry import shape

        try:
            lonlat = shape(geometry)
        except Exception as exc:  # shapely raises several types for malformed coordinates
            raise InvalidArgument(f"geofence '{name}' has malformed coordinates: {exc}") from exc
        if lonlat.is_empty:
            raise InvalidArgument(f"geofence '{name}' is empty")
        for lon, lat in shapely.get_coordinates(lonlat):
            try:
                geo.check_lat_lon(float(lat), float(lon))
            except InvalidArgument as exc:
                raise InvalidArgument(
                    f"geofence '{name}': {exc.message} (GeoJSON coordinates are [longitude, latitude])"
                ) from exc
        min_lon, min_lat, max_lon, max_lat = lonlat.bounds
        origin = ((min_lat + max_lat) / 2.0, (min_lon + max_lon) / 2.0)
        local = _project_geometry(lonlat, origin)
        if not local.is_valid:
            raise InvalidArgument(
                f"geofence '{name}' is not a valid polygon: {shapely.is_valid_reason(local)}"
            )
        if local.area <= 0.0:
            raise InvalidArgument(f"geofence '{name}' has zero area")
        return cls(name=name, kind=kind, scope=scope, geojson=dict(geometry), origin=origin, local=local)

    def _point(self, lat: float, lon: float) -> Point:
        from shapely.geometry import Point

        north, east = geo.ned_offset(self.origin[0], self.origin[1], lat, lon)
        return Point(east, north)

    def contains(self, lat: float, lon: float) -> bool:
        """Inside or on the edge."""
        return bool(self.local.intersects(self._point(lat, lon)))

    def distance_m(self, lat: float, lon: float) -> float:
        """Metres from the point to the zone (0 inside)."""
        return float(self.local.distance(self._point(lat, lon)))

    def depth_m(self, lat: float, lon: float) -> float:
        """Metres from a point inside the zone to its edge (0 outside)."""
        point = self._point(lat, lon)
        if not self.local.intersects(point):
            return 0.0
        return float(self.local.boundary.distance(point))

    def leg(self, start: tuple[float, float], end: tuple[float, float]) -> BaseGeometry:
        from shapely.geometry import LineString

        a, b = self._point(*start), self._point(*end)
        if a.equals(b):
            return a
        return LineString([a, b])

    def to_record(self) -> JsonObject:
        return {"name": self.name, "kind": self.kind, "scope": self.scope, "geometry": self.geojson}


def _project_geometry(lonlat: BaseGeometry, origin: tuple[float, float]) -> BaseGeometry:
    from shapely.geometry import MultiPolygon, Polygon

    def project_ring(coords: Iterable[tuple[float, ...]]) -> list[tuple[float, float]]:
        out = []
        for lon, lat, *_ in coords:
            north, east = geo.ned_offset(origin[0], origin[1], lat, lon)
            out.append((east, north))
        return out

    def project_polygon(poly: Polygon) -> Polygon:
        return Polygon(project_ring(poly.exterior.coords), [project_ring(r.coords) for r in poly.interiors])

    if isinstance(lonlat, Polygon):
        return project_polygon(lonlat)
    assert isinstance(lonlat, MultiPolygon)
    return MultiPolygon([project_polygon(p) for p in lonlat.geoms])


class GeofenceSet:
    """Zones per fleet ("*") or per vehicle id; `check_target` / `check_leg` report violations."""

    def __init__(self, zones: Iterable[Zone] = ()) -> None:
        self._zones: dict[str, Zone] = {}
        for zone in zones:
            self._put(zone)

    def _put(self, zone: Zone) -> None:
        if zone.name in self._zones:
            raise InvalidArgument(f"a geofence zone named '{zone.name}' already exists")
        self._zones[zone.name] = zone

    def add(self, name: str, kind: str, geometry: JsonValue, scope: str = FLEET) -> Zone:
        """Add a zone; names are unique across the set."""
        zone = Zone.from_geojson(name, kind, geometry, scope)
        self._put(zone)
        return zone

    def remove(self, name: str) -> Zone:
        try:
            return self._zones.pop(name)
        except KeyError:
            known = ", ".join(sorted(self._zones)) or "none"
            raise InvalidArgument(f"no geofence zone named '{name}'; zones: {known}") from None

    def __iter__(self) -> Iterator[Zone]:
        return iter(self._zones.values())

    def __len__(self) -> int:
        return len(self._zones)

    def for_vehicle(self, vehicle_id: str) -> list[Zone]:
        return [z for z in self._zones.values() if z.scope in (FLEET, vehicle_id)]

    def check_target(self, vehicle_id: str, lat: float, lon: float, radius_m: float = 0.0) -> list[Violation]:
        """Violations of a target, or with ``radius_m`` of the circle of that radius around it (a
        mission's loiter): inside every keep-in zone, clear of every keep-out zone."""
        out: list[Violation] = []
        for zone in self.for_vehicle(vehicle_id):
            if zone.kind == "keep_in" and not zone.contains(lat, lon):
                out.append(Violation(zone.name, "keep_in", "target", zone.distance_m(lat, lon) + radius_m))
            elif zone.kind == "keep_in" and radius_m > 0 and zone.depth_m(lat, lon) < radius_m:
                out.append(Violation(zone.name, "keep_in", "target", radius_m - zone.depth_m(lat, lon)))
            elif zone.kind == "keep_out" and zone.contains(lat, lon):
                out.append(Violation(zone.name, "keep_out", "target", zone.depth_m(lat, lon) + radius_m))
            elif zone.kind == "keep_out" and radius_m > 0 and zone.distance_m(lat, lon) <= radius_m:
                out.append(Violation(zone.name, "keep_out", "target", radius_m - zone.distance_m(lat, lon)))
        return out

    def check_leg(
        self, vehicle_id: str, start: tuple[float, float], end: tuple[float, float], width_m: float = 0.0
    ) -> list[Violation]:
        """Violations of the straight leg start -> end (lat, lon pairs); the end point itself is
        checked by `check_target`. ``width_m``: every point within that distance of the leg counts (a
        leg from or to a loiter's circle of that radius)."""
        out: list[Violation] = []
        for zone in self.for_vehicle(vehicle_id):
            leg = zone.leg(start, end)
            if width_m > 0:
                leg = leg.buffer(width_m)
            if zone.kind == "keep_in":
                if zone.contains(*start) and not zone.local.covers(leg):
                    outside = leg.difference(zone.local)
                    out.append(Violation(zone.name, "keep_in", "path", _metres_along(outside, width_m)))
            else:
                inside = leg.intersection(zone.local)
                if inside.is_empty:
                    continue
                if width_m <= 0 and zone.contains(*start) and _single_piece_from_start(inside, zone, start):
                    continue  # leaving a zone we are already in is allowed
                out.append(Violation(zone.name, "keep_out", "path", _metres_along(inside, width_m)))
        return out

    def to_records(self) -> list[JsonObject]:
        return [z.to_record() for z in self._zones.values()]

    @classmethod
    def from_records(cls, records: Iterable[JsonMapping]) -> GeofenceSet:
        zones = []
        for rec in records:
            try:
                name, kind = (_text(rec[key], f"geofence record {key}") for key in ("name", "kind"))
                scope = _text(rec.get("scope", FLEET), "geofence record scope")
                zones.append(Zone.from_geojson(name, kind, rec["geometry"], scope))
            except KeyError as exc:
                raise InvalidArgument(f"geofence record lacks {exc.args[0]!r}: {dict(rec)!r}") from None
        return cls(zones)

    @classmethod
    def from_geojson(cls, document: JsonValue) -> GeofenceSet:
        """A GeoJSON FeatureCollection: each feature a Polygon/MultiPolygon with properties
        ``kind`` ("keep_in"/"keep_out"), optional ``name`` and optional ``vehicle_id`` (default: fleet)."""
        if not isinstance(document, dict) or document.get("type") != "FeatureCollection":
            raise InvalidArgument("geofence document must be a GeoJSON FeatureCollection")
        features = document.get("features") or []
        if not isinstance(features, list):
            raise InvalidArgument("geofence document's features must be a list of GeoJSON Features")
        zones = []
        for index, feature in enumerate(features):
            if not isinstance(feature, dict):
                raise InvalidArgument(f"geofence feature {index + 1} must be a GeoJSON Feature object")
            props = feature.get("properties") or {}
            if not isinstance(props, dict):
                raise InvalidArgument(f"geofence feature {index + 1}'s properties must be an object")
            name = _text(props.get("name") or f"zone-{index + 1}", "geofence feature name")
            kind = props.get("kind")
            if kind is None:
                raise InvalidArgument(f"geofence feature '{name}' needs properties.kind: keep_in or keep_out")
            scope = _text(props.get("vehicle_id") or FLEET, f"geofence feature '{name}' vehicle_id")
            zones.append(
                Zone.from_geojson(name, _text(kind, "geofence kind"), feature.get("geometry"), scope)
            )
        return cls(zones)


def _text(value: JsonValue, what: str) -> str:
    """A text field of a stored or given geofence; InvalidArgument naming it otherwise."""
    if not isinstance(value, str):
        raise InvalidArgument(f"{what} must be text; got {value!r}")
    return value


def _metres_along(part: BaseGeometry, width_m: float) -> float:
    """How long a piece of a leg is: its length, or for a widened leg its area over the width."""
    return float(part.length) if width_m <= 0 else float(part.area) / (2.0 * width_m)


def load_geofence_file(path: str | Path) -> GeofenceSet:
    """Read a GeoJSON FeatureCollection file (see `GeofenceSet.from_geojson`)."""
    try:
        document = json.loads(Path(path).read_text(encoding="utf-8"))
    except (OSError, ValueError) as exc:
        raise InvalidArgument(f"cannot read geofence file {path}: {exc}") from exc
    return GeofenceSet.from_geojson(document)


def _single_piece_from_start(inside: BaseGeometry, zone: Zone, start: tuple[float, float]) -> bool:
    """True when the part of a leg inside the zone is one connected piece that begins at the start."""
    import shapely
    from shapely.geometry import Point

    if inside.geom_type == "Point":
        return True
    if inside.geom_type != "LineString":
        merged = shapely.line_merge(inside) if inside.geom_type == "MultiLineString" else inside
        if merged.geom_type != "LineString":
            return False
        inside = merged
    first = Point(inside.coords[0])
    last = Point(inside.coords[-1])
    start_pt = zone._point(*start)
    return math.isclose(min(first.distance(start_pt), last.distance(start_pt)), 0.0, abs_tol=1e-6)
