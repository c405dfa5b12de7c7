"""The cluster's messages on NATS: telemetry fan-out, broadcasts, and calls routed to a vehicle's owner.

Subjects (``fleet.`` prefix):

- ``fleet.tele.<vehicle>``: the owner's telemetry snapshots (every node subscribes to ``fleet.tele.*``);
- ``fleet.call.<vehicle>``: calls for a vehicle; only its owner subscribes (queue group ``owner``, so a
  handover overlap never runs a call twice). The caller gets zero or more ``progress`` messages, then
  one ``result``, on its reply inbox (NATS request/reply with partial replies). Nobody subscribed
  (no owner at the moment) is NATS's "no responders" status, answered at once;
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
from collections.abc import Awaitable, Callable
from typing import Any

import nats
from nats.aio.client import Client
from nats.aio.msg import Msg
from nats.aio.subscription import Subscription

from gateway.errors import GatewayError, NoOwner, OwnerTimeout

log = logging.getLogger("gateway.cluster.bus")

PREFIX = "fleet"
KIND = "Fleet-Kind"
ProgressSink = Callable[[dict[str, Any]], Awaitable[None]]
#: ``handler(call name, arguments, caller, progress)`` -> JSON-serialisable result
CallHandler = Callable[[str, dict[str, Any], dict[str, Any], ProgressSink], Awaitable[Any]]


def tele_subject(vehicle_id: str) -> str:
    return f"{PREFIX}.tele.{vehicle_id}"


def call_subject(vehicle_id: str) -> str:
    return f"{PREFIX}.call.{vehicle_id}"


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


def error_body(exc: GatewayError) -> dict[str, Any]:
    return {
        "code": exc.code,
        "message": exc.message,
        "details": _jsonable(exc.details),
        "status": exc.http_status,
    }


def rebuild_error(body: dict[str, Any]) -> GatewayError:
    """The error a remote node raised, as the same class here (a plain GatewayError if unknown)."""
    code = str(body.get("code") or "gateway_error")
    cls = _error_classes().get(code, GatewayError)
    exc = cls.__new__(cls)
    raw = body.get("details")
    details: dict[str, Any] = raw if isinstance(raw, dict) else {}
    GatewayError.__init__(exc, str(body.get("message") or code), **details)
    if "rule" in details:
        exc.rule = details["rule"]  # type: ignore[attr-defined]
    if cls is GatewayError:
        exc.code = code
        exc.http_status = int(body.get("status") or 500)
    return exc


def _jsonable(value: Any) -> Any:
    return json.loads(json.dumps(value, default=str))


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

    async def publish(self, subject: str, payload: bytes, **kw: Any) -> None:
        self._count(subject, len(payload))
        await self.client.publish(subject, payload, **kw)

    async def broadcast(self, kind: str, body: dict[str, Any]) -> None:
        await self.publish(event_subject(kind), json.dumps(body, default=str).encode())

    async def subscribe(
        self, subject: str, handler: Callable[[Msg], Awaitable[None]], queue: str = ""
    ) -> Subscription:
        return await self.client.subscribe(subject, queue=queue, cb=handler)

    # --- calls to a vehicle's owner -----------------------------------------------------------------
    async def call(
        self,
        vehicle_id: str,
        name: str,
        arguments: dict[str, Any],
        caller: dict[str, Any],
        timeout_s: float,
        on_progress: ProgressSink | None = None,
    ) -> Any:
        """Run ``name`` on the vehicle's owner; its result, or its error raised again here."""
        nc = self.client
        inbox = nc.new_inbox()
        replies: asyncio.Queue[Msg] = asyncio.Queue()

        async def collect(msg: Msg) -> None:
            await replies.put(msg)

        sub = await nc.subscribe(inbox, cb=collect)
        try:
            body = json.dumps({"call": name, "args": arguments, "caller": caller}, default=str).encode()
            await self.publish(call_subject(vehicle_id), body, reply=inbox)
            deadline = time.monotonic() + timeout_s
            while True:
                remaining = deadline - time.monotonic()
                if remaining <= 0:
                    raise OwnerTimeout(
                        f"the node that owns {vehicle_id} did not answer {name} within {timeout_s:g} s; "
                        f"it may still have run: check the drone's state before sending {name} again"
                    )
                try:
                    msg = await asyncio.wait_for(replies.get(), remaining)
                except TimeoutError:
                    continue
                headers = msg.headers or {}
                if headers.get("Status") == "503":
                    raise NoOwner(
                        f"no node owns drone '{vehicle_id}' right now (its node was lost and a takeover is "
                        "under way, or no live node may own it): retry in a few seconds",
                        vehicle_id=vehicle_id,
                    )
                reply = json.loads(msg.data) if msg.data else {}
                if headers.get(KIND) == "progress":
                    if on_progress is not None:
                        with contextlib.suppress(Exception):  # progress is a courtesy
                            await on_progress(reply)
                    continue
                if reply.get("ok"):
                    return reply.get("result")
                raise rebuild_error(reply.get("error") or {})
        finally:
            with contextlib.suppress(Exception):
                await sub.unsubscribe()

    async def serve_calls(self, vehicle_id: str, handler: CallHandler) -> Subscription:
        """Answer calls for ``vehicle_id`` (this node owns it) with ``handler``, each in its own task."""

        async def on_message(msg: Msg) -> None:
            task = asyncio.create_task(self._answer(msg, handler), name=f"call-{vehicle_id}")
            self._tasks.add(task)
            task.add_done_callback(self._tasks.discard)

        return await self.subscribe(call_subject(vehicle_id), on_message, queue="owner")

    async def _answer(self, msg: Msg, handler: CallHandler) -> None:
        reply_to = msg.reply
        try:
            body = json.loads(msg.data)
            name, arguments, caller = (
                str(body["call"]),
                dict(body.get("args") or {}),
                dict(body.get("caller") or {}),
            )
        except Exception as exc:
            answer: dict[str, Any] = {
                "ok": False,
                "error": {"code": "invalid_argument", "message": f"bad call: {exc}"},
            }
        else:

            async def progress(update: dict[str, Any]) -> None:
                if reply_to:
                    await self.publish(
                        reply_to, json.dumps(update, default=str).encode(), headers={KIND: "progress"}
                    )

            try:
                answer = {"ok": True, "result": _jsonable(await handler(name, arguments, caller, progress))}
            except GatewayError as exc:
                answer = {"ok": False, "error": error_body(exc)}
            except Exception as exc:
                log.exception("forwarded call %s failed", name)
                answer = {
                    "ok": False,
                    "error": {"code": "gateway_error", "message": f"{name} failed on the owner: {exc!r}"},
                }
        if reply_to:
            await self.publish(reply_to, json.dumps(answer, default=str).encode(), headers={KIND: "result"})
