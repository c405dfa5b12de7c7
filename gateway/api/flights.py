"""/api/v1/flights: flown flights (arm to disarm) and their tracks as GeoJSON, KML and MAVLink telemetry
logs (the formats: `gateway.fleet.missions.flight_export`)."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path as FilePath
from typing import Annotated

from fastapi import APIRouter, Path, Query
from fastapi.responses import JSONResponse, Response, StreamingResponse

from gateway.api.audit import AuditedRoute
from gateway.api.deps import MAX_ROW, GatewayDep, RegistryDep, StoreDep
from gateway.api.schemas import FlightPage, IsoTime, StatusTextList, time_window
from gateway.errors import NotFound, UnknownVehicle
from gateway.fleet.missions.flight_export import track_feature, track_kml, track_tlog
from gateway.fleet.missions.raw_tlog import tlog_file, tlog_folder, was_cut
from gateway.registry.store import FlightRecord, Store, TrackSample

FlightId = Annotated[int, Path(ge=1, le=MAX_ROW, description="Flight id.")]

router = APIRouter(prefix="/flights", tags=["flights"], route_class=AuditedRoute)

GEOJSON_MEDIA_TYPE = "application/geo+json"
KML_MEDIA_TYPE = "application/vnd.google-earth.kml+xml"
TLOG_MEDIA_TYPE = "application/octet-stream"


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
    since, until = time_window(since, until)
    items, total = await store.list_flights(vehicle_id, since, until, limit=limit, offset=offset)
    return FlightPage(items=items, total=total, limit=limit, offset=offset)


async def _flight(store: Store, flight_id: int) -> FlightRecord:
    flight = await store.get_flight(flight_id)
    if flight is None:
        raise NotFound(f"no flight with id {flight_id}", id=flight_id)
    return flight


async def _flown(store: Store, flight_id: int) -> tuple[FlightRecord, list[TrackSample]]:
    """A flight and its track (the track exports render both); NotFound when there is no such flight."""
    return await _flight(store, flight_id), await store.get_track(flight_id)


@router.get("/{flight_id}", response_model=FlightRecord, summary="One flight with its summary figures")
async def get_flight(flight_id: FlightId, store: StoreDep) -> FlightRecord:
    return await _flight(store, flight_id)


@router.get(
    "/{flight_id}/track.geojson",
    summary="The flight's track as a GeoJSON Feature (LineString)",
    response_class=JSONResponse,
    responses={200: {"content": {GEOJSON_MEDIA_TYPE: {}}}},
)
async def flight_track(flight_id: FlightId, store: StoreDep) -> JSONResponse:
    flight, track = await _flown(store, flight_id)
    return JSONResponse(track_feature(flight, track), media_type=GEOJSON_MEDIA_TYPE)


def _file_part(path: FilePath, size: int) -> Iterator[bytes]:
    """The first ``size`` bytes of ``path`` in 64 KiB chunks (run in a worker thread)."""
    with path.open("rb") as file:
        left = size
        while left > 0:
            chunk = file.read(min(left, 65536))
            if not chunk:
                return
            left -= len(chunk)
            yield chunk


def _attachment(name: str) -> dict[str, str]:
    return {"Content-Disposition": f'attachment; filename="{name}"'}


@router.get(
    "/{flight_id}/track.kml",
    summary="The flight's track as KML (Google Earth, GIS tools), altitudes above mean sea level",
    response_class=Response,
    responses={200: {"content": {KML_MEDIA_TYPE: {}}}},
)
async def flight_kml(flight_id: FlightId, store: StoreDep) -> Response:
    flight, track = await _flown(store, flight_id)
    return Response(
        track_kml(flight, track),
        media_type=KML_MEDIA_TYPE,
        headers=_attachment(f"{flight.vehicle_id}-flight-{flight_id}.kml"),
    )


TLOG_SOURCE_HEADER = "X-Tlog-Source"
TLOG_CUT_HEADER = "X-Tlog-Cut"


@router.get(
    "/{flight_id}/tlog",
    summary="The flight as a MAVLink telemetry log (.tlog: QGroundControl, Mission Planner, MAVExplorer)",
    description="The frames the drone sent during the flight, as received, each after its 8-byte "
    "big-endian receive time in microseconds (header X-Tlog-Source: autopilot; X-Tlog-Cut: true when "
    "the log reached flight_tlog_max_mib). A flight without a raw log on this node (recorded before, "
    "with flight_tlog_dir none, or on another node) is written from its 1 Hz track and status texts "
    "instead (X-Tlog-Source: reconstructed): HEARTBEAT, GPS_RAW_INT, GLOBAL_POSITION_INT, VFR_HUD and "
    "SYS_STATUS per sample, STATUSTEXT at its time.",
    response_class=Response,
    responses={
        200: {
            "content": {TLOG_MEDIA_TYPE: {}},
            "headers": {
                TLOG_SOURCE_HEADER: {
                    "description": "autopilot: the drone's own frames; reconstructed: from the 1 Hz track",
                    "schema": {"type": "string", "enum": ["autopilot", "reconstructed"]},
                },
                TLOG_CUT_HEADER: {
                    "description": "true: the raw log reached its cap and later frames are missing",
                    "schema": {"type": "string", "enum": ["true", "false"]},
                },
            },
        }
    },
)
async def flight_tlog(
    flight_id: FlightId, store: StoreDep, registry: RegistryDep, gateway: GatewayDep
) -> Response:
    flight = await _flight(store, flight_id)
    name = f"{flight.vehicle_id}-flight-{flight_id}.tlog"
    folder = tlog_folder(gateway.settings, store.url)
    raw = tlog_file(folder, flight.vehicle_id, flight_id) if folder is not None else None
    if raw is not None and raw.is_file():
        size = raw.stat().st_size  # a flight in progress: what is written now
        headers = {
            **_attachment(name),
            "Content-Length": str(size),
            TLOG_SOURCE_HEADER: "autopilot",
            TLOG_CUT_HEADER: "true" if was_cut(raw, gateway.settings) else "false",
        }
        return StreamingResponse(_file_part(raw, size), media_type=TLOG_MEDIA_TYPE, headers=headers)
    track = await store.get_track(flight_id)
    texts = await store.list_flight_status_texts(flight_id, limit=1000)
    vehicle = await store.get_vehicle(flight.vehicle_id)
    sysid, autopilot = (vehicle.expected_sysid if vehicle else None) or 1, None
    try:
        status = registry.get(flight.vehicle_id).status()
        heard, named = status.get("sysid"), status.get("autopilot")
        sysid = heard if isinstance(heard, int) and heard else sysid
        autopilot = named if isinstance(named, str) else None
    except UnknownVehicle:
        pass
    data = track_tlog(flight, track, texts, sysid=sysid, autopilot=autopilot)
    headers = {**_attachment(name), TLOG_SOURCE_HEADER: "reconstructed", TLOG_CUT_HEADER: "false"}
    return Response(data, media_type=TLOG_MEDIA_TYPE, headers=headers)


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
