"""Audit of REST calls: every state-changing request (POST, PUT, PATCH, DELETE) is written to the
audit table with source 'rest', the caller, the vehicle, the arguments, the outcome and the duration.

A call that starts an operation (a land, a goto...: the command pass names it through ``AUDIT_SENT``)
is written running, naming the operation and timed from the call; the store finishes the row when the
operation ends, with its outcome and the whole time to that end (not the few milliseconds the request
took to send it), as it does for the MCP door's calls.

Reads are not audited: dashboards poll them and they change nothing. Routers opt in by using
:class:`AuditedRoute` as their ``route_class``.
"""

from __future__ import annotations

import asyncio
import json
import logging
import re
import time
from collections.abc import Callable, Coroutine
from datetime import datetime
from typing import Any

from fastapi import Request, Response
from fastapi.exceptions import RequestValidationError
from fastapi.routing import APIRoute
from starlette.exceptions import HTTPException as StarletteHTTPException

from gateway.errors import GatewayError, SafetyRefusal
from gateway.fleet.commands.command_pass import AUDIT_SENT
from gateway.registry.spec import redacted
from gateway.registry.store import AuditEntry, utcnow

log = logging.getLogger(__name__)

AUDITED_METHODS = frozenset({"POST", "PUT", "PATCH", "DELETE"})

Handler = Callable[[Request], Coroutine[Any, Any, Response]]  # Any: FastAPI, get_route_handler's


async def _arguments(request: Request) -> dict[str, object]:
    args: dict[str, object] = dict(request.path_params)
    if request.query_params:
        args["query"] = dict(request.query_params)
    try:
        raw = await request.body()
    except Exception:  # the body could not be read (e.g. too large): audit without it
        return args
    if raw:
        try:
            body = json.loads(raw)
        except (ValueError, RecursionError):  # not JSON, or nested too deeply to read: kept as text
            body = raw[:500].decode("utf-8", errors="replace")
        try:
            args["body"] = _without_credentials(body)
        except RecursionError:  # nested too deeply to walk: kept as text, credentials cut out
            args["body"] = _CREDENTIALS.sub("://***@", raw[:500].decode("utf-8", errors="replace"))
    note = getattr(request.state, "audit_note", None)
    if isinstance(note, dict):
        args.update(note)
    return args


_CREDENTIALS = re.compile(r"://[^/@\s\"']*@")


def _without_credentials(value: object) -> object:
    """The body as the audit keeps it: any URL's credentials (``user:pw@``, refused anyway) replaced."""
    if isinstance(value, str):
        return redacted(value)
    if isinstance(value, list):
        return [_without_credentials(v) for v in value]
    if isinstance(value, dict):
        return {k: _without_credentials(v) for k, v in value.items()}
    return value


def _vehicle_id(request: Request, args: dict[str, object]) -> str | None:
    vid = request.path_params.get("vehicle_id")
    body = args.get("body")
    if vid is None and isinstance(body, dict):
        body_id = body.get("id")
        vid = body_id if isinstance(body_id, str) else None
    return vid[:32] if isinstance(vid, str) else None


async def record_rest_call(
    request: Request,
    action: str,
    outcome: str,
    error: str | None,
    started: float,
    operation: tuple[str, datetime] | None = None,
) -> None:
    """Write one audit row (and touch the caller's REST session); never fails the request.
    ``operation``: the id of the operation the call started and when the call came (the row is then
    written running, from that time, for the store to finish when the operation ends)."""
    duration_ms = (time.perf_counter() - started) * 1000.0
    gateway = request.app.state.gateway
    store = gateway.store
    if store is None or not store.is_open:
        return
    principal = getattr(request.state, "principal", None)
    try:
        args = await _arguments(request)
        session_key = principal.session_key if principal else None
        # the session's last-seen time is a courtesy, written without the spool: skipped while the
        # database is known not to answer (no answer, an emergency stop's least, waits on it); the audit
        # row below is kept until the database is back
        if principal is not None and not store.spool.unreachable:
            try:
                await store.touch_session(session_key, principal.door, principal=principal.name)
            except Exception:
                log.warning("could not record the REST session of %s", principal.name)
        await store.add_audit(
            AuditEntry(
                session_key=session_key,
                principal=principal.name if principal else None,
                source=principal.door if principal else "rest",
                vehicle_id=_vehicle_id(request, args),
                action=action,
                arguments=args,
                outcome=outcome,
                error=error,
                duration_ms=duration_ms,
                operation_id=None if operation is None else operation[0],
                t=None if operation is None else operation[1],
            )
        )
    except Exception:
        log.exception("could not write the audit entry of %s %s", request.method, request.url.path)


