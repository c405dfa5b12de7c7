"""What the Commander returns: plain pydantic models, JSON-serialisable (``model_dump(mode="json")``)
and rebuilt from JSON (``model_validate``), so a result can cross a process boundary unchanged."""

from __future__ import annotations

from datetime import UTC, datetime
from typing import Literal

from pydantic import BaseModel, Field, SkipValidation, field_validator

from gateway.fleet.missions.mission import MissionItem
from gateway.fleet.operations.operation_state import Operation
from gateway.fleet.policy.operator_locks import Lock
from gateway.fleet.vehicles.protocols import VehicleView
from gateway.fleet.vehicles.readings import position
from gateway.registry.records import OperationRecord
from gateway.util.json_types import JsonObject


class OperationFacts(BaseModel):
    """What every answer about a tracked operation says (the REST view, the MCP tools' result)."""

    drone_id: str
    operation_id: str
    kind: str
    status: str
    progress: float
    message: str
    eta_s: float | None = None
    elapsed_s: float


class OperationView(OperationFacts):
    """A tracked operation at one moment, with where its drone is."""

    params: JsonObject = Field(default_factory=dict)
    lat_deg: float | None = None
    lon_deg: float | None = None
    alt_m: float | None = None

    @classmethod
    def of(cls, op: Operation, vehicle: VehicleView | None) -> OperationView:
        pos = None if vehicle is None else position(vehicle)
        return cls(
            operation_id=op.id,
            drone_id=op.vehicle_id,
            kind=op.kind,
            status=op.status.value,
            progress=round(op.progress, 3),
            message=op.message,
            eta_s=None if op.eta_s is None else round(op.eta_s, 1),
            elapsed_s=round(op.elapsed_s(), 1),
            params=dict(op.params),
            lat_deg=None if pos is None else pos[0],
            lon_deg=None if pos is None else pos[1],
            alt_m=None if pos is None else round(pos[2], 2),
        )

    @classmethod
    def of_record(cls, record: OperationRecord, message: str | None = None) -> OperationView:
        """A stored operation (run by another process), as the database last had it."""
        end = record.finished_at or datetime.now(UTC)
        start = record.created_at
        if start.tzinfo is None or end.tzinfo is None:  # SQLite gives naive UTC times
            start, end = start.replace(tzinfo=UTC), end.replace(tzinfo=UTC)
        return cls(
            operation_id=record.id,
            drone_id=record.vehicle_id,
            kind=record.kind,
            status=record.status,
            progress=round(record.progress, 3),
            message=message or record.message or record.status,
            elapsed_s=round(max(0.0, (end - start).total_seconds()), 1),
            params=dict(record.params),
        )

    @property
    def running(self) -> bool:
        return self.status == "running"


class ActionResult(BaseModel):
    """An instant command (arm, hold, mode, kill, speed, mission upload...): done when accepted.
    ``facts`` holds what the command established (e.g. the mode's native name, the item count)."""

    drone_id: str
    action: str
    message: str
    superseded_operation: str | None = None
    facts: JsonObject = Field(default_factory=dict)


class ArrivalView(BaseModel):
    """Whether the last goto arrived; with no goto sent, only the drone, ``arrived`` false and why."""

    drone_id: str
    arrived: bool
    operation_id: str | None = None
    kind: str | None = None
    status: str | None = None
    distance_m: float | None = None
    vertical_m: float | None = None
    message: str


class MissionView(BaseModel):
    drone_id: str
    items: list[SkipValidation[MissionItem]]

    @field_validator("items", mode="before")
    @classmethod
    def _as_the_drone_holds_them(cls, value: object) -> object:
        """A downloaded mission is reported as the drone holds it, not checked again as new input: a
        mission another planner wrote may have items at latitude and longitude 0 (ArduPilot: where the
        drone is), which an upload would refuse (the view crosses to the caller as JSON and back)."""
        if not isinstance(value, list):
            return value
        return [MissionItem.model_construct(**v) if isinstance(v, dict) else v for v in value]


class MissionFileView(BaseModel):
    """A drone's mission as a ground station's file (QGC .plan JSON or QGC WPL 110 text)."""

    drone_id: str
    format: str
    items: int
    content: str


class MissionProgressView(BaseModel):
    drone_id: str
    current: int
    total: int
    finished: bool
    operation_status: str | None


class ParamValue(BaseModel):
    drone_id: str
    name: str
    value: float
    type: str


class ParamPage(BaseModel):
    drone_id: str
    prefix: str
    total: int
    offset: int
    params: dict[str, float]
    next_offset: int | None


class FleetView(BaseModel):
    """A fleet operation at one moment: per-drone outcomes in ``drones``; drones that were not sent
    the command (recovery commands go to those that can) in ``not_sent``."""

    operation_id: str
    kind: str
    status: str
    message: str
    phase: int
    phases: list[str]
    progress: float
    eta_s: float | None
    elapsed_s: float
    dispatch_s: list[float]
    drones: list[JsonObject]
    not_sent: list[dict[str, object]] = Field(default_factory=list)  # `Unable.to_dict`: error details
    notes: list[str] = Field(default_factory=list)
    plan: JsonObject | None = None

    @property
    def running(self) -> bool:
        return self.status == "running"


class FleetHoldResult(BaseModel):
    held: list[str]
    failed: list[dict[str, object]]  # `Unable.to_dict`: error details
    not_sent: list[dict[str, object]]
    superseded_fleet_operations: list[str]


#: what became of one drone's stop (the REST answer and the Commander's say the same)
StopOutcomeKind = Literal["sent", "skipped", "taking_over", "unreached", "failed"]
STOP_OUTCOME_DOC = (
    "sent: the command was sent to the drone (by its node, or over the drone's own link by the node that "
    "took the stop when its node did not answer); skipped: on the ground or not connected; taking_over: "
    "not confirmed yet: no node acknowledged it in time and the drone's link is held elsewhere, so the node "
    "that took the stop keeps trying and sends it itself as soon as it reaches the drone (the message says "
    "how and for how long); unreached: nothing was sent and nothing more is being tried; failed: the command "
    "was refused or its answer was lost."
)


class StopReport(BaseModel):
    """What a stop did to one drone, without the drone's name (`StopOutcome` names it ``drone_id``, the
    REST API's answer ``vehicle_id``)."""

    action: str
    outcome: StopOutcomeKind = Field(description=STOP_OUTCOME_DOC)
    message: str | None = Field(None, description="Why, and for taking_over what is being done about it.")
    superseded_operation: str | None = None
    operation_id: str | None = Field(None, description="The tracked operation (GET /api/v1/operations).")


class StopOutcome(StopReport):
    """One drone's part of a stop (the fleet stop, or an operator's hold, land or RTL of one drone)."""

    drone_id: str


class LockResult(BaseModel):
    scope: str = Field(description='A vehicle id, or "*" for the whole fleet.')
    reason: str
    by: str
    locked_at: datetime
    stored: bool = Field(
        True,
        description="False: the database was unreachable; the lock holds on this node (and every node "
        "that heard of it) now and is stored when the database is back.",
    )

    @classmethod
    def of(cls, lock: Lock) -> LockResult:
        """A lock in force (an operator's lock or a takeover lock), as stored."""
        return cls(scope=lock.scope, reason=lock.reason, by=lock.by, locked_at=lock.locked_at)


class UnlockResult(BaseModel):
    scope: str
    was_locked: bool


class StopResult(BaseModel):
    action: str
    fleet_lock: LockResult | None
    superseded_fleet_operations: list[str]
    results: list[StopOutcome]
