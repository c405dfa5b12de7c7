"""The operator REST API (FastAPI routers), mounted under /api/v1 by :mod:`gateway.app`."""

from __future__ import annotations

from fastapi import APIRouter, Depends

import gateway.api.fastapi_v1  # first: FastAPI's v1 checks, before any route is built
import gateway.util.lean_uvicorn  # noqa: F401  (before sse_starlette: uvicorn without its command line)
from gateway.api import (
    activity,
    cluster,
    control,
    declared,
    events,
    flights,
    geofences,
    missions,
    origins,
    params,
    vehicles,
)
from gateway.api.deps import authorize

API_PREFIX = "/api/v1"


def build_api_router(*beside: APIRouter) -> APIRouter:
    """All /api/v1 routes behind one authorisation dependency (the single place auth plugs in); ``beside``
    are routes of other parts served under the same prefix and auth (the console's configuration), so
    the API imports none of them."""
    api = APIRouter(prefix=API_PREFIX, dependencies=[Depends(authorize)])
    api.include_router(vehicles.router)
    api.include_router(flights.router)
    api.include_router(activity.router)
    api.include_router(control.router)
    api.include_router(declared.build_declared_router())
    api.include_router(missions.router)
    api.include_router(params.router)
    api.include_router(geofences.router)
    api.include_router(origins.router)
    api.include_router(cluster.router)
    api.include_router(events.router)
    for router in beside:
        api.include_router(router)
    return api
