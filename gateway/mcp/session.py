"""Who is talking (MCP sessions, both protocol eras) and the audit record of every tool call.

- 2025-era clients (initialize handshake): the session is the Mcp-Session-Id, with the client name and
  version from initialize.
- 2026-07-28 clients (stateless, no session id): the session is the caller's identity (token principal)
  plus the clientInfo sent in each request's ``_meta``; first and last seen are kept by the store.

Both are recorded through ``Store.touch_session``; every ``tools/call`` through ``Store.queue_audit``
(its row and its session's touch, written off the request path in batches), from this one middleware,
including calls rejected before the tool ran (unknown tool, invalid arguments). A call whose command
starts an operation on a drone has its row written the moment the command pass sends it
(`gateway.fleet.commands.command_pass.AUDIT_SENT`: outcome running, naming the operation), and the store
completes the row when the operation ends; every other call's row is written when the call ends.

A call of a tool that commands a drone (a verb's tool; not a read: monitor_flight) has its row written
before anything is sent, once the SDK has taken its arguments and before the tool runs
(`Store.audit_call`: outcome running; a call refused for its arguments sent nothing, and its row is
queued when it ends, as a read's is), waited for up to `CALL_ROW_WAIT_S` (a database that hangs does
not hold the command longer; the write goes on), except for the stops (land,
return, hold, kill, disarm and their fleet forms), which are sent at once with their row written beside
them; the call's end (or the operation it started) is written before the call is answered
(`CALL_END_WAIT_S`: in the database, or in the spool file). So a node killed while or just after it ran
the call keeps its row.
"""

from __future__ import annotations

import logging
import os
import time
from dataclasses import dataclass

import anyio
from mcp.server.auth.middleware.auth_context import get_access_token
from pydantic import BaseModel

from gateway.fleet.commands.command_core import READ_VERBS, TOOLS
from gateway.fleet.commands.command_pass import AUDIT_SENT
from gateway.fleet.operations.routing import ACTING
from gateway.fleet.policy.caller import Caller
from gateway.mcp.access import CallInfo, FleetState, current_call
from gateway.mcp.sdk_types import CallNext, HandlerResult, RequestContext
from gateway.registry.audit_kept import SessionSeen
from gateway.registry.records import AUDIT_OUTCOME_OF_OPERATION, AuditEntry, SessionKind
from gateway.registry.spool import WRITE_TIMEOUT_S
from gateway.registry.store import Store
from gateway.registry.store_audit import AuditCall

log = logging.getLogger(__name__)

CLIENT_INFO_META = "io.modelcontextprotocol/clientInfo"
TOUCH_EVERY_S = 5.0
"""A session's last_seen is refreshed at most this often (and on every tool call)."""
CALL_ROW_WAIT_S = 1.0
"""A call that commands a drone waits this long at most for its audit row before the command is sent (a
database that hangs does not hold the command longer; the write goes on)."""
CALL_END_WAIT_S = WRITE_TIMEOUT_S + 1.0
"""...and this long at most for its end (and its row) before it is answered: until both are in the
database, or kept in the node's spool file once the database has not answered within the spool's time, so
a node killed just after answering keeps the call's row and outcome."""
#: the verbs whose tools stop drones: sent without waiting for their audit row (it is written beside them)
STOP_VERBS = frozenset(
    {"land", "return_to_launch", "hold", "kill", "disarm"}
    | {"fleet_hold", "fleet_land", "fleet_return_to_launch"}
)


@dataclass(frozen=True)
class SessionInfo:
    key: str
    kind: SessionKind
    principal: str
    client_name: str | None
    client_version: str | None


def _principal(is_http: bool) -> str:
    token = get_access_token()
    if token is not None:
        return token.subject or token.client_id
    return "anonymous" if is_http else "local"


def session_info(ctx: RequestContext) -> SessionInfo:
    """The session of one inbound MCP message (``ServerRequestContext``)."""
    request = getattr(ctx, "request", None)
    headers = getattr(request, "headers", None)
    principal = _principal(headers is not None)
    version = str(ctx.protocol_version or "")
    if version >= "2026-":
        meta = ctx.meta or {}
        info = meta.get(CLIENT_INFO_META) if hasattr(meta, "get") else None
        info = info if isinstance(info, dict) else {}
        name, ver = info.get("name"), info.get("version")
        key = f"{principal}|{name or 'unknown'}/{ver or '?'}"
        return SessionInfo(key[:200], "mcp-2026", principal, name, ver)
    params = getattr(ctx.session, "client_params", None)
    client = getattr(params, "client_info", None)
    name = getattr(client, "name", None)
    ver = getattr(client, "version", None)
    sid = headers.get("mcp-session-id") if headers is not None else None
    key = sid or f"stdio-{os.getpid()}"  # stdio: one client per server process
    return SessionInfo(key, "mcp-2025", principal, name, ver)


