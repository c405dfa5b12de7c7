"""Geofences over REST: keep-in / keep-out polygons (GeoJSON) for the whole fleet or for one drone.

The zones live in the safety policy's `GeofenceSet`; every change builds a complete new set first and
swaps it in only when all of it is valid (bad input changes nothing). When ``GATEWAY_GEOFENCE_FILE`` is
set, the file is rewritten (atomically) after each change, so the zones survive a restart; without it
they last until the gateway stops (the answer says ``persisted: false``).
"""

from __future__ import annotations

import json
import logging
import os
import tempfile
from pathlib import Path
from typing import Any, Literal

from fastapi import APIRouter
from pydantic import BaseModel, ConfigDict, Field

from gateway.api.audit import AuditedRoute
from gateway.api.deps import GatewayDep, PrincipalDep, RegistryDep
from gateway.errors import GatewayError, InvalidArgument
from gateway.fleet.policy.geofence import FLEET, GeofenceSet, Zone
from gateway.fleet.policy.safety import SafetyPolicy
from gateway.runtime import Gateway

log = logging.getLogger(__name__)

router = APIRouter(tags=["geofences"], route_class=AuditedRoute)

MAX_ZONES = 200


_POSITION = {
    "type": "array",
    "description": "[longitude, latitude]",
    "prefixItems": [
        {"type": "number", "minimum": -180, "maximum": 180},
        {"type": "number", "minimum": -90, "maximum": 90},
    ],
    "minItems": 2,
    "maxItems": 3,
}
_RING = {"type": "array", "items": _POSITION, "minItems": 4, "description": "A closed ring: first = last"}
_POLYGON = {"type": "array", "items": _RING, "minItems": 1}
#: what `Zone.from_geojson` accepts, as far as a schema can say it (a ring must also be closed, simple
#: and enclose an area: checked there, answered 422 with the zone's name)
GEOMETRY_SCHEMA: dict[str, Any] = {
    "description": "A GeoJSON Polygon or MultiPolygon ([lon, lat] pairs).",
    "oneOf": [
        {
            "type": "object",
            "required": ["type", "coordinates"],
            "properties": {"type": {"const": "Polygon"}, "coordinates": _POLYGON},
        },
        {
            "type": "object",
            "required": ["type", "coordinates"],
            "properties": {
                "type": {"const": "MultiPolygon"},
                "coordinates": {"type": "array", "items": _POLYGON, "minItems": 1},
            },
        },
    ],
}
PROPERTIES_SCHEMA: dict[str, Any] = {
    "type": "object",
    "description": "kind: keep_in | keep_out (required); name (unique); vehicle_id (fleet file only).",
    "required": ["kind"],
    "properties": {
        "kind": {"type": "string", "enum": ["keep_in", "keep_out"]},
        "name": {"type": "string", "minLength": 1, "pattern": r"\S"},
        "vehicle_id": {"type": "string"},
    },
}


def _schema(schema: dict[str, Any]) -> Any:
    def replace(generated: dict[str, Any]) -> None:
        generated.clear()
        generated.update(schema)

    return replace


class FeatureIn(BaseModel):
    model_config = ConfigDict(
        extra="allow", json_schema_extra={"required": ["type", "properties", "geometry"]}
    )

    type: Literal["Feature"]
    properties: dict[str, Any] | None = Field(None, json_schema_extra=_schema(PROPERTIES_SCHEMA))
    geometry: dict[str, Any] = Field(json_schema_extra=_schema(GEOMETRY_SCHEMA))


class FeatureCollectionIn(BaseModel):
    model_config = ConfigDict(extra="allow")

    type: Literal["FeatureCollection"]
    features: list[FeatureIn] = Field(max_length=MAX_ZONES)


class GeofencesOut(BaseModel):
    type: Literal["FeatureCollection"] = "FeatureCollection"
    features: list[dict[str, Any]]
    persisted: bool = Field(description="Whether the zones are saved to GATEWAY_GEOFENCE_FILE.")


def _feature(zone: Zone) -> dict[str, object]:
    props: dict[str, object] = {"kind": zone.kind, "name": zone.name}
    if zone.scope != FLEET:
        props["vehicle_id"] = zone.scope
    return {"type": "Feature", "properties": props, "geometry": zone.geojson}


def _policy(gateway: Gateway) -> SafetyPolicy:
    return gateway.require_safety()


