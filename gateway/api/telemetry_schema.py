"""Typed shapes of a vehicle's status and telemetry snapshot, as ``GET /api/v1/vehicles/{id}`` answers them.

The telemetry models are derived from the cache's own value types (``gateway.link.telemetry``), so the
OpenAPI document follows the cache when a field is added. Every part carries ``age_s`` and ``stale``; a
value MAVSDK reports as unknown (NaN) is null. Extra keys are allowed: a vehicle owned by another
cluster node reports a few more (owner, lease epoch, snapshot age).
"""

from __future__ import annotations

import dataclasses
import typing
from typing import Any

from pydantic import BaseModel, ConfigDict, Field, create_model

from gateway.link.telemetry import TelemetryCache


class _Open(BaseModel):
    model_config = ConfigDict(extra="allow")


class SidecarStatus(_Open):
    state: str = Field(description="stopped, starting, serving, backoff, failed (remote: on its owner node)")
    pid: int | None = None
    grpc_port: int | None = Field(
        None,
        description="While serving: the gRPC port on 127.0.0.1, or with socket confinement (the default) the "
        "number naming its private unix socket.",
    )
    restarts: int = 0


class GroundStationStatus(_Open):
    url: str = Field(description="The endpoint as registered (gcs_endpoints).")
    peer: str | None = Field(None, description="Who is connected there now (address:port), if anyone.")
    frames_in: int = Field(0, description="MAVLink frames received from ground stations there.")
    frames_out: int = Field(0, description="MAVLink frames relayed to ground stations there.")
    last_in_age_s: float | None = None
    system_ids: list[int] = Field(default_factory=list, description="MAVLink system ids heard there.")
    error: str | None = Field(None, description="Why the endpoint is not open or not reached.")


class VehicleStatus(_Open):
    """The link's view of a vehicle: connection state, heartbeat, autopilot, sidecar."""

    id: str
    name: str | None = None
    url: str | None = None
    tags: list[str] = Field(default_factory=list)
    state: str = Field(description="registered, connecting, connected, ready, link_lost, failed")
    state_age_s: float | None = None
    last_heartbeat_age_s: float | None = None
    last_heartbeat_at: str | None = Field(None, description="ISO 8601 time of the last HEARTBEAT.")
    last_error: str | None = None
    sysid: int | None = Field(None, description="MAVLink system id heard on the link.")
    expected_sysid: int | None = None
    sysid_mismatch: bool | None = None
    duplicate_sysid: list[str] = Field(
        default_factory=list, description="Other connected vehicles reporting the same system id."
    )
    other_sysids_on_link: list[int] = Field(default_factory=list)
    is_simulator: bool | None = None
    autopilot: str | None = Field(None, description="ardupilot, px4 or another MAV_AUTOPILOT name.")
    autopilot_version: str | None = None
    flight_mode: str | None = None
    armed: bool | None = None
    initialising: str | None = Field(None, description="What a connected vehicle still waits for.")
    unsupported_streams: list[str] = Field(default_factory=list)
    sidecar: SidecarStatus | None = None
    ground_stations: list[GroundStationStatus] = Field(
        default_factory=list, description="The gcs_endpoints the drone's MAVLink is relayed to, live."
    )


class StatusTextItem(_Open):
    t: float = Field(description="Unix time it arrived.")
    severity: str = Field(description="info, warning, critical, ...")
    text: str


# Any: pydantic, a type expression (typing.get_args) and create_model's field definitions
def _part_model(name: str, value_type: Any) -> type[BaseModel]:
    fields: dict[str, Any] = {}  # Any: pydantic, create_model's field definitions
    if dataclasses.is_dataclass(value_type):
        hints = typing.get_type_hints(value_type)
        for f in dataclasses.fields(value_type):
            fields[f.name] = (hints[f.name] | None, None)
    else:
        fields["value"] = (value_type | None, None)
    fields["age_s"] = (float, Field(description="Seconds since the value arrived."))
    fields["stale"] = (bool, Field(description="Older than the stale limit, or the link is down."))
    title = "".join(part.capitalize() for part in name.split("_")) + "Part"
    model: type[BaseModel] = create_model(title, __base__=_Open, **fields)
    return model


def _telemetry_model() -> type[BaseModel]:
    hints = typing.get_type_hints(TelemetryCache)
    fields: dict[str, Any] = {}  # Any: pydantic, create_model's field definitions
    for name in TelemetryCache.FIELDS:
        sample_type = next(a for a in typing.get_args(hints[name]) if a is not type(None))
        (value_type,) = typing.get_args(sample_type)
        fields[name] = (_part_model(name, value_type) | None, None)
    fields["status_texts"] = (
        list[StatusTextItem],
        Field(default_factory=list, description="The last 10 STATUSTEXT messages, oldest first."),
    )
    model: type[BaseModel] = create_model(
        "TelemetrySnapshot",
        __base__=_Open,
        __doc__="The latest value of every stream, each with its age; null until first received.",
        **fields,
    )
    return model


TelemetrySnapshot = _telemetry_model()
