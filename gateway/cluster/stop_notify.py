"""Stops relayed through PostgreSQL notifications, for a node cut off from NATS that reaches the database.

An operator's stop (land, return, hold) for a drone another node owns goes over the bus
(`gateway.cluster.bus`). When the bus does not carry it (this node is cut off from NATS, or the owner did
not accept it within the accept time), the stopping node publishes it with ``pg_notify`` on
:data:`STOP_CHANNEL`: ``{id, vehicle, command, args, epoch, by, node, at, accept_by}``. Every node listens
on that channel (one asyncpg connection of its own, opened again when the database returns); the node
that owns the drone under that lease epoch (or keeps a stop-only path to it after fencing itself) runs
the stop through the same path as a stop that came over the bus, and answers on :data:`ACK_CHANNEL`
``{id, node, ok, result | error}``. Only the three stops cross this way; anything else is refused, and a
stop that arrives after its ``accept_by`` (:data:`RELAYED_ACCEPT_S` after it was sent) is dropped.
Without an answer in time the stopping node goes on without it (`gateway.cluster.stop_takeover`).

The listening connection only listens: every notification is sent on a connection of a small pool, one
per send at a time, so stops relayed at once (a fleet stop relays each drone's) never share a connection
(asyncpg runs one statement per connection at a time). The stopping node sends a stop again, under the
same id, until its owner answers or its time is up (a notification sent while the owner's listener was
reconnecting is lost); the owner runs each id once and answers a repeat with the first answer.
"""

from __future__ import annotations

import asyncio
import contextlib
import json
import logging
import time
import uuid
from collections.abc import Awaitable, Callable, Mapping

import asyncpg  # type: ignore[import-untyped]
from sqlalchemy.engine import make_url

from gateway.errors import GatewayError, NotRun
from gateway.util.json_types import JsonObject, JsonValue

from .bus import error_body, rebuild_error

log = logging.getLogger("gateway.cluster.stop_notify")

STOP_CHANNEL = "fleet_stop"
ACK_CHANNEL = "fleet_stop_ack"
#: the verbs that may cross this way
RELAYED = frozenset({"land", "return_to_launch", "hold"})
#: how long the listener waits before opening its connection again
RECONNECT_S = 1.0
#: connections of the pool notifications are sent on (each send takes one for its statement)
SEND_POOL_SIZE = 4
#: a stop not answered this long after it was sent is sent again (same id), until its time is up
RESEND_S = 0.4
#: stop ids an owner remembers (each runs once; a repeat gets the first answer)
SEEN_KEPT = 1000
#: an owner still runs a relayed stop that reaches it this long after it was sent: the stopping node keeps
#: at a stop it has not seen acknowledged (`gateway.cluster.stop_takeover`), so a land that arrives late
#: is still the operator's land, never a command its caller was told had not run
RELAYED_ACCEPT_S = 10.0
#: ``handler(stop)`` -> the stop's JSON result when this node ran it, None when the drone is not this
#: node's (it stays silent); raises a GatewayError when it is this node's and it refused it
StopHandler = Callable[[JsonObject], Awaitable[object]]


def asyncpg_dsn(database_url: str) -> str:
    """The store's SQLAlchemy URL (``postgresql+asyncpg://...``) as a DSN asyncpg takes."""
    return make_url(database_url).set(drivername="postgresql").render_as_string(hide_password=False)


