"""/api/v1/sessions, /api/v1/audit, /api/v1/operations: who talked to the gateway and what they did."""

from __future__ import annotations

from typing import Annotated

from fastapi import APIRouter, Query

from gateway.api.audit import AuditedRoute
from gateway.api.deps import MAX_ROW, StoreDep
from gateway.api.schemas import AuditPage, IsoTime, OperationList, SessionList, time_window
from gateway.registry.store import OperationStatus, SessionKind

router = APIRouter(route_class=AuditedRoute)


@router.get("/sessions", response_model=SessionList, tags=["sessions"], summary="Sessions, recent first")
async def list_sessions(
    store: StoreDep,
    kind: Annotated[SessionKind | None, Query()] = None,
    principal: Annotated[str | None, Query(max_length=200)] = None,
    limit: Annotated[int, Query(ge=1, le=1000)] = 100,
    offset: Annotated[int, Query(ge=0, le=MAX_ROW)] = 0,
) -> SessionList:
    items = await store.list_sessions(kind=kind, principal=principal, limit=limit, offset=offset)
    return SessionList(items=items)


@router.get("/audit", response_model=AuditPage, tags=["audit"], summary="Audit entries, newest first")
async def list_audit(
    store: StoreDep,
    vehicle_id: Annotated[str | None, Query(max_length=32)] = None,
    session_key: Annotated[str | None, Query(max_length=200)] = None,
    since: Annotated[IsoTime | None, Query(description="Only entries at or after this time.")] = None,
    until: Annotated[IsoTime | None, Query(description="Only entries at or before this time.")] = None,
    include_fleet: Annotated[
        bool,
        Query(description="With vehicle_id: also the entries that name no single vehicle (fleet tools)."),
    ] = False,
    limit: Annotated[int, Query(ge=1, le=1000)] = 100,
    offset: Annotated[int, Query(ge=0, le=MAX_ROW)] = 0,
) -> AuditPage:
    since, until = time_window(since, until)
    items = await store.list_audit(
        vehicle_id, session_key, limit, offset, since=since, until=until, include_fleet=include_fleet
    )
    total = await store.count_audit(
        vehicle_id, session_key, since=since, until=until, include_fleet=include_fleet
    )
    return AuditPage(items=items, total=total, limit=limit, offset=offset)


@router.get(
    "/operations",
    response_model=OperationList,
    tags=["operations"],
    summary="Vehicle operations, newest first",
)
async def list_operations(
    store: StoreDep,
    vehicle_id: Annotated[str | None, Query(max_length=32)] = None,
    status: Annotated[OperationStatus | None, Query()] = None,
    limit: Annotated[int, Query(ge=1, le=500)] = 50,
) -> OperationList:
    return OperationList(items=await store.list_operations(vehicle_id, status=status, limit=limit))
