"""Request and response bodies of the REST API (they make the OpenAPI document at /docs)."""

from __future__ import annotations

import re
from collections.abc import Callable
from datetime import UTC, datetime
from typing import Annotated

from pydantic import BaseModel, BeforeValidator, ConfigDict, Field, StrictBool, field_validator

from gateway.api.telemetry_schema import TelemetrySnapshot, VehicleStatus
from gateway.errors import InvalidArgument
from gateway.registry.spec import (
    MAX_GCS_ENDPOINTS,
    NODE_TAG_PATTERN,
    VehicleChanges,
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
from gateway.util.json_types import DocumentedJsonObject, JsonObject

_NUMBER = re.compile(r"^\s*[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?\s*$")


def _iso_time_only(value: object) -> object:
    """A time in a query is ISO 8601: a bare number ('0.5') would be read as seconds since 1970."""
    if isinstance(value, int | float) or (isinstance(value, str) and _NUMBER.match(value)):
        raise ValueError(f"must be an ISO 8601 time such as 2026-11-27T10:00:00Z; got {str(value)[:40]!r}")
    return value


#: a time given in a query string: ISO 8601 only
IsoTime = Annotated[datetime, BeforeValidator(_iso_time_only)]


_PORT = r"([1-9][0-9]{0,3}|[1-5][0-9]{4}|6[0-4][0-9]{3}|65[0-4][0-9]{2}|655[0-2][0-9]|6553[0-5])"
_NETWORK_URL = rf"(udpin|udpout|tcpin|tcpout)://[A-Za-z0-9.\-]{{1,253}}:{_PORT}"
#: what `validate_connection_url` accepts, said in the OpenAPI document (the validator's line stays the
#: answer to a URL outside it)
URL_SCHEMA: JsonObject = {
    "type": "string",
    "maxLength": 256,
    "pattern": rf"^({_NETWORK_URL}|serial:///[^:?#@]*(:[0-9]*)?)$",
}
GCS_ENDPOINTS_SCHEMA: JsonObject = {
    "type": "array",
    "items": {"type": "string", "maxLength": 256, "pattern": rf"^{_NETWORK_URL}$"},
    "maxItems": MAX_GCS_ENDPOINTS,
    "uniqueItems": True,
}
TAGS_SCHEMA: JsonObject = {
    "type": "array",
    "items": {"type": "string", "pattern": r"^[A-Za-z0-9_.\-]{1,32}$"},
    "maxItems": 20,
}


class VehicleCreate(VehicleSpec):
    """A registration: the vehicle spec, and whether to connect now (and on every start)."""

    url: str = Field(
        description="MAVLink connection URL in mavsdk_server syntax, e.g. tcpout://127.0.0.1:5760",
        json_schema_extra=URL_SCHEMA,
    )
    tags: list[str] = Field(
        default_factory=list,
        description="Free tags, e.g. ['survey'].",
        json_schema_extra=TAGS_SCHEMA,
    )
    gcs_endpoints: list[str] = Field(
        default_factory=list,
        description=VehicleSpec.model_fields["gcs_endpoints"].description,
        json_schema_extra=GCS_ENDPOINTS_SCHEMA,
    )
    connect: StrictBool = Field(
        True, description="Start the vehicle's sidecar now and whenever the gateway starts."
    )

    def to_spec(self) -> VehicleSpec:
        return VehicleSpec.model_validate(self.model_dump(exclude={"connect"}))


def _not_nullable(schema: JsonObject) -> Callable[[JsonObject], None]:
    """The field's OpenAPI schema is ``schema`` (it may be omitted, never null), with its description."""

    def replace(generated: JsonObject) -> None:
        described: JsonObject = {k: generated[k] for k in ("title", "description") if k in generated}
        generated.clear()
        generated.update({**schema, **described})

    return replace


class VehicleUpdate(BaseModel):
    """Fields to change; omitted fields stay as they are. ``null`` clears name / expected_sysid /
    node_tag; at least one field is given."""

    model_config = ConfigDict(extra="forbid", json_schema_extra={"minProperties": 1})

    url: str | None = Field(
        None,
        description="New MAVLink connection URL (mavsdk_server syntax).",
        json_schema_extra=_not_nullable(URL_SCHEMA),
    )
    name: str | None = Field(None, max_length=100)
    tags: list[str] | None = Field(None, max_length=20, json_schema_extra=_not_nullable(TAGS_SCHEMA))
    expected_sysid: int | None = Field(None, ge=1, le=255)
    node_tag: str | None = Field(
        None, pattern=NODE_TAG_PATTERN, description="Cluster: only nodes with this tag own it; null: any."
    )
    gcs_endpoints: list[str] | None = Field(
        None,
        description="The ground station endpoints, replacing the registered ones ([] removes them all); "
        "changing them reconnects a connected vehicle.",
        json_schema_extra=_not_nullable(GCS_ENDPOINTS_SCHEMA),
    )
    auto_connect: StrictBool | None = Field(
        None,
        description="Connect this vehicle whenever the gateway starts.",
        json_schema_extra=_not_nullable({"type": "boolean"}),
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

    def changes(self) -> VehicleChanges:
        """The fields the request set (a null where one is refused was refused by the validators)."""
        changes = VehicleChanges()
        given = self.model_fields_set
        if "name" in given:
            changes["name"] = self.name
        if "tags" in given and self.tags is not None:
            changes["tags"] = self.tags
        if "expected_sysid" in given:
            changes["expected_sysid"] = self.expected_sysid
        if "node_tag" in given:
            changes["node_tag"] = self.node_tag
        if "url" in given and self.url is not None:
            changes["url"] = self.url
        if "gcs_endpoints" in given and self.gcs_endpoints is not None:
            changes["gcs_endpoints"] = self.gcs_endpoints
        if "auto_connect" in given and self.auto_connect is not None:
            changes["auto_connect"] = self.auto_connect
        return changes


class VehicleOut(VehicleRecord):
    """A registered vehicle with its live connection state."""

    model_config = ConfigDict(extra="ignore")

    state: str | None = Field(None, description="registered, connecting, connected, ready, link_lost, failed")
    status: VehicleStatus | None = Field(None, description="Connection details: heartbeat age, sidecar...")
    locked: str | None = Field(
        None, description="Why agents may not command this drone (its takeover lock, operator locks)."
    )
    taken_over: DocumentedJsonObject | None = Field(
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


def time_window(since: datetime | None, until: datetime | None) -> tuple[datetime | None, datetime | None]:
    """A query's ``since`` and ``until`` in UTC; refused when since is after until."""
    since, until = as_utc(since), as_utc(until)
    if since is not None and until is not None and since > until:
        raise InvalidArgument(f"since ({since.isoformat()}) is after until ({until.isoformat()})")
    return since, until


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
    "time_window",
]
