"""The operator REST API (FastAPI routers), mounted under /api/v1 by :mod:`gateway.app`."""

from __future__ import annotations

from fastapi import APIRouter, Depends

from gateway import console
from gateway.api import activity, cluster, control, events, flights, flying, geofences, missions, vehicles
from gateway.api.deps import authorize

API_PREFIX = "/api/v1"


def build_api_router() -> APIRouter:
    """All /api/v1 routes behind one authorisation dependency (the single place auth plugs in)."""
    api = APIRouter(prefix=API_PREFIX, dependencies=[Depends(authorize)])
    api.include_router(vehicles.router)
    api.include_router(flights.router)
    api.include_router(activity.router)
    api.include_router(control.router)
    api.include_router(flying.router)
    api.include_router(missions.router)
    api.include_router(geofences.router)
    api.include_router(cluster.router)
    api.include_router(events.router)
    api.include_router(console.router)
    return api