class StopRelay:
    """One node's end of the relay: it listens for stops and their answers, and sends its own."""

    def __init__(self, database_url: str, node_id: str, handler: StopHandler) -> None:
        self.dsn = asyncpg_dsn(database_url)
        self.node_id = node_id
        self.handler = handler
        self.conn: asyncpg.Connection | None = None
        self._pool: asyncpg.Pool | None = None
        self._pending: dict[str, asyncio.Future[JsonObject]] = {}
        # stop ids this node ran (or is running) -> its answer once there is one
        self._seen: dict[str, Mapping[str, object] | None] = {}
        self._task: asyncio.Task[None] | None = None
        self._tasks: set[asyncio.Task[None]] = set()
        self._ready = asyncio.Event()

    async def start(self) -> None:
        # min_size 0: made without a server; a connection is opened when a send needs one
        self._pool = asyncpg.create_pool(self.dsn, min_size=0, max_size=SEND_POOL_SIZE, timeout=5.0)
        await self._pool
        self._task = asyncio.create_task(self._listen(), name="cluster-stop-relay")

    @property
    def listening(self) -> bool:
        """Whether this node is connected to PostgreSQL and listening (as far as it has seen)."""
        return self._ready.is_set()

    async def close(self) -> None:
        tasks = [t for t in (self._task, *self._tasks) if t is not None]
        for task in tasks:
            task.cancel()
        await asyncio.gather(*tasks, return_exceptions=True)
        conn, self.conn = self.conn, None
        if conn is not None:
            with contextlib.suppress(Exception):
                await asyncio.wait_for(conn.close(), 3.0)
        pool, self._pool = self._pool, None
        if pool is not None:
            try:
                await asyncio.wait_for(pool.close(), 3.0)
            except Exception:
                pool.terminate()

    async def _listen(self) -> None:
        lost = False
        while True:
            try:
                conn = await asyncpg.connect(self.dsn, timeout=5.0)
                closed = asyncio.Event()
                conn.add_termination_listener(lambda _c, ended=closed: ended.set())
                await conn.add_listener(STOP_CHANNEL, self._on_notify)
                await conn.add_listener(ACK_CHANNEL, self._on_notify)
                self.conn = conn
                self._ready.set()
                if lost:
                    log.warning("stop relay: listening on PostgreSQL again (%s)", STOP_CHANNEL)
                lost = False
                while not closed.is_set():  # a dead server is seen when a query fails
                    with contextlib.suppress(TimeoutError):
                        await asyncio.wait_for(closed.wait(), 2.0)
                    if not closed.is_set():
                        await asyncio.wait_for(conn.execute("SELECT 1"), 5.0)
            except asyncio.CancelledError:
                raise
            except Exception as exc:
                if not lost:
                    log.warning("stop relay: not listening on PostgreSQL (%r): retrying", exc)
                lost = True
            self._ready.clear()
            conn_, self.conn = self.conn, None
            if conn_ is not None:
                conn_.terminate()
            await asyncio.sleep(RECONNECT_S)

    def _on_notify(self, _conn: object, _pid: int, channel: str, payload: str) -> None:
        try:
            body: JsonValue = json.loads(payload)
        except ValueError:
            log.warning("stop relay: unreadable notification on %s: %.200s", channel, payload)
            return
        if not isinstance(body, dict):
            return
        if channel == ACK_CHANNEL:
            future = self._pending.get(str(body.get("id")))
            if future is not None and not future.done():
                future.set_result(body)
            return
        if body.get("node") == self.node_id:  # its own stop: this node did not reach the owner
            return
        stop_id = str(body.get("id"))
        if stop_id in self._seen:  # sent again: run once; a repeat after the answer gets it again
            answer = self._seen[stop_id]
            if answer is not None:
                self._spawn(self._notify(ACK_CHANNEL, answer), f"relayed-stop-ack-{body.get('vehicle')}")
            return
        self._seen[stop_id] = None
        while len(self._seen) > SEEN_KEPT:
            del self._seen[next(iter(self._seen))]
        self._spawn(self._run(body), f"relayed-stop-{body.get('vehicle')}")

    def _spawn(self, work: Awaitable[None], name: str) -> None:
        async def run() -> None:
            try:
                await work
            except Exception as exc:
                log.warning("stop relay: %s failed (%r)", name, exc)

        task = asyncio.create_task(run(), name=name)
        self._tasks.add(task)
        task.add_done_callback(self._tasks.discard)

    async def _run(self, body: JsonObject) -> None:
        command = body.get("command")
        try:
            if command not in RELAYED:  # never accepted this way, whoever owns the drone
                log.warning(
                    "stop relay: refused %r for %s from node %s: only land, return_to_launch and hold "
                    "cross PostgreSQL", command, body.get("vehicle"), body.get("node"),
                )  # fmt: skip
                return
            accept_by = body.get("accept_by")
            if isinstance(accept_by, int | float) and time.time() > accept_by:  # its caller heard "no path"
                log.info("stop relay: dropped %s for %s from node %s: it arrived %.1f s after its deadline",
                         command, body.get("vehicle"), body.get("node"), time.time() - accept_by)  # fmt: skip
                return
            result = await self.handler(body)
            if result is None:
                return
            answer: dict[str, object] = {"ok": True, "result": result}
        except GatewayError as exc:
            answer = {"ok": False, "error": error_body(exc)}
        except Exception as exc:
            log.exception("stop relay: %s for %s failed", command, body.get("vehicle"))
            failed = {"code": "gateway_error", "message": f"{command} failed: {exc!r}"}
            answer = {"ok": False, "error": failed}
        ack = {"id": body.get("id"), "node": self.node_id, **answer}
        stop_id = str(body.get("id"))
        if stop_id in self._seen:
            self._seen[stop_id] = ack
        await self._notify(ACK_CHANNEL, ack)

    async def _notify(self, channel: str, body: Mapping[str, object], within_s: float = 5.0) -> None:
        """One notification on a pool connection of its own (never the listener's, never shared)."""
        pool = self._pool
        if pool is None:
            raise ConnectionError("the stop relay is closed")
        async with asyncio.timeout(within_s), pool.acquire() as conn:
            await conn.execute("SELECT pg_notify($1, $2)", channel, json.dumps(body, default=str))

    async def send(
        self, vehicle_id: str, command: str, arguments: JsonObject, epoch: int | None,
        caller: Mapping[str, object], within_s: float,
    ) -> JsonValue:  # fmt: skip
        """Relay the stop ``command`` for ``vehicle_id`` to its owner; the owner's result, or its error
        raised again here; :class:`NotRun` ("no path") when no node answered within ``within_s``."""
        if command not in RELAYED:
            raise NotRun(f"only land, return_to_launch and hold cross PostgreSQL; {command} was not sent")
        stop_id = uuid.uuid4().hex
        started = time.monotonic()
        deadline = started + within_s
        future: asyncio.Future[JsonObject] = asyncio.get_running_loop().create_future()
        self._pending[stop_id] = future
        body = {"id": stop_id, "vehicle": vehicle_id, "command": command, "args": arguments,
                "epoch": epoch, "by": caller, "node": self.node_id, "at": time.time(),
                "accept_by": time.time() + max(within_s, RELAYED_ACCEPT_S)}  # fmt: skip
        sends, last_error = 0, "no node answered"
        try:
            with contextlib.suppress(TimeoutError):  # answers come to the listener: it may be reconnecting
                await asyncio.wait_for(self._ready.wait(), within_s / 2)
            while not future.done() and time.monotonic() < deadline:
                left = deadline - time.monotonic()
                try:
                    await self._notify(STOP_CHANNEL, body, left)
                    sends += 1
                except (TimeoutError, ConnectionError, OSError, asyncpg.PostgresError,
                        asyncpg.InterfaceError) as exc:  # fmt: skip
                    last_error = f"{type(exc).__name__}: {exc}"
                    log.warning("%s: relaying %s through PostgreSQL failed (%s): sending it again",
                                vehicle_id, command, last_error)  # fmt: skip
                    await asyncio.sleep(min(RESEND_S / 4, max(0.0, deadline - time.monotonic())))
                    continue
                with contextlib.suppress(TimeoutError):
                    await asyncio.wait_for(asyncio.shield(future), min(RESEND_S, deadline - time.monotonic()))
            if not future.done():
                raise NotRun(
                    f"no path to {vehicle_id}'s owner: the bus did not carry {command}, and no node answered "
                    f"it through PostgreSQL notifications within {within_s:g} s ({sends} sent; {last_error}):"
                    " "
                    "nothing is known to have been run",
                    vehicle_id=vehicle_id,
                )
            answer = future.result()
        finally:
            self._pending.pop(stop_id, None)
        log.warning("%s: %s relayed through PostgreSQL to node %s (answered after %.0f ms, %d sent)",
                    vehicle_id, command, answer.get("node"), (time.monotonic() - started) * 1000,
                    sends)  # fmt: skip
        if answer.get("ok"):
            return answer.get("result")
        error = answer.get("error")
        raise rebuild_error(error if isinstance(error, dict) else {})
