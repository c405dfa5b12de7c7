"""What a fleet operation is made of: its members (one per drone, with its latest outcome and slot), its
phases' progress, its status and the events its waiters wait on."""

from __future__ import annotations

import asyncio
import time
from dataclasses import dataclass, field
from datetime import UTC, datetime
from typing import TypedDict

from gateway.fleet.operations.operation_state import Operation, OpStatus
from gateway.fleet.policy.caller import Caller
from gateway.util.json_types import JsonObject

FLEET_CALLER = Caller(via="cluster", principal="fleet")
"""The caller of a fleet operation started without one (judged as an agent)."""


class SlotSummary(TypedDict, total=False):
    """A drone's own figures in a fleet operation's result: its formation slot (target, transit altitude,
    distance to fly), its takeoff altitude (``target_alt_m`` alone) or its return altitude."""

    target_lat_deg: float
    target_lon_deg: float
    target_alt_m: float
    transit_alt_m: float | None
    distance_m: float
    rtl_alt_m: float


@dataclass
class Member:
    """One drone of a fleet operation: its latest outcome and, for formations, its slot."""

    drone_id: str
    status: str = "waiting"  # waiting | running | succeeded | failed | superseded | held | not_sent
    message: str = "waiting for its phase"
    operation_id: str | None = None
    sent_after_s: float | None = None  # since the fleet operation started: its latest command went out
    accepted_after_s: float | None = None  # ... and was accepted by the vehicle
    slot: SlotSummary | None = None

    def to_dict(self) -> JsonObject:
        out: JsonObject = {
            "drone_id": self.drone_id,
            "status": self.status,
            "message": self.message,
            "operation_id": self.operation_id,
            "sent_after_s": self.sent_after_s,
            "accepted_after_s": self.accepted_after_s,
        }
        if self.slot is not None:
            out.update(**self.slot)
        return out


FINAL_FLEET = frozenset({"succeeded", "partial", "failed", "aborted", "superseded", "interrupted"})


@dataclass
class FleetOperation:
    """A group of per-drone operations run in phases. Status: running, then succeeded (every drone),
    partial (some drones), failed (none), aborted (a formation stopped after a failure), superseded or
    interrupted."""

    id: str
    kind: str
    drone_ids: list[str]
    params: JsonObject
    members: dict[str, Member]
    phase_names: list[str]
    session_key: str | None = None
    plan: JsonObject | None = None
    notes: list[str] = field(default_factory=list)
    caller: Caller = FLEET_CALLER  # who asked: a step run on another node is judged as theirs
    status: str = "running"
    message: str = "starting"
    phase: int = 0  # 1-based index of the phase running (0: not started)
    dispatch_s: list[float] = field(default_factory=list)  # per phase: first command sent -> all accepted
    created_at: datetime = field(default_factory=lambda: datetime.now(UTC))
    started_mono: float = field(default_factory=time.monotonic)
    finished_mono: float | None = None
    changed: asyncio.Event = field(default_factory=asyncio.Event, repr=False)
    done: asyncio.Event = field(default_factory=asyncio.Event, repr=False)
    dispatched: asyncio.Event = field(default_factory=asyncio.Event, repr=False)  # first phase sent
    ops: dict[str, Operation] = field(default_factory=dict, repr=False)  # current step per drone

    @property
    def finished(self) -> bool:
        return self.status in FINAL_FLEET

    def elapsed_s(self) -> float:
        end = self.finished_mono if self.finished_mono is not None else time.monotonic()
        return end - self.started_mono

    @property
    def progress(self) -> float:
        """Phases done plus the mean progress of the current phase's steps, over the phase count."""
        if self.status == "succeeded":
            return 1.0
        total = max(1, len(self.phase_names))
        current = [op.progress if not op.finished or op.status is not OpStatus.succeeded else 1.0
                   for op in self.ops.values()]  # fmt: skip
        within = sum(current) / len(current) if current else 0.0
        return max(0.0, min(1.0, (max(self.phase, 1) - 1 + within) / total))

    def eta_s(self) -> float | None:
        etas = [op.eta_s for op in self.ops.values() if not op.finished and op.eta_s is not None]
        return max(etas) if etas else None

    def to_dict(self) -> JsonObject:
        eta = self.eta_s()
        return {
            "operation_id": self.id,
            "kind": self.kind,
            "status": self.status,
            "message": self.message,
            "phase": self.phase,
            "phases": list(self.phase_names),
            "progress": round(self.progress, 3),
            "eta_s": None if eta is None or self.finished else round(eta, 1),
            "elapsed_s": round(self.elapsed_s(), 1),
            "dispatch_s": [round(d, 3) for d in self.dispatch_s],
            "drones": [m.to_dict() for m in self.members.values()],
            "notes": list(self.notes),
        }
