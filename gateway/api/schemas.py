"""Request and response bodies of the REST API (they make the OpenAPI document at /docs)."""

from __future__ import annotations

import re
from datetime import UTC, datetime
from typing import Annotated, Any

from pydantic import BaseModel, BeforeValidator, ConfigDict, Field, StrictBool, field_validator

from gateway.api.telemetry_schema import TelemetrySnapshot, VehicleStatus
from gateway.registry.spec import (
    NODE_TAG_PATTERN,
    VehicleSpec,
    validate_connection_url,
    validate_gcs_endpoints,
)
from gateway.registry.store import (
    AuditRecord,
    FlightRecord,
    OperationRecord,
    SessionRecord,
    StatusTextRecord,
    VehicleRecord,
)

_NUMBER = re.compile(r"^\s*[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?\s*$")


def _iso_time_only(value: object) -> object:
    """A time in a query is ISO 8601: a bare number ('0.5') would be read as seconds since 1970."""
    if isinstance(value, int | float) or (isinstance(value, str) and _NUMBER.match(value)):
        raise ValueError(f"must be an ISO 8601 time such as 2026-11-27T10:00:00Z; got {str(value)[:40]!r}")
    return value


#: a time given in a query string: ISO 8601 only
IsoTime = Annotated[datetime, BeforeValidator(_iso_time_only)]


class VehicleCreate(VehicleSpec):
    """A registration: the vehicle spec, and whether to connect now (and on every start)."""

    connect: StrictBool = Field(
        True, description="Start the vehicle's sidecar now and whenever the gateway starts."
    )

    def to_spec(self) -> VehicleSpec:
        return VehicleSpec.model_validate(self.model_dump(exclude={"connect"}))


class VehicleUpdate(BaseModel):
    """Fields to change; omitted fields stay as they are. ``null`` clears name / expected_sysid."""

    model_config = ConfigDict(extra="forbid")

    url: str | None = Field(None, description="New MAVLink connection URL (mavsdk_server syntax).")
    name: str | None = Field(None, max_length=100)
    tags: list[str] | None = Field(None, max_length=20)
    expected_sysid: int | None = Field(None, ge=1, le=255)
    node_tag: str | None = Field(
        None, pattern=NODE_TAG_PATTERN, description="Cluster: only nodes with this tag own it; null: any."
    )
    gcs_endpoints: list[str] | None = Field(
        None,
        description="The ground station endpoints, replacing the registered ones ([] removes them all); "
        "changing them reconnects a connected vehicle.",
    )
    auto_connect: StrictBool | None = Field(
        None, description="Connect this vehicle whenever the gateway starts."
    )

    @field_validator("url")
    @classmethod
    def _url(cls, value: str | None) -> str | None:
        if value is None:
            raise ValueError("url cannot be null")
        return validate_connection_url(value)

    @field_validator("gcs_endpoints")
    @classmethod
    def _gcs(cls, value: list[str] | None) -> list[str] | None:
        if value is None:
            raise ValueError("gcs_endpoints cannot be null; [] removes them all")
        return validate_gcs_endpoints(value)

    @field_validator("tags", "auto_connect")
    @classmethod
    def _not_null(cls, value: object) -> object:
        if value is None:
            raise ValueError("cannot be null")
        return value

    def changes(self) -> dict[str, object]:
        return {name: getattr(self, name) for name in self.model_fields_set}


class VehicleOut(VehicleRecord):
    """A registered vehicle with its live connection state."""

    model_config = ConfigDict(extra="ignore")

    state: str | None = Field(None, description="registered, connecting, connected, ready, link_lost, failed")
    status: VehicleStatus | None = Field(None, description="Connection details: heartbeat age, sidecar...")
    locked: str | None = Field(
        None, description="Why agents may not command this drone (its takeover lock, operator locks)."
    )
    taken_over: dict[str, Any] | None = Field(
        None,
        description="Its takeover lock: a pilot, another ground station or a failsafe changed its mode "
        "while the gateway flew it (reason, by, locked_at); DELETE /vehicles/{id}/takeover releases it.",
    )
    telemetry: TelemetrySnapshot | None = Field(  # type: ignore[valid-type]
        None, description="Latest telemetry snapshot, each part with its age (only on GET of one vehicle)."
    )


class VehicleList(BaseModel):
    items: list[VehicleOut]
    total: int


class Page(BaseModel):
    total: int
    limit: int
    offset: int


class FlightPage(Page):
    items: list[FlightRecord]


class AuditPage(Page):
    items: list[AuditRecord]


class SessionList(BaseModel):
    items: list[SessionRecord]


class StatusTextList(BaseModel):
    vehicle_id: str
    items: list[StatusTextRecord]


class OperationList(BaseModel):
    items: list[OperationRecord]


def as_utc(value: datetime | None) -> datetime | None:
    """Query datetimes without a zone are taken as UTC."""
    if value is None:
        return None
    return value.replace(tzinfo=UTC) if value.tzinfo is None else value.astimezone(UTC)


__all__ = [
    "AuditPage",
    "FlightPage",
    "OperationList",
    "SessionList",
    "StatusTextList",
    "VehicleCreate",
    "VehicleList",
    "VehicleOut",
    "VehicleUpdate",
    "as_utc",
]
