"""The cluster's messages on NATS: telemetry fan-out, broadcasts, and calls routed to a vehicle's owner.

Subjects (``fleet.`` prefix):

- ``fleet.tele.<vehicle>``: the owner's telemetry snapshots (every node subscribes to ``fleet.tele.*``);
- ``fleet.call.<vehicle>``: calls for a vehicle; only its owner subscribes (queue group ``owner``, so a
  handover overlap never runs a call twice). The caller gets zero or more ``progress`` messages, then
  one ``result``, on its reply inbox (NATS request/reply with partial replies). Nobody subscribed
  (no owner at the moment) is NATS's "no responders" status, answered at once. A call carries the
  wall-clock time by which the owner must accept it and the lease epoch the caller saw; the owner
  answers ``accepted`` first, and refuses (runs nothing) a call that reaches it after that time or for
  an epoch it does not hold. A caller that heard no ``accepted`` in time says "not run", and that is
  true: a call delayed in the bus (a node cut off, then healed) is dropped by its owner, not run;
- ``fleet.stop.<vehicle>``: a stop (land, return, hold) for a vehicle whose node fenced itself (the database
  unreachable) and stopped its sidecar: that node alone listens, and sends it over the drone's own link;
- ``fleet.event.<kind>``: broadcasts to every node (operator locks, registrations changed, stop).

Errors cross as ``{code, message, details}`` and are raised again on the caller as the same
:class:`~gateway.errors.GatewayError` subclass, so MCP and REST present them exactly as a local error.
"""

from __future__ import annotations

import asyncio
import contextlib
import json
import logging
import time
from collections.abc import Awaitable, Callable, Mapping
from typing import Any, Protocol, Required

import nats
from nats.aio.client import Client
from nats.aio.msg import Msg
from nats.aio.subscription import Subscription
from pydantic import TypeAdapter, ValidationError
from typing_extensions import TypedDict  # pydantic validates CallRequest with it on Python 3.11

from gateway.errors import GatewayError, NoOwner, NotRun, OwnerLost, OwnerTimeout
from gateway.fleet.operations.routing import ProgressMessage
from gateway.util.json_types import JsonObject, JsonValue

log = logging.getLogger("gateway.cluster.bus")

PREFIX = "fleet"
KIND = "Fleet-Kind"
#: the owner refuses a call this long after its accept deadline already (clocks of nodes differ a little:
#: NTP keeps them within milliseconds); the caller waits this long past the deadline before "not run"
CLOCK_MARGIN_S = 0.5
#: how often a caller waiting on an accepted call checks that its node still owns the vehicle
OWNER_CHECK_S = 0.5
ProgressSink = Callable[[ProgressMessage], Awaitable[None]]
#: ``handler(call name, arguments, caller (a Caller's JSON), progress)`` -> JSON-serialisable result
CallHandler = Callable[[str, JsonObject, Mapping[str, object], ProgressSink], Awaitable[object]]


class ErrorBody(TypedDict, total=False):
    """A GatewayError as a call's answer carries it (`error_body`; `rebuild_error` takes whatever of it
    came)."""

    code: str
    message: str
    details: dict[str, object]
    status: int


class CallRequest(TypedDict, total=False):
    """A call for a vehicle's owner as it crosses the bus (`Bus.call` sends it, the owner validates it)."""

    call: Required[str]  # the verb (or ``wait``)
    args: JsonObject  # its JSON arguments
    caller: JsonObject  # a Caller's JSON
    accept_by: float | None  # wall-clock time after which the owner must not run it
    epoch: int | None  # the lease epoch the caller saw


_CALL_REQUEST = TypeAdapter(CallRequest)


class CallAnswer(TypedDict, total=False):
    """The owner's last message on a call's inbox: its result as JSON, or its error."""

    ok: Required[bool]
    result: JsonValue
    error: ErrorBody


_CALL_ANSWER = TypeAdapter(CallAnswer)
_PROGRESS = TypeAdapter(ProgressMessage)


def _problems(exc: ValidationError) -> str:
    """What is wrong with a body, on one line (each member with what it holds and what it must be)."""
    return "; ".join(
        f"{'.'.join(str(p) for p in err['loc']) or 'body'}: {err['msg']} (got {str(err['input'])[:60]})"
        for err in exc.errors()
    )


async def no_progress(_update: ProgressMessage) -> None:
    """The progress sink of a call run for no one who follows it."""
    return None


#: ``check(epoch the caller saw)`` raises when the call must not run here (a stale epoch)
CallCheck = Callable[[int | None], None]


class Leased(Protocol):
    """What a node holds of a drone for its calls: a lease, or a fenced node's stop path."""

    @property
    def epoch(self) -> int: ...


