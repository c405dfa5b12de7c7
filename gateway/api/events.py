"""GET /api/v1/events: the fleet's live state and the audit log as server-sent events.

The operator console reads this stream; so can any dashboard. It carries, as named events whose data is
one JSON object:

- ``hello``: who the stream is for (``principal``, ``role``) and the interval of ``fleet`` events;
- ``fleet``: the whole fleet (:func:`gateway.api.fleetview.fleet_view`) every ``FLEET_PERIOD_S``, read
  from the telemetry caches: no vehicle is asked anything for it;
- ``audit``: ``{"items": [...]}`` audit rows: first the newest ``AUDIT_BACKLOG`` (oldest first), then
  every row as it is written, and again when a call that answered "running" finishes. Rows carry their
  ``id``: a later copy of a row replaces the earlier one;
- ``geofences``: the zones (as ``GET /api/v1/geofences``) at the start and whenever they change.

One :class:`EventHub` per app builds each fleet snapshot once and hands the same text to every open
stream; it runs only while a stream is open. A stream that cannot keep up (its queue fills) is ended;
the client reconnects and receives the backlog again. Authorisation is the REST API's (a viewer token
may read it); browsers send the token in the Authorization header by reading the stream with ``fetch``.
"""

from __future__ import annotations

import asyncio
import contextlib
import json
import logging
from collections.abc import AsyncIterator, Callable
from dataclasses import dataclass, field

from fastapi import APIRouter, Request
from sse_starlette import EventSourceResponse

from gateway.api.deps import GatewayDep, PrincipalDep, StoreDep
from gateway.api.fleetview import fleet_view
from gateway.fleet.policy.geofence import GeofenceSet
from gateway.fleet.policy.zones import Zones
from gateway.registry.store import AuditRecord, Store
from gateway.runtime import Gateway

log = logging.getLogger(__name__)

router = APIRouter(tags=["live"])

FLEET_PERIOD_S = 0.5
AUDIT_BACKLOG = 100
QUEUE_SIZE = 512
PING_S = 15

_OVERFLOW = ("", "")


def _json(body: object) -> str:
    return json.dumps(body, separators=(",", ":"), allow_nan=False, default=str)


@dataclass(eq=False)
class Subscriber:
    """One open stream: named events waiting to be sent."""

    queue: asyncio.Queue[tuple[str, str]] = field(default_factory=lambda: asyncio.Queue(QUEUE_SIZE))
    overflowed: bool = False

    def put(self, event: str, data: str) -> None:
        if self.overflowed:
            return
        try:
            self.queue.put_nowait((event, data))
        except asyncio.QueueFull:
            self.overflowed = True
            while not self.queue.empty():
                self.queue.get_nowait()
            self.queue.put_nowait(_OVERFLOW)


class EventHub:
    """Fans the gateway's live state out to every open event stream."""

    def __init__(self, gateway: Gateway, period_s: float = FLEET_PERIOD_S) -> None:
        self.gateway = gateway
        self.period_s = period_s
        self._subscribers: set[Subscriber] = set()
        self._task: asyncio.Task[None] | None = None
        self._listening_to: Store | None = None  # whose audit rows are forwarded
        self._stop_listening: Callable[[], None] | None = None
        self._fences: GeofenceSet | None = (
            None  # the GeofenceSet last sent (kept, so its identity cannot be reused)
        )

    @property
    def subscriber_count(self) -> int:
        return len(self._subscribers)

    @contextlib.asynccontextmanager
    async def subscribe(self) -> AsyncIterator[Subscriber]:
        sub = Subscriber()
        self._subscribers.add(sub)
        self._listen_to_audit()
        sub.put("geofences", self._geofences_text())
        if self._task is None or self._task.done():
            self._task = asyncio.create_task(self._run(), name="event-hub")
        try:
            yield sub
        finally:
            self._subscribers.discard(sub)
            if not self._subscribers:
                await self._idle()

    async def _idle(self) -> None:
        task, self._task = self._task, None
        if task is not None:
            task.cancel()
            with contextlib.suppress(asyncio.CancelledError):
                await task
        if self._stop_listening is not None:
            self._stop_listening()
        self._stop_listening = self._listening_to = None

    def _listen_to_audit(self) -> None:
        store = self.gateway.store
        if store is None or store is self._listening_to:
            return
        if self._stop_listening is not None:
            self._stop_listening()
        self._listening_to = store
        self._stop_listening = store.on_audit(self._on_audit)

    def _on_audit(self, record: AuditRecord) -> None:
        self.publish("audit", _json({"items": [record.model_dump(mode="json")]}))

    def publish(self, event: str, data: str) -> None:
        for sub in list(self._subscribers):
            sub.put(event, data)

    def _geofences_text(self) -> str:
        if self.gateway.safety is None:
            return _json({"type": "FeatureCollection", "features": [], "persisted": False})
        self._fences = self.gateway.safety.geofences
        view = Zones(self.gateway.safety, self.gateway.settings.geofence_file).view()
        return _json(view.model_dump(mode="json"))

    async def _run(self) -> None:
        while True:
            try:
                self._listen_to_audit()  # the store is replaced when the gateway restarts
                self.publish("fleet", _json(fleet_view(self.gateway)))
                safety = self.gateway.safety
                if safety is not None and safety.geofences is not self._fences:
                    self.publish("geofences", self._geofences_text())
            except asyncio.CancelledError:
                raise
            except Exception:  # a bad snapshot must not end the stream of every console
                log.exception("live fleet snapshot failed")
            await asyncio.sleep(self.period_s)


def get_hub(request: Request) -> EventHub:
    hub: EventHub | None = getattr(request.app.state, "event_hub", None)
    if hub is None:
        hub = request.app.state.event_hub = EventHub(request.app.state.gateway)
    return hub


async def _stream(hub: EventHub, store: Store, hello: dict[str, object]) -> AsyncIterator[dict[str, str]]:
    async with hub.subscribe() as sub:
        yield {"event": "hello", "data": _json(hello)}
        backlog = await store.list_audit(limit=AUDIT_BACKLOG)  # after subscribing: no row falls between
        items = [r.model_dump(mode="json") for r in reversed(backlog)]
        yield {"event": "audit", "data": _json({"items": items, "backlog": True})}
        while True:
            event, data = await sub.queue.get()
            if (event, data) == _OVERFLOW:
                log.warning("an event stream could not keep up and was ended (the client reconnects)")
                return
            yield {"event": event, "data": data}


@router.get(
    "/events",
    summary="Live fleet state and audit log (server-sent events: hello, fleet, audit, geofences)",
    response_class=EventSourceResponse,
    responses={200: {"content": {"text/event-stream": {}}, "description": "An endless event stream."}},
)
async def events(
    request: Request, gateway: GatewayDep, store: StoreDep, who: PrincipalDep
) -> EventSourceResponse:
    hub = get_hub(request)
    gateway.require_registry()  # 503 while starting: the client retries
    hello = {"principal": who.name, "role": who.role, "fleet_period_s": hub.period_s}
    return EventSourceResponse(_stream(hub, store, hello), ping=PING_S)
