"""Geofences over REST: keep-in / keep-out polygons (GeoJSON) for the whole fleet or for one drone.

Each change is one call of the verb `set_geofences` with the operator's caller
(`gateway.fleet.commands.zone_verbs`; the zones service, `gateway.fleet.policy.zones`, swaps in a
complete new set only when all of it is valid, and keeps ``GATEWAY_GEOFENCE_FILE`` current). What is
here is the request's schema and the routes.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Literal

from fastapi import APIRouter
from pydantic import BaseModel, ConfigDict, Field

from gateway.api.audit import AuditedRoute
from gateway.api.control import operator
from gateway.api.deps import CommanderDep, PrincipalDep
from gateway.fleet.policy.geofence import FLEET
from gateway.fleet.policy.zones import MAX_ZONES, GeofencesView, ZoneFeature
from gateway.util.json_types import JsonObject

router = APIRouter(tags=["geofences"], route_class=AuditedRoute)

_POSITION: JsonObject = {
    "type": "array",
    "description": "[longitude, latitude]",
    "prefixItems": [
        {"type": "number", "minimum": -180, "maximum": 180},
        {"type": "number", "minimum": -90, "maximum": 90},
    ],
    "minItems": 2,
    "maxItems": 3,
}
_RING: JsonObject = {
    "type": "array",
    "items": _POSITION,
    "minItems": 4,
    "description": "A closed ring: first = last",
}
_POLYGON: JsonObject = {"type": "array", "items": _RING, "minItems": 1}
#: what `Zone.from_geojson` accepts, as far as a schema can say it (a ring must also be closed, simple
#: and enclose an area: checked there, answered 422 with the zone's name)
GEOMETRY_SCHEMA: JsonObject = {
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
PROPERTIES_SCHEMA: JsonObject = {
    "type": "object",
    "description": "kind: keep_in | keep_out (required); name (unique); vehicle_id (fleet file only).",
    "required": ["kind"],
    "properties": {
        "kind": {"type": "string", "enum": ["keep_in", "keep_out"]},
        "name": {"type": "string", "minLength": 1, "pattern": r"\S"},
        "vehicle_id": {"type": "string"},
    },
}


def _schema(schema: JsonObject) -> Callable[[JsonObject], None]:
    """A field's ``json_schema_extra`` that puts ``schema`` in place of the one pydantic generates."""

    def replace(generated: JsonObject) -> None:
        generated.clear()
        generated.update(schema)

    return replace


class FeatureIn(ZoneFeature):
    """A zone as the request gives it (its schema for the API's documentation)."""

    model_config = ConfigDict(
        extra="allow", json_schema_extra={"required": ["type", "properties", "geometry"]}
    )

    properties: JsonObject | None = Field(None, json_schema_extra=_schema(PROPERTIES_SCHEMA))
    geometry: JsonObject = Field(json_schema_extra=_schema(GEOMETRY_SCHEMA))


class FeatureCollectionIn(BaseModel):
    model_config = ConfigDict(extra="allow")

    type: Literal["FeatureCollection"]
    features: list[FeatureIn] = Field(max_length=MAX_ZONES)


@router.get("/geofences", response_model=GeofencesView, summary="All geofence zones (fleet and per drone)")
async def list_geofences(commander: CommanderDep) -> GeofencesView:
    return commander.geofences()


@router.put("/fleet/geofences", response_model=GeofencesView, summary="Replace the fleet-wide geofence zones")
async def put_fleet_geofences(
    body: FeatureCollectionIn, commander: CommanderDep, who: PrincipalDep
) -> GeofencesView:
    return await commander.set_geofences(operator(who), FLEET, list(body.features))


@router.delete(
    "/fleet/geofences", response_model=GeofencesView, summary="Remove the fleet-wide geofence zones"
)
async def delete_fleet_geofences(commander: CommanderDep, who: PrincipalDep) -> GeofencesView:
    return await commander.set_geofences(operator(who), FLEET, [])


@router.put(
    "/vehicles/{vehicle_id}/geofences",
    response_model=GeofencesView,
    summary="Replace one drone's geofence zones",
)
async def put_vehicle_geofences(
    vehicle_id: str, body: FeatureCollectionIn, commander: CommanderDep, who: PrincipalDep
) -> GeofencesView:
    return await commander.set_geofences(operator(who), vehicle_id, list(body.features))


@router.delete(
    "/vehicles/{vehicle_id}/geofences",
    response_model=GeofencesView,
    summary="Remove one drone's geofence zones",
)
async def delete_vehicle_geofences(
    vehicle_id: str, commander: CommanderDep, who: PrincipalDep
) -> GeofencesView:
    return await commander.set_geofences(operator(who), vehicle_id, [])
