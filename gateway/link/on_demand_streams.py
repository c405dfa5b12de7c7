"""Telemetry streams held open at rest only while they are read.

MAVSDK sends an RC status item with every SYS_STATUS (1 Hz at rest, for the health and the battery): one
gRPC stream item a second for the sidecar to write and the gateway to read, which only ``get_rc_status``
reads. Such a stream (``ON_DEMAND_AT_REST``) is open while the drone is armed or in the air, and at rest
for ``ON_DEMAND_HOLD_S`` after a read asked for it (``TelemetryCache.refresh``): the read opens it and
waits for its next item, at most ``ON_DEMAND_WAIT_S``. A stream nobody reads costs nothing open (the
sidecar's gRPC thread for it sleeps until an item comes): what is saved is the items, not the stream.
"""

from __future__ import annotations

import asyncio
import contextlib
import math
import time
from collections.abc import AsyncIterator, Callable, Coroutine
from typing import Any

ON_DEMAND_AT_REST = frozenset({"rc_status"})
ON_DEMAND_HOLD_S = 60.0
ON_DEMAND_WAIT_S = 2.5

#: how a stream is opened and each of its items handled (the feed's ``_subscribe`` arguments)
Subscribe = Callable[[], AsyncIterator[Any]]  # Any: MAVSDK's stream item classes, untyped
Handle = Callable[[Any], None]
#: the feed's loop that keeps one stream flowing into the cache: pump(name, subscribe, handle)
Pump = Callable[[str, Subscribe, Handle], Coroutine[Any, Any, None]]


class OnDemandStreams:
    """The streams of one vehicle's feed opened at rest only for reads (``ON_DEMAND_AT_REST``)."""

    def __init__(self, vehicle_id: str, pump: Pump) -> None:
        self._vehicle_id = vehicle_id
        self._pump = pump
        self._streams: dict[str, tuple[Subscribe, Handle]] = {}
        self._tasks: dict[str, asyncio.Task[None]] = {}
        self._read_at: dict[str, float] = {}
        self._arrived: dict[str, asyncio.Event] = {}
        self._active = False

    def __bool__(self) -> bool:
        return bool(self._streams)

    def add(self, name: str, subscribe: Subscribe, handle: Handle, *, active: bool) -> None:
        self._streams[name] = (subscribe, handle)
        self.hold(active)

    def hold(self, active: bool) -> None:
        """Open each stream while the drone is active (armed or in the air) or the stream was read in
        the last ``ON_DEMAND_HOLD_S``, close it otherwise (the feed calls this with every position and
        landed state item)."""
        self._active = active
        now = time.monotonic()
        for name, (subscribe, handle) in self._streams.items():
            wanted = active or now - self._read_at.get(name, -math.inf) < ON_DEMAND_HOLD_S
            task = self._tasks.get(name)
            if wanted and task is None:
                self._tasks[name] = asyncio.create_task(
                    self._pump(name, subscribe, self._noting_arrival(name, handle)),
                    name=f"tm-{self._vehicle_id}-{name}",
                )
            elif not wanted and task is not None:
                del self._tasks[name]
                task.cancel()

    def _noting_arrival(self, name: str, handle: Handle) -> Handle:
        arrived = self._arrived.setdefault(name, asyncio.Event())

        def handled(item: object) -> None:
            handle(item)
            arrived.set()

        return handled

    async def refresh(self, name: str) -> None:
        """A read of ``name`` is coming: a stream closed at rest is opened (and held open for
        ``ON_DEMAND_HOLD_S``) and its next item awaited, at most ``ON_DEMAND_WAIT_S``; nothing for a
        stream that is open, or not one of these."""
        if name not in self._streams:
            return
        self._read_at[name] = time.monotonic()
        if name in self._tasks:
            return  # open: the cache holds its latest item
        arrived = self._arrived.setdefault(name, asyncio.Event())
        arrived.clear()
        self.hold(self._active)
        with contextlib.suppress(TimeoutError):
            await asyncio.wait_for(arrived.wait(), ON_DEMAND_WAIT_S)

    def close(self) -> list[asyncio.Task[None]]:
        """Forget every stream; their open tasks, cancelled, for the caller to await."""
        tasks = list(self._tasks.values())
        for task in tasks:
            task.cancel()
        self._tasks, self._streams = {}, {}
        return tasks
