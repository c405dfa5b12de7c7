"""/healthz (the process answers) and /readyz (database open and registry started)."""

from __future__ import annotations

from fastapi import APIRouter, Request
from fastapi.responses import JSONResponse

router = APIRouter(tags=["health"])


@router.get("/healthz", summary="Liveness: the process answers")
async def healthz() -> dict[str, str]:
    return {"status": "ok"}


@router.get("/readyz", summary="Readiness: database open and vehicle registry started")
async def readyz(request: Request) -> JSONResponse:
    gateway = request.app.state.gateway
    checks = {
        "database": gateway.store is not None and gateway.store.is_open and await gateway.store.ping(),
        "registry": gateway.ready,
    }
    ready = all(checks.values())
    return JSONResponse(
        {"status": "ready" if ready else "not_ready", "checks": checks}, status_code=200 if ready else 503
    )