#: the routes whose answer never waits long on its audit row: the emergency stop (its drones are told
#: before it is recorded; a database that hangs must not hold the operator's answer either)
STOP_ACTIONS = frozenset({"rest.fleet_stop"})
#: how long the emergency stop's answer waits for its audit row (the write goes on beside it)
STOP_AUDIT_WAIT_S = 0.5
_RECORDING: set[asyncio.Task[None]] = set()


async def _recorded(action: str, record: Coroutine[object, object, None]) -> None:
    """Record a call; the emergency stop's answer waits STOP_AUDIT_WAIT_S for it at most."""
    if action not in STOP_ACTIONS:
        await record
        return
    task = asyncio.create_task(record, name=f"audit-{action}")
    _RECORDING.add(task)  # it may outlive the request (a database that hangs)
    task.add_done_callback(_RECORDING.discard)
    await asyncio.wait({task}, timeout=STOP_AUDIT_WAIT_S)


def _failure(exc: Exception) -> tuple[str, str]:
    """The audit outcome and error of a call that raised ``exc``."""
    if isinstance(exc, SafetyRefusal):
        return "refused", f"{exc.code}: {exc.message}"
    if isinstance(exc, GatewayError):
        return "error", f"{exc.code}: {exc.message}"
    if isinstance(exc, RequestValidationError):
        summary = "; ".join(str(e.get("msg")) for e in list(exc.errors())[:3])
        return "error", f"validation_error: {summary}"
    if isinstance(exc, StarletteHTTPException):
        return "error", f"http_{exc.status_code}"
    return "error", f"internal_error: {exc!r}"[:500]


def note_unchecked(request: Request, unchecked: object) -> None:
    """An operator's mission with items the gateway cannot check: said in the call's audit row."""
    if isinstance(unchecked, list) and unchecked:
        note = getattr(request.state, "audit_note", None) or {}
        request.state.audit_note = {**note, "unchecked": [str(u) for u in unchecked]}


class AuditedRoute(APIRoute):
    """An APIRoute that audits its state-changing calls; the action is the route's name."""

    def get_route_handler(self) -> Handler:
        handler = super().get_route_handler()
        action = f"rest.{self.name}"

        async def audited(request: Request) -> Response:
            if request.method not in AUDITED_METHODS:
                return await handler(request)
            started, called_at = time.perf_counter(), utcnow()
            operations: list[str] = []

            def sent(operation_id: str) -> None:
                operations.append(operation_id)

            async def record(outcome: str, error: str | None) -> None:
                await _recorded(action, record_rest_call(request, action, outcome, error, started))

            noting = AUDIT_SENT.set(sent)
            try:
                response = await handler(request)
            except Exception as exc:
                await record(*_failure(exc))
                raise
            finally:
                AUDIT_SENT.reset(noting)
            # one drone's operation: the row runs until it ends. A fleet call (the emergency stop among
            # them) starts one per drone, some on other nodes: its row says it was sent, as its answer does
            if response.status_code < 400 and len(operations) == 1 and action not in STOP_ACTIONS:
                started_op = (operations[0], called_at)
                await record_rest_call(request, action, "running", None, started, started_op)
                return response
            outcome = "ok" if response.status_code < 400 else "error"
            error = None if outcome == "ok" else f"http_{response.status_code}"
            await record(outcome, error)
            return response

        return audited