def epoch_check(
    held: Mapping[str, Leased], vehicle_id: str, node_id: str, words: tuple[str, str]
) -> CallCheck:
    """The check of a call against the lease epoch this node holds for the drone (in ``held``): the first
    of ``words`` when it holds none, the second when the call was sent for another epoch (then it is not
    run); formatted with ``node``, ``vehicle``, ``sent`` and ``held``."""

    def check(epoch: int | None) -> None:
        now = held.get(vehicle_id)
        if now is None:
            raise NoOwner(words[0].format(node=node_id, vehicle=vehicle_id))
        if epoch is not None and epoch != now.epoch:
            raise NotRun(words[1].format(node=node_id, vehicle=vehicle_id, sent=epoch, held=now.epoch))

    return check


def tele_subject(vehicle_id: str) -> str:
    return f"{PREFIX}.tele.{vehicle_id}"


def call_subject(vehicle_id: str) -> str:
    return f"{PREFIX}.call.{vehicle_id}"


def stop_subject(vehicle_id: str) -> str:
    """Stops (land, return, hold) for a vehicle whose node fenced itself: it sends them over the drone's own
    link (`gateway.cluster.stoplink`)."""
    return f"{PREFIX}.stop.{vehicle_id}"


def event_subject(kind: str) -> str:
    return f"{PREFIX}.event.{kind}"


def _error_classes() -> dict[str, type[GatewayError]]:
    found: dict[str, type[GatewayError]] = {}
    todo: list[type[GatewayError]] = [GatewayError]
    while todo:
        cls = todo.pop()
        found.setdefault(cls.code, cls)
        todo.extend(cls.__subclasses__())
    return found


def error_body(exc: GatewayError) -> ErrorBody:
    details = _jsonable(exc.details)  # a JSON object: the details are keyword arguments
    return {
        "code": exc.code,
        "message": exc.message,
        "details": dict(details) if isinstance(details, dict) else {},
        "status": exc.http_status,
    }


def rebuild_error(body: Mapping[str, object]) -> GatewayError:
    """The error a remote node raised, as the same class here (a plain GatewayError if unknown)."""
    code = str(body.get("code") or "gateway_error")
    cls = _error_classes().get(code, GatewayError)
    exc = cls.__new__(cls)
    raw = body.get("details")
    details: dict[str, object] = raw if isinstance(raw, dict) else {}
    GatewayError.__init__(exc, str(body.get("message") or code), **details)
    if "rule" in details:
        exc.rule = details["rule"]  # type: ignore[attr-defined]
    if cls is GatewayError:
        exc.code = code
        status = body.get("status")
        exc.http_status = status if isinstance(status, int) else 500
    return exc


def _jsonable(value: object) -> JsonValue:
    """``value`` as the JSON its answer carries (what JSON cannot hold, as its text)."""
    carried: JsonValue = json.loads(json.dumps(value, default=str))
    return carried


async def probe(url: str, timeout_s: float) -> None:
    """Connect to NATS once and leave: raises (naming the last connection error) when no server of
    ``url`` answers within ``timeout_s``."""
    errors: list[Exception] = []

    async def quiet(exc: Exception) -> None:  # the client would log every failed attempt
        errors.append(exc)

    try:
        nc = await asyncio.wait_for(
            nats.connect(
                servers=Bus.servers_of(url),
                connect_timeout=min(2.0, timeout_s),
                allow_reconnect=False,
                max_reconnect_attempts=1,
                error_cb=quiet,
                name="fleet-gateway start-up check",
            ),
            timeout_s,
        )
    except Exception as exc:
        cause = errors[-1] if errors else exc
        raise ConnectionError(str(cause) or type(cause).__name__) from None
    await nc.close()


