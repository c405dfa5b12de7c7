"""The plain records the store takes and returns (pydantic models, never live ORM objects)."""

from __future__ import annotations

import json
import math
from collections.abc import Mapping
from dataclasses import dataclass
from datetime import UTC, datetime
from typing import Literal

from pydantic import BaseModel, ConfigDict, Field, field_validator

from gateway.registry.spec import VehicleSpec
from gateway.util.json_types import DocumentedJsonObject, JsonObject, JsonValue

AUDIT_MAX_STRING = 500
AUDIT_MAX_JSON = 8_000
AUDIT_MAX_ERROR = 2_000
STATUS_TEXT_MAX = 255

# MAVLink MAV_SEVERITY numbers to the names MAVSDK uses.
SEVERITY_NAMES = ("EMERGENCY", "ALERT", "CRITICAL", "ERROR", "WARNING", "NOTICE", "INFO", "DEBUG")

SessionKind = Literal["mcp-2025", "mcp-2026", "rest", "console"]
#: the door a call came through; "gateway": what the gateway itself recorded (a takeover it saw)
AuditSource = Literal["mcp", "rest", "console", "gateway"]
AuditOutcome = Literal["ok", "error", "refused", "running", "superseded", "cancelled"]
OperationStatus = Literal["running", "succeeded", "failed", "superseded", "interrupted", "cancelled"]
#: how a call that left its operation running ends in the audit, by how the operation ended (a fleet
#: operation's "partial" and "aborted" are errors too: not every drone did what was asked)
AUDIT_OUTCOME_OF_OPERATION: dict[str, AuditOutcome] = {
    "succeeded": "ok",
    "failed": "error",
    "interrupted": "error",
    "superseded": "superseded",
    "cancelled": "cancelled",
    "partial": "error",
    "aborted": "error",
}


def utcnow() -> datetime:
    return datetime.now(UTC)


# --- records -----------------------------------------------------------------------------------


class _Record(BaseModel):
    model_config = ConfigDict(from_attributes=True)


class VehicleRecord(VehicleSpec):
    """A stored vehicle registration: the spec plus bookkeeping."""

    model_config = ConfigDict(extra="forbid", from_attributes=True)

    auto_connect: bool = True
    created_at: datetime
    updated_at: datetime

    @property
    def spec(self) -> VehicleSpec:
        return VehicleSpec.model_validate(self.model_dump(include=set(VehicleSpec.model_fields)))


class FlightRecord(_Record):
    id: int
    vehicle_id: str
    started_at: datetime
    ended_at: datetime | None = None
    home_lat: float | None = None
    home_lon: float | None = None
    home_alt_amsl: float | None = None
    duration_s: float | None = None
    distance_m: float | None = None
    max_alt_rel_m: float | None = None
    battery_used_pct: float | None = None

    @property
    def is_open(self) -> bool:
        return self.ended_at is None


class TrackSample(_Record):
    """One point of a flight's track. ``t`` accepts an aware datetime or a Unix timestamp."""

    flight_id: int
    t: datetime
    lat: float = Field(ge=-90, le=90)
    lon: float = Field(ge=-180, le=180)
    alt_rel_m: float | None = None
    heading_deg: float | None = None
    ground_speed_mps: float | None = None
    battery_pct: float | None = None
    #: the autopilot's HEARTBEAT at the sample: its MAV_TYPE and custom mode (its flight mode)
    mav_type: int | None = Field(None, ge=0, le=255)
    custom_mode: int | None = Field(None, ge=0, le=2**32 - 1)
    #: its GPS at the sample: GPS_FIX_TYPE and satellites visible
    gps_fix_type: int | None = Field(None, ge=0, le=255)
    satellites: int | None = Field(None, ge=0, le=255)

    @field_validator("alt_rel_m", "heading_deg", "ground_speed_mps", "battery_pct")
    @classmethod
    def _finite_or_none(cls, value: float | None) -> float | None:
        """A non-finite reading is no reading (and would make the GeoJSON invalid)."""
        return value if value is None or math.isfinite(value) else None


