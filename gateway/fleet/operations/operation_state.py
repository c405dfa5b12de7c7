"""One operation's state: its status (running until final), progress, message, estimate, and the events
its waiters wait on; what the manager saves to the store and the tools show."""

from __future__ import annotations

import asyncio
import contextlib
import time
from collections.abc import Awaitable, Callable, Hashable
from dataclasses import dataclass, field
from datetime import datetime
from enum import StrEnum
from typing import Protocol, TypeVar

from gateway.util.json_types import JsonObject


class OpStatus(StrEnum):
    running = "running"
    succeeded = "succeeded"
    failed = "failed"
    superseded = "superseded"
    interrupted = "interrupted"
    cancelled = "cancelled"


FINAL = frozenset(s for s in OpStatus if s is not OpStatus.running)


@dataclass
class Operation:
    id: str
    vehicle_id: str
    kind: str
    params: JsonObject
    session_key: str | None
    created_at: datetime
    status: OpStatus = OpStatus.running
    progress: float = 0.0
    message: str = "command sent"
    #: what every later message keeps saying (e.g. that another node took the operation over)
    note: str | None = None
    #: why tracking was interrupted, once per interruption (sidecar restart, link lost): the answer says so
    interruptions: list[str] = field(default_factory=list)
    eta_s: float | None = None
    updated_at: datetime | None = None
    finished_at: datetime | None = None
    started_mono: float = field(default_factory=time.monotonic)
    changed: asyncio.Event = field(default_factory=asyncio.Event, repr=False)
    done: asyncio.Event = field(default_factory=asyncio.Event, repr=False)

    @property
    def finished(self) -> bool:
        return self.status in FINAL

    def elapsed_s(self) -> float:
        return time.monotonic() - self.started_mono

    def to_dict(self) -> JsonObject:
        return {
            "operation_id": self.id,
            "drone_id": self.vehicle_id,
            "kind": self.kind,
            "status": self.status.value,
            "progress": round(self.progress, 3),
            "message": self.message,
            "eta_s": None if self.eta_s is None else round(self.eta_s, 1),
            "elapsed_s": round(self.elapsed_s(), 1),
            "params": self.params,
        }


class Watched(Protocol):
    """What a waiter reads of an operation, one drone's or a fleet's: whether it finished and the event
    set on each change."""

    @property
    def finished(self) -> bool: ...

    @property
    def changed(self) -> asyncio.Event: ...


W = TypeVar("W", bound=Watched)


async def wait_reporting(
    watched: W,
    cap_s: float,
    mark: Callable[[W], Hashable],
    report: Callable[[W], Awaitable[None]] | None,
) -> W:
    """Wait until ``watched`` has finished or ``cap_s`` passed, calling ``report`` after each change
    whose ``mark`` differs from the last reported; cancelling the waiter stops nothing."""
    deadline = time.monotonic() + max(0.0, cap_s)
    last: Hashable = None
    while not watched.finished:
        remaining = deadline - time.monotonic()
        if remaining <= 0:
            break
        watched.changed.clear()
        with contextlib.suppress(TimeoutError):
            await asyncio.wait_for(watched.changed.wait(), timeout=min(remaining, 1.0))
        now = mark(watched)
        if report is not None and now != last:
            last = now
            await report(watched)
    return watched