class Bus:
    """One NATS connection of a node."""

    def __init__(self, servers: list[str], name: str) -> None:
        self.servers = servers
        self.name = name
        self.nc: Client | None = None
        self._tasks: set[asyncio.Task[None]] = set()
        #: bytes and messages this node published, by subject family (for the benchmark and /metrics)
        self.sent: dict[str, list[int]] = {}

    @classmethod
    def servers_of(cls, url: str) -> list[str]:
        return [u.strip() for u in url.split(",") if u.strip()]

    async def connect(self, timeout_s: float = 10.0) -> None:
        async def disconnected() -> None:
            log.warning("NATS: disconnected from %s", self.servers)

        async def reconnected() -> None:
            log.warning("NATS: reconnected")

        async def error(exc: Exception) -> None:
            log.warning("NATS: %r", exc)

        self.nc = await nats.connect(
            servers=self.servers,
            name=self.name,
            connect_timeout=timeout_s,
            max_reconnect_attempts=-1,
            reconnect_time_wait=0.5,
            disconnected_cb=disconnected,
            reconnected_cb=reconnected,
            error_cb=error,
        )

    @property
    def client(self) -> Client:
        if self.nc is None:
            raise RuntimeError("the NATS bus is not connected")
        return self.nc

    async def close(self) -> None:
        for task in list(self._tasks):
            task.cancel()
        await asyncio.gather(*self._tasks, return_exceptions=True)
        if self.nc is not None:
            nc, self.nc = self.nc, None
            with contextlib.suppress(Exception):
                await nc.drain()
            with contextlib.suppress(Exception):
                await nc.close()

    def _count(self, subject: str, size: int) -> None:
        family = ".".join(subject.split(".")[:2])
        tally = self.sent.setdefault(family, [0, 0])
        tally[0] += 1
        tally[1] += size

    # Any: nats-py, the options of its publish
    async def publish(self, subject: str, payload: bytes, **kw: Any) -> None:
        self._count(subject, len(payload))
        await self.client.publish(subject, payload, **kw)

    async def broadcast(self, kind: str, body: Mapping[str, object]) -> None:
        await self.publish(event_subject(kind), json.dumps(body, default=str).encode())

    async def subscribe(
        self, subject: str, handler: Callable[[Msg], Awaitable[None]], queue: str = ""
    ) -> Subscription:
        return await self.client.subscribe(subject, queue=queue, cb=handler)

    # --- calls to a vehicle's owner -----------------------------------------------------------------
    @property
    def connected(self) -> bool:
        return self.nc is not None and self.nc.is_connected

    def cut_off(self, what: str) -> NotRun:
        return NotRun(
            f"this node is cut off from the cluster's bus (NATS at {', '.join(self.servers)}): {what} was "
            "not sent and did not run; call a node that reaches the bus, or retry when this one does",
            bus="down",
        )

    async def call(
        self,
        vehicle_id: str,
        name: str,
        arguments: JsonObject,
        caller: Mapping[str, object],
        timeout_s: float,
        on_progress: ProgressSink | None = None,
        *,
        accept_s: float = 3.0,
        epoch: int | None = None,
        owner_gone: Callable[[], str | None] | None = None,
        subject: str | None = None,
        accepted_event: asyncio.Event | None = None,
    ) -> JsonValue:
        """Run ``name`` on the vehicle's owner; its result, or its error raised again here. The owner
        must accept it within ``accept_s`` (else :class:`NotRun`, and the owner will not run it later);
        then its answer may take ``timeout_s`` in all (else :class:`OwnerTimeout`: it was running).
        ``owner_gone()`` says why the node that accepted it no longer owns the vehicle (None while it
        does): then :class:`OwnerLost` at once, not at the timeout. ``subject``: another than the
        vehicle's call subject (its stop subject). ``accepted_event`` is set once the owner accepted it."""
        if not self.connected:
            raise self.cut_off(f"{name} for {vehicle_id}")
        nc = self.client
        inbox = nc.new_inbox()
        replies: asyncio.Queue[Msg] = asyncio.Queue()

        async def collect(msg: Msg) -> None:
            await replies.put(msg)

        sub = await nc.subscribe(inbox, cb=collect)
        try:
            accept_by = time.time() + accept_s
            body = json.dumps(
                {"call": name, "args": arguments, "caller": caller, "accept_by": accept_by, "epoch": epoch},
                default=str,
            ).encode()
            await self.publish(subject or call_subject(vehicle_id), body, reply=inbox)
            started = time.monotonic()
            accept_deadline = started + accept_s + CLOCK_MARGIN_S
            deadline = started + max(timeout_s, accept_s + CLOCK_MARGIN_S)
            accepted = False
            while True:
                now = time.monotonic()
                if not accepted and now >= accept_deadline:
                    why = "" if self.connected else " (this node lost the bus meanwhile)"
                    raise NotRun(
                        f"the node that owns {vehicle_id} did not accept {name} within {accept_s:g} s"
                        f"{why}: it was not run, and its owner refuses it if it arrives later",
                        vehicle_id=vehicle_id,
                        bus="no answer",
                    )
                gone = owner_gone() if accepted and owner_gone is not None else None
                if gone is not None:
                    raise OwnerLost(
                        f"{gone} while it ran {name} for {vehicle_id}; the call had been accepted, so it may "
                        "have run",
                        vehicle_id=vehicle_id,
                    )
                if now >= deadline:
                    raise OwnerTimeout(
                        f"the node that owns {vehicle_id} accepted {name} but did not answer within "
                        f"{timeout_s:g} s; it may still be running: check the drone's state before sending "
                        f"{name} again",
                        vehicle_id=vehicle_id,
                    )
                wait_s = (deadline if accepted else accept_deadline) - now
                if owner_gone is not None:
                    wait_s = min(wait_s, OWNER_CHECK_S)
                try:
                    msg = await asyncio.wait_for(replies.get(), wait_s)
                except TimeoutError:
                    continue
                answer = await self._call_reply(msg, vehicle_id, name, on_progress)
                accepted = True
                if accepted_event is not None:
                    accepted_event.set()
                if answer is not None:
                    return answer[0]
        finally:
            with contextlib.suppress(Exception):
                await sub.unsubscribe()

    async def _call_reply(
        self, msg: Msg, vehicle_id: str, name: str, on_progress: ProgressSink | None
    ) -> tuple[JsonValue] | None:
        """One message on a call's inbox: None when it says the owner accepted the call or reports its
        progress; else the owner's result (in a 1-tuple), or its error raised here."""
        headers = msg.headers or {}
        if headers.get("Status") == "503":
            raise NoOwner(
                f"no node owns drone '{vehicle_id}' right now (its node was lost and a takeover is "
                f"under way, or no live node may own it): {name} was not run; retry in a few seconds",
                vehicle_id=vehicle_id,
            )
        kind = headers.get(KIND)
        if kind == "accepted":
            return None
        if kind == "progress":
            if on_progress is not None:
                with contextlib.suppress(Exception):  # progress is a courtesy
                    await on_progress(_PROGRESS.validate_json(msg.data or b"{}"))
            return None
        try:
            reply = _CALL_ANSWER.validate_json(msg.data or b"{}")
        except ValidationError as exc:
            raise GatewayError(
                f"the answer to {name} for {vehicle_id} is not a call's answer: {_problems(exc)}"
            ) from None
        if reply["ok"]:
            return (reply.get("result"),)
        raise rebuild_error(reply.get("error") or ErrorBody())

    async def serve_calls(
        self,
        vehicle_id: str,
        handler: CallHandler,
        check: CallCheck | None = None,
        subject: str | None = None,
    ) -> Subscription:
        """Answer calls for ``vehicle_id`` (this node owns it) with ``handler``, each in its own task;
        ``check`` refuses a call for a lease epoch this node does not hold. ``subject``: another than the
        vehicle's call subject (its stop subject)."""

        async def on_message(msg: Msg) -> None:
            task = asyncio.create_task(self._answer(msg, handler, check), name=f"call-{vehicle_id}")
            self._tasks.add(task)
            task.add_done_callback(self._tasks.discard)

        return await self.subscribe(subject or call_subject(vehicle_id), on_message, queue="owner")

    async def _reply(self, reply_to: str | None, kind: str, body: Mapping[str, object]) -> None:
        if reply_to:
            await self.publish(reply_to, json.dumps(body, default=str).encode(), headers={KIND: kind})

    async def _answer(self, msg: Msg, handler: CallHandler, check: CallCheck | None = None) -> None:
        reply_to = msg.reply
        try:
            request = _CALL_REQUEST.validate_json(msg.data)
            name, arguments, caller = request["call"], request.get("args", {}), request.get("caller", {})
            accept_by, epoch = request.get("accept_by"), request.get("epoch")
        except ValidationError as exc:  # not JSON, or not a call
            answer: CallAnswer = {
                "ok": False,
                "error": {"code": "invalid_argument", "message": f"bad call: {_problems(exc)}"},
            }
        else:
            try:
                if accept_by is not None and time.time() > accept_by:  # its caller was told it did not run
                    late_s = time.time() - accept_by
                    log.warning("dropped %s from %s: it arrived %.1f s after its deadline", name,
                                caller.get("node", "?"), late_s)  # fmt: skip
                    raise NotRun(f"{name} reached the owner {late_s:.1f} s after its deadline: not run")
                if check is not None:
                    check(epoch)
            except GatewayError as exc:
                answer = {"ok": False, "error": error_body(exc)}
            else:
                await self._reply(reply_to, "accepted", {})

                async def progress(update: ProgressMessage) -> None:
                    await self._reply(reply_to, "progress", update)

                try:
                    result = await handler(name, arguments, caller, progress)
                    answer = {"ok": True, "result": _jsonable(result)}
                except GatewayError as exc:
                    answer = {"ok": False, "error": error_body(exc)}
                except Exception as exc:
                    log.exception("forwarded call %s failed", name)
                    answer = {
                        "ok": False,
                        "error": {"code": "gateway_error", "message": f"{name} failed on the owner: {exc!r}"},
                    }
        await self._reply(reply_to, "result", answer)