class SessionAudit:
    """MCP server middleware: session bookkeeping for every message, audit rows for tool calls. The
    store comes from the server's lifespan state (`FleetState`)."""

    def __init__(self) -> None:
        self._touched: dict[str, tuple[float, str | None]] = {}

    async def __call__(self, ctx: RequestContext, call_next: CallNext) -> HandlerResult:
        if ctx.method == "initialize":
            return await call_next(ctx)  # no session id yet; recorded from the next message on
        state = ctx.lifespan_context
        running = isinstance(state, FleetState) and state.gateway.ready
        store = state.gateway.store if running else None
        info = session_info(ctx)
        is_call = ctx.method == "tools/call" and ctx.request_id is not None
        if not is_call:  # a call's touch of its session is written with its audit row
            await self._touch(store, info)
        # who acts in this request: the Commander's registry shows an agent only its scope of vehicles
        acting = ACTING.set(Caller(via="mcp", principal=info.principal, session=info.key))
        try:
            if not is_call:
                return await call_next(ctx)
            return await self._call(ctx, call_next, info, store)
        finally:
            ACTING.reset(acting)

    async def _call(
        self,
        ctx: RequestContext,
        call_next: CallNext,
        info: SessionInfo,
        store: Store | None,
    ) -> HandlerResult:
        params = ctx.params or {}
        arguments = params.get("arguments") or {}
        call = CallInfo(session_key=info.key, principal=info.principal, vehicle_id=_drone_id(arguments))
        token = current_call.set(call)
        tool = str(params.get("name", "?"))
        audited = _AuditedCall(store, info, call, tool, arguments, started=time.perf_counter())
        written: list[str] = []
        row: AuditCall | None = None

        async def before_tool() -> None:
            """The SDK took the arguments and the tool is about to run: the row of a call that commands a
            drone, written now. A call refused for its arguments never gets here (it sent nothing): its
            row is queued when it ends, as a read's, without a database write on its way."""
            nonlocal row
            call.before_tool = None  # once
            row = self._begin(audited)
            if row is not None and TOOLS[tool].verb not in STOP_VERBS:
                await row.written(CALL_ROW_WAIT_S)

        call.before_tool = before_tool

        def sent(operation_id: str) -> None:
            """The command pass sent the call's operation: its row now, running; the store completes it
            when the operation ends (a crash while it flies loses no call)."""
            if row is not None:
                written.append(operation_id)
                row.operation(operation_id)
            elif not written:
                written.append(operation_id)
                self._audit(audited, "running", None, operation_id)

        audit_sent = AUDIT_SENT.set(sent)
        result: HandlerResult = None
        failure: BaseException | None = None
        try:
            result = await call_next(ctx)
            return result
        except BaseException as exc:
            failure = exc
            raise
        finally:
            AUDIT_SENT.reset(audit_sent)
            current_call.reset(token)
            if row is not None:
                await self._end(row, audited, result, failure, written)
            elif not written:
                self._audit_end(audited, result, failure)

    def _begin(self, audited: _AuditedCall) -> AuditCall | None:
        """The row of a call of a tool that commands a drone, started before anything is sent."""
        store = audited.store
        if store is None or audited.tool not in TOOLS or TOOLS[audited.tool].verb in READ_VERBS:
            return None  # (a read commands nothing: its row is written when it ends)
        self._note_touched(audited.info)
        try:
            return store.audit_call(audited.entry("running"), audited.seen())
        except Exception:
            log.exception("could not start the audit row of %s", audited.tool)
            return None

    @staticmethod
    async def _end(
        row: AuditCall,
        audited: _AuditedCall,
        result: HandlerResult,
        failure: BaseException | None,
        written: list[str],
    ) -> None:
        """The end of a call whose row was written before it ran: its outcome; or, when it started an
        operation, that operation (whose end finishes the row). Waited for up to CALL_END_WAIT_S."""
        call = audited.call
        took_ms = round((time.perf_counter() - audited.started) * 1000.0, 1)
        operation_id: str | None
        error: str | None
        ended = _ended_operation(result) if written and failure is None else None
        if ended is not None:  # the call waited for its operation's end: recorded now, not left to it
            outcome, error, operation_id = (*ended, written[0])
        elif written and failure is None and _outcome(call, result, None)[0] == "error":
            # answered as an error after its operation was sent (its owner gave the drone up while it
            # ran): the call's end is that answer, whatever becomes of the operation
            outcome, error = _outcome(call, result, None)
            operation_id = written[0]
        elif written:
            outcome, error, operation_id = "running", None, written[0]
        else:
            outcome, error = _outcome(call, result, failure)
            operation_id = _operation_id(result) if outcome == "running" else None
        try:
            await row.end(outcome, error and error[:1000], took_ms, CALL_END_WAIT_S, operation_id)
        except Exception:
            log.exception("could not finish the audit row of call %s", row.id)

    def _audit_end(self, audited: _AuditedCall, result: HandlerResult, failure: BaseException | None) -> None:
        """The row of a call that sent no operation (a read, a refusal, an instant command, a fleet
        command: its operation is started by the fleet engine), written when it ends. A call that
        returns while an operation runs (wait:false) names it: when the operation ends, on whichever
        node runs it then, the store finishes the row (Store.save_operation)."""
        outcome, error = _outcome(audited.call, result, failure)
        operation_id = _operation_id(result) if outcome == "running" else None
        self._audit(audited, outcome, error, operation_id)

    def _note_touched(self, info: SessionInfo) -> None:
        if len(self._touched) > 10_000:
            self._touched.clear()
        self._touched[info.key] = (time.monotonic(), info.client_name)

    async def _touch(self, store: Store | None, info: SessionInfo) -> None:
        if store is None:
            return
        last = self._touched.get(info.key)
        if last is not None and time.monotonic() - last[0] < TOUCH_EVERY_S and last[1] == info.client_name:
            return
        self._note_touched(info)
        try:
            await store.touch_session(
                info.key,
                info.kind,
                principal=info.principal,
                client_name=info.client_name,
                client_version=info.client_version,
            )
        except Exception:
            log.exception("could not record MCP session %s", info.key)

    def _audit(
        self, audited: _AuditedCall, outcome: str, error: str | None, operation_id: str | None = None
    ) -> None:
        """Queue the call's audit row with the touch of its session (written off the request path, in
        batches: `Store.queue_audit`)."""
        if audited.store is None:
            return
        self._note_touched(audited.info)
        try:
            entry = audited.entry(
                outcome,
                error=None if error is None else error[:1000],
                duration_ms=round((time.perf_counter() - audited.started) * 1000.0, 1),
                operation_id=operation_id,
            )
            audited.store.queue_audit(entry, audited.seen())
        except Exception:
            log.exception("could not queue the audit row of %s", audited.tool)


