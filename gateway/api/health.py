"""/healthz (the process answers) and /readyz (database open and registry started)."""

from __future__ import annotations

from fastapi import APIRouter, Request
from fastapi.responses import JSONResponse

router = APIRouter(tags=["health"])

_READINESS = {
    "type": "object",
    "required": ["status", "checks"],
    "properties": {
        "status": {"type": "string", "enum": ["ready", "not_ready"]},
        "checks": {
            "type": "object",
            "properties": {"database": {"type": "boolean"}, "registry": {"type": "boolean"}},
            "additionalProperties": {"type": "boolean"},
        },
    },
}
_READINESS_BODY = {"application/json": {"schema": _READINESS}}


@router.get("/healthz", summary="Liveness: the process answers")
async def healthz() -> dict[str, str]:
    return {"status": "ok"}


@router.get(
    "/readyz",
    summary="Readiness: database open and vehicle registry started",
    responses={
        200: {"content": _READINESS_BODY},
        503: {"description": "Not ready: the checks say which part is not", "content": _READINESS_BODY},
    },
)
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
