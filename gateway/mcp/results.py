"""Structured results of the MCP tools. Field names carry their units (``_m``, ``_deg``, ``_s``, ``_pct``)
so the output schemas need no descriptions."""

from __future__ import annotations

import dataclasses
import enum
import json
import math
from typing import Self

from pydantic import BaseModel, PrivateAttr

from gateway.fleet.operations.views import (
    ActionResult,
    MissionProgressView,
    OperationFacts,
    ParamPage,
    ParamValue,
)
from gateway.fleet.vehicles.vehicle_text import VEHICLE_TEXT_LABEL, clean_vehicle_text
from gateway.util.json_types import JsonValue


class Result(BaseModel):
    """Base of every tool result: structured fields plus a one-line text summary."""

    _text: str = PrivateAttr(default="")

    def say(self, text: str) -> Self:
        self._text = text
        return self

    def text(self) -> str:
        return self._text or json.dumps(self.model_dump(mode="json"), separators=(",", ":"))


class OperationOut(Result, OperationFacts):
    """A long-running action: 'running' means it continues on the vehicle; call monitor_flight."""

    lat_deg: float | None = None
    lon_deg: float | None = None
    alt_m: float | None = None


class ActionOut(Result):
    drone_id: str
    action: str
    message: str
    superseded_operation: str | None = None


def action_out(result: ActionResult, text: str) -> ActionOut:
    """An instant command's result as a tool presents it, with its one line of text."""
    return ActionOut(
        drone_id=result.drone_id,
        action=result.action,
        message=result.message,
        superseded_operation=result.superseded_operation,
    ).say(text)


class Fresh(Result):
    """Base of telemetry answers: how old the data is and whether it is stale (link lost)."""

    drone_id: str
    age_s: float | None
    stale: bool


class PositionOut(Fresh):
    lat_deg: float
    lon_deg: float
    alt_m: float
    alt_amsl_m: float


class BatteryOut(Fresh):
    remaining_pct: float | None
    voltage_v: float | None


class SpeedOut(Fresh):
    north_mps: float
    east_mps: float
    climb_mps: float
    ground_speed_mps: float


class AttitudeOut(Fresh):
    roll_deg: float
    pitch_deg: float
    yaw_deg: float


class GpsOut(Fresh):
    num_satellites: int
    fix_type: str


# Open JSON in these results: a telemetry value as `plain` makes it (a JsonValue), typed ``object`` so that
# pydantic gives it an open outputSchema, which clients validate against (JsonValue adds a $defs entry)
class ValueOut(Fresh):
    """A single telemetry value (flight mode, armed, in air, landed state, heading)."""

    value: object


class DataOut(Fresh):
    """A telemetry record with many fields (health, RC, IMU, odometry)."""

    data: dict[str, object]


class SnapshotOut(Result):
    drone_id: str
    state: str
    telemetry: dict[str, object]
    operation: dict[str, object] | None


class StatusTextOut(Result):
    drone_id: str
    messages: list[dict[str, object]]


class ArrivalOut(Result):
    drone_id: str
    arrived: bool
    operation_id: str | None
    status: str | None
    distance_m: float | None
    vertical_m: float | None
    message: str


class MissionItemOut(Result):
    index: int
    kind: str
    lat_deg: float
    lon_deg: float
    alt_m: float
    hold_s: float = 0.0
    speed_mps: float | None = None


class MissionOut(Result):
    drone_id: str
    count: int
    items: list[MissionItemOut]


class MissionProgressOut(Result, MissionProgressView):
    pass


class ParamOut(Result, ParamValue):
    pass


class ParamListOut(Result, ParamPage):
    names_note: str = ""


def plain_object(value: object) -> dict[str, JsonValue]:
    """`plain` of a record (a status, a snapshot): its fields; anything else is no record (empty)."""
    out = plain(value)
    return out if isinstance(out, dict) else {}


def plain(value: object, depth: int = 0) -> JsonValue:
    """MAVSDK objects, dataclasses, enums -> JSON-friendly values (NaN -> None)."""
    if depth > 6:
        return str(value)
    if value is None or isinstance(value, bool | int | str):
        return value
    if isinstance(value, float):
        return value if math.isfinite(value) else None
    if isinstance(value, enum.Enum):
        return value.name
    if isinstance(value, dict):
        return {str(k): plain(v, depth + 1) for k, v in value.items()}
    if isinstance(value, list | tuple | set | frozenset):
        return [plain(v, depth + 1) for v in value]
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        return {f.name: plain(getattr(value, f.name), depth + 1) for f in dataclasses.fields(value)}
    if hasattr(value, "model_dump"):
        return plain(value.model_dump(), depth + 1)
    if hasattr(value, "__dict__"):
        return {k: plain(v, depth + 1) for k, v in vars(value).items() if not k.startswith("_")}
    if hasattr(value, "__slots__"):
        return {k: plain(getattr(value, k), depth + 1) for k in value.__slots__ if not k.startswith("_")}
    return str(value)


#: telemetry field names of the fleet layer -> the names every tool uses (lat_deg, lon_deg, alt_m above
#: home, alt_amsl_m, climb_mps); see docs/tools.md, "Names"
_SURFACE_NAMES = {"rel_alt_m": "alt_m", "abs_alt_m": "alt_amsl_m"}


def surface_telemetry(snapshot: dict[str, JsonValue]) -> dict[str, JsonValue]:
    """A telemetry snapshot in the tools' own names, its status texts as data from the vehicle."""
    out: dict[str, JsonValue] = {}
    for part, body in snapshot.items():
        if isinstance(body, dict):
            body = {_SURFACE_NAMES.get(k, k): v for k, v in body.items()}
            if "down_mps" in body:
                down = body.pop("down_mps")
                body["climb_mps"] = -down + 0.0 if isinstance(down, int | float) else None
        elif part == "status_texts" and isinstance(body, list):
            body = [
                {**item, "text": clean_vehicle_text(str(item.get("text", "")))}
                if isinstance(item, dict)
                else item
                for item in body
            ]
            if body:
                out["status_texts_note"] = VEHICLE_TEXT_LABEL
        out[part] = body
    return out