@dataclass(frozen=True)
class _AuditedCall:
    """One tool call as its audit row names it: the session, the call, the tool and its arguments, and
    when it started (``time.perf_counter``)."""

    store: Store | None
    info: SessionInfo
    call: CallInfo
    tool: str
    arguments: object
    started: float

    def entry(
        self, outcome: str, *, error: str | None = None, duration_ms: float | None = None,
        operation_id: str | None = None,
    ) -> AuditEntry:  # fmt: skip
        """The call's audit row with ``outcome`` (and its end, once it has one)."""
        vehicle_id, arguments = self.call.vehicle_id, self.arguments
        return AuditEntry(
            session_key=self.info.key,
            principal=self.info.principal,
            source="mcp",
            vehicle_id=vehicle_id if isinstance(vehicle_id, str) else None,
            action=self.tool[:64],
            arguments=arguments if isinstance(arguments, dict) else {"arguments": str(arguments)},
            outcome=outcome,
            error=error,
            duration_ms=duration_ms,
            operation_id=operation_id,
        )

    def seen(self) -> SessionSeen:
        """The touch of the call's session that goes with its row."""
        info = self.info
        return SessionSeen(info.key, info.kind, info.principal, info.client_name, info.client_version)


def _operation_id(result: HandlerResult) -> str | None:
    structured = getattr(result, "structured_content", None)
    if structured is None and isinstance(result, dict):
        structured = result.get("structuredContent")
    value = structured.get("operation_id") if isinstance(structured, dict) else None
    return value if isinstance(value, str) else None


def _ended_operation(result: HandlerResult) -> tuple[str, str | None] | None:
    """The audit outcome (and error) of the operation a call's result shows ended; None while it runs."""
    structured = getattr(result, "structured_content", None)
    if structured is None and isinstance(result, dict):
        structured = result.get("structuredContent")
    status = structured.get("status") if isinstance(structured, dict) else None
    if not isinstance(status, str) or status not in AUDIT_OUTCOME_OF_OPERATION:
        return None
    outcome = AUDIT_OUTCOME_OF_OPERATION[status]
    message = structured.get("message") if isinstance(structured, dict) else None
    return outcome, None if outcome == "ok" else str(message or status)[:1000]


def _drone_id(arguments: object) -> str | None:
    value = arguments.get("drone_id") if isinstance(arguments, dict) else None
    return value[:64] if isinstance(value, str) else None


def _outcome(call: CallInfo, result: HandlerResult, failure: BaseException | None) -> tuple[str, str | None]:
    if failure is not None:
        if isinstance(failure, anyio.get_cancelled_exc_class()):
            return "error", "call cancelled by the client (the vehicle's action continues)"
        return "error", f"{type(failure).__name__}: {failure}"
    if call.outcome is not None:
        return call.outcome, call.error
    body = result.model_dump(by_alias=True) if isinstance(result, BaseModel) else result
    if not isinstance(body, dict):
        return "ok", None
    if body.get("resultType") == "input_required" or "inputRequests" in body:
        return "running", "waiting for the client's answer (elicitation)"
    if body.get("isError"):
        texts = [c.get("text", "") for c in body.get("content") or [] if isinstance(c, dict)]
        return "error", " ".join(texts)[:1000] or "tool error"
    structured = body.get("structuredContent")
    if isinstance(structured, dict) and structured.get("status") == "running":
        return "running", None
    return "ok", None
