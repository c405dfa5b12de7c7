"""/api/v1/flights: flown flights (arm to disarm) and their tracks as GeoJSON."""

from __future__ import annotations

from typing import Annotated, Any

from fastapi import APIRouter, Path, Query
from fastapi.responses import JSONResponse

from gateway.api.audit import AuditedRoute
from gateway.api.deps import MAX_ROW, StoreDep
from gateway.api.schemas import FlightPage, IsoTime, StatusTextList, as_utc
from gateway.errors import InvalidArgument, NotFound
from gateway.registry.store import FlightRecord, Store, TrackSample

FlightId = Annotated[int, Path(ge=1, le=MAX_ROW, description="Flight id.")]

router = APIRouter(prefix="/flights", tags=["flights"], route_class=AuditedRoute)

GEOJSON_MEDIA_TYPE = "application/geo+json"


@router.get("", response_model=FlightPage, summary="Flights, newest first, filtered by vehicle and time")
async def list_flights(
    store: StoreDep,
    vehicle_id: Annotated[str | None, Query(description="Only this vehicle's flights.")] = None,
    since: Annotated[
        IsoTime | None, Query(description="Flights still in the air at or after this time.")
    ] = None,
    until: Annotated[IsoTime | None, Query(description="Flights started at or before this time.")] = None,
    limit: Annotated[int, Query(ge=1, le=500)] = 50,
    offset: Annotated[int, Query(ge=0, le=MAX_ROW)] = 0,
) -> FlightPage:
    since, until = as_utc(since), as_utc(until)
    if since is not None and until is not None and since > until:
        raise InvalidArgument(f"since ({since.isoformat()}) is after until ({until.isoformat()})")
    items, total = await store.list_flights(vehicle_id, since, until, limit=limit, offset=offset)
    return FlightPage(items=items, total=total, limit=limit, offset=offset)


async def _flight(store: Store, flight_id: int) -> FlightRecord:
    flight = await store.get_flight(flight_id)
    if flight is None:
        raise NotFound(f"no flight with id {flight_id}", id=flight_id)
    return flight


@router.get("/{flight_id}", response_model=FlightRecord, summary="One flight with its summary figures")
async def get_flight(flight_id: FlightId, store: StoreDep) -> FlightRecord:
    return await _flight(store, flight_id)


def track_feature(flight: FlightRecord, track: list[TrackSample]) -> dict[str, Any]:
    """A GeoJSON Feature: LineString [lon, lat, alt_rel_m] with per-point arrays in the properties.

    The per-point arrays run parallel to the coordinates (``times`` as ISO 8601, like the common
    ``coordTimes`` convention). A track of one point is a Point, an empty one has no geometry.
    """
    coordinates = [[s.lon, s.lat, s.alt_rel_m] if s.alt_rel_m is not None else [s.lon, s.lat] for s in track]
    if len(coordinates) >= 2:
        geometry: dict[str, Any] | None = {"type": "LineString", "coordinates": coordinates}
    elif coordinates:
        geometry = {"type": "Point", "coordinates": coordinates[0]}
    else:
        geometry = None
    properties: dict[str, Any] = flight.model_dump(mode="json")
    properties["flight_id"] = properties.pop("id")
    properties["sample_count"] = len(track)
    properties["altitude_reference"] = "metres above home"
    properties["times"] = [s.t.isoformat() for s in track]
    for name in ("alt_rel_m", "heading_deg", "ground_speed_mps", "battery_pct"):
        properties[name] = [getattr(s, name) for s in track]
    return {"type": "Feature", "id": flight.id, "geometry": geometry, "properties": properties}


@router.get(
    "/{flight_id}/track.geojson",
    summary="The flight's track as a GeoJSON Feature (LineString)",
    response_class=JSONResponse,
    responses={200: {"content": {GEOJSON_MEDIA_TYPE: {}}}},
)
async def flight_track(flight_id: FlightId, store: StoreDep) -> JSONResponse:
    flight = await _flight(store, flight_id)
    track = await store.get_track(flight_id)
    return JSONResponse(track_feature(flight, track), media_type=GEOJSON_MEDIA_TYPE)


@router.get(
    "/{flight_id}/statustexts",
    response_model=StatusTextList,
    summary="The STATUSTEXT messages received during a flight, oldest first",
)
async def flight_status_texts(
    flight_id: FlightId,
    store: StoreDep,
    limit: Annotated[int, Query(ge=1, le=1000, description="At most this many (the first ones).")] = 500,
) -> StatusTextList:
    flight = await _flight(store, flight_id)
    items = await store.list_flight_status_texts(flight_id, limit=limit)
    return StatusTextList(vehicle_id=flight.vehicle_id, items=items)