class StatusTextIn(_Record):
    """A STATUSTEXT to store; ``severity`` is a MAV_SEVERITY number or name (stored as the name)."""

    vehicle_id: str
    flight_id: int | None = None
    t: datetime
    severity: str
    text: str

    @field_validator("severity", mode="before")
    @classmethod
    def _severity(cls, value: object) -> str:
        if isinstance(value, int) and 0 <= value < len(SEVERITY_NAMES):
            return SEVERITY_NAMES[value]
        name = getattr(value, "name", value)  # enums (e.g. MAVSDK's StatusTextType)
        return str(name).upper()[:16]

    @field_validator("text")
    @classmethod
    def _text(cls, value: str) -> str:
        return value[:STATUS_TEXT_MAX]


class StatusTextRecord(StatusTextIn):
    id: int


class SessionRecord(_Record):
    key: str
    kind: str
    principal: str | None = None
    client_name: str | None = None
    client_version: str | None = None
    first_seen: datetime
    last_seen: datetime
    request_count: int = 1


class AuditEntry(_Record):
    """One audited call. ``t`` defaults to now; arguments are bounded by the store."""

    session_key: str | None = None
    principal: str | None = None
    source: AuditSource
    vehicle_id: str | None = None
    action: str
    arguments: dict[str, object] = Field(default_factory=dict)  # as the caller gave them: bounded when stored
    outcome: AuditOutcome
    error: str | None = None
    duration_ms: float | None = None
    t: datetime | None = None
    operation_id: str | None = None


class AuditRecord(AuditEntry):
    id: int
    t: datetime


class OperationRecord(_Record):
    """A long-running vehicle action; saved (upserted by id) on every change of status or progress."""

    id: str = Field(min_length=1, max_length=64)
    vehicle_id: str
    kind: str
    params: DocumentedJsonObject = Field(default_factory=dict)
    status: OperationStatus
    progress: float = Field(0.0, ge=0.0, le=1.0)
    message: str | None = None
    result: DocumentedJsonObject | None = None
    session_key: str | None = None
    created_at: datetime = Field(default_factory=utcnow)
    updated_at: datetime = Field(default_factory=utcnow)
    finished_at: datetime | None = None


class LockRecord(_Record):
    """A stored operator lock (scope: a vehicle id, or "*" for the whole fleet)."""

    scope: str
    reason: str
    by: str
    locked_at: datetime


# --- argument bounding -------------------------------------------------------------------------


def bound_arguments(
    arguments: Mapping[str, object], max_string: int = AUDIT_MAX_STRING, max_json: int = AUDIT_MAX_JSON
) -> JsonObject:
    """Make audit arguments JSON-safe and bounded: long strings cut, whole object capped in size."""

    def walk(value: object, depth: int) -> JsonValue:
        if depth > 8:
            return "<nested too deep>"
        if value is None or isinstance(value, bool | int):
            return value
        if isinstance(value, float):
            return value if value == value and abs(value) != float("inf") else str(value)
        if isinstance(value, str):
            if len(value) > max_string:
                return value[:max_string] + f"...<{len(value) - max_string} more chars>"
            return value
        if isinstance(value, dict):
            return {str(k)[:max_string]: walk(v, depth + 1) for k, v in value.items()}
        if isinstance(value, list | tuple | set):
            return [walk(v, depth + 1) for v in value]
        if isinstance(value, BaseModel):
            return walk(value.model_dump(mode="json"), depth + 1)
        return walk(str(value), depth + 1)

    bounded = {str(k)[:max_string]: walk(v, 1) for k, v in arguments.items()}
    text = json.dumps(bounded, ensure_ascii=False)
    if len(text) > max_json:
        return {"_truncated": True, "_size": len(text), "_preview": text[: max_json // 2]}
    return bounded


OriginSource = Literal["first_home", "operator"]
ORIGIN_SOURCES: tuple[OriginSource, ...] = ("first_home", "operator")


@dataclass(frozen=True)
class Origin:
    """The point a vehicle's distance limit and zones count from (`gateway.fleet.policy.origin`), who
    set it and when."""

    vehicle_id: str
    lat: float
    lon: float
    alt_amsl_m: float
    source: OriginSource
    set_by: str
    set_at: datetime

    @property
    def point(self) -> tuple[float, float, float]:
        return (self.lat, self.lon, self.alt_amsl_m)

    def to_record(self) -> dict[str, object]:
        return {
            "vehicle_id": self.vehicle_id,
            "lat": self.lat,
            "lon": self.lon,
            "alt_amsl_m": self.alt_amsl_m,
            "source": self.source,
            "set_by": self.set_by,
            "set_at": self.set_at.isoformat(),
        }