def geofences_out(gateway: Gateway) -> GeofencesOut:
    zones = sorted(_policy(gateway).geofences, key=lambda z: (z.scope != FLEET, z.scope, z.name))
    return GeofencesOut(features=[_feature(z) for z in zones], persisted=bool(gateway.settings.geofence_file))


def _zones_of(body: FeatureCollectionIn, scope: str) -> list[Zone]:
    zones = []
    for index, feature in enumerate(body.features):
        props = feature.properties or {}
        name = props.get("name") or f"{'fleet' if scope == FLEET else scope}-zone-{index + 1}"
        owner = props.get("vehicle_id")
        if owner not in (None, scope if scope != FLEET else None):
            raise InvalidArgument(
                f"geofence '{name}' names vehicle_id {owner!r}; zones set here apply to "
                f"{'the whole fleet' if scope == FLEET else scope}: use PUT /api/v1/vehicles/{{id}}/geofences"
            )
        kind = props.get("kind")
        if not isinstance(kind, str):
            raise InvalidArgument(f"geofence '{name}' needs properties.kind: keep_in or keep_out")
        if not isinstance(name, str):
            raise InvalidArgument(f"geofence name must be a string; got {name!r}")
        zones.append(Zone.from_geojson(name, kind, feature.geometry, scope))
    return zones


def _save(gateway: Gateway, fences: GeofenceSet) -> None:
    path = gateway.settings.geofence_file
    if not path:
        return
    document = {"type": "FeatureCollection", "features": [_feature(z) for z in fences]}
    target = Path(path)
    fd, tmp = tempfile.mkstemp(dir=target.parent, prefix=f".{target.name}.")
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as handle:
            json.dump(document, handle, indent=1)
        os.replace(tmp, target)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


def replace_zones(gateway: Gateway, scope: str, zones: list[Zone], who: str) -> GeofencesOut:
    """Swap in a new set: the other scopes' zones kept, this scope's replaced by ``zones``."""
    policy = _policy(gateway)
    kept = [z for z in policy.geofences if z.scope != scope]
    fences = GeofenceSet([*kept, *zones])  # raises on duplicate names: nothing changed yet
    try:
        _save(gateway, fences)
    except OSError as exc:
        raise GatewayError(f"could not write GATEWAY_GEOFENCE_FILE: {exc}") from exc
    policy.geofences = fences
    what = "the fleet" if scope == FLEET else scope
    log.warning("operator %s set %d geofence zone(s) for %s", who, len(zones), what)
    return geofences_out(gateway)


@router.get("/geofences", response_model=GeofencesOut, summary="All geofence zones (fleet and per drone)")
async def list_geofences(gateway: GatewayDep) -> GeofencesOut:
    return geofences_out(gateway)


@router.put("/fleet/geofences", response_model=GeofencesOut, summary="Replace the fleet-wide geofence zones")
async def put_fleet_geofences(
    body: FeatureCollectionIn, gateway: GatewayDep, who: PrincipalDep
) -> GeofencesOut:
    return replace_zones(gateway, FLEET, _zones_of(body, FLEET), who.name)


@router.delete(
    "/fleet/geofences", response_model=GeofencesOut, summary="Remove the fleet-wide geofence zones"
)
async def delete_fleet_geofences(gateway: GatewayDep, who: PrincipalDep) -> GeofencesOut:
    return replace_zones(gateway, FLEET, [], who.name)


@router.put(
    "/vehicles/{vehicle_id}/geofences",
    response_model=GeofencesOut,
    summary="Replace one drone's geofence zones",
)
async def put_vehicle_geofences(
    vehicle_id: str, body: FeatureCollectionIn, gateway: GatewayDep, registry: RegistryDep, who: PrincipalDep
) -> GeofencesOut:
    registry.get(vehicle_id)  # UnknownVehicle names the known ids
    return replace_zones(gateway, vehicle_id, _zones_of(body, vehicle_id), who.name)


@router.delete(
    "/vehicles/{vehicle_id}/geofences",
    response_model=GeofencesOut,
    summary="Remove one drone's geofence zones",
)
async def delete_vehicle_geofences(
    vehicle_id: str, gateway: GatewayDep, registry: RegistryDep, who: PrincipalDep
) -> GeofencesOut:
    registry.get(vehicle_id)
    return replace_zones(gateway, vehicle_id, [], who.name)
