"""Telemetry toolset: answers at once from the telemetry cache, with each value's age. Every tool here
only reads (nothing is sent to the drone and no state changes), so none is a command: commands are
declared with their verbs (gateway/fleet/commands).

A value older than its stream's limit (``link_lost_after_s``, longer for a stream asked for slower at
rest: ``TelemetryCache.stale_limit_s``) is flagged ``stale`` (and said so in the text), never passed off
as current.
"""

from __future__ import annotations

import json
import math
from collections.abc import Callable
from typing import Annotated, TypedDict, TypeVar

from pydantic import Field

from gateway.errors import VehicleNotReady
from gateway.fleet.vehicles.readings import is_stale
from gateway.fleet.vehicles.vehicle_text import VEHICLE_TEXT_LABEL, clean_vehicle_text
from gateway.link.telemetry import Sample, TelemetryCache
from gateway.mcp.access import ToolCall
from gateway.mcp.results import (
    AttitudeOut,
    BatteryOut,
    DataOut,
    GpsOut,
    SnapshotOut,
    SpeedOut,
    StatusTextOut,
    ValueOut,
    plain,
    plain_object,
    surface_telemetry,
)
from gateway.mcp.toolkit import DroneId, Toolset
from gateway.util.json_types import JsonValue

toolset = Toolset("telemetry")

T = TypeVar("T")


class Freshness(TypedDict):
    """The fields every telemetry answer starts with (`Fresh`): whose value, how old, whether stale."""

    drone_id: str
    age_s: float
    stale: bool


def read(
    call: ToolCall, drone_id: str, name: str, pick: Callable[[TelemetryCache], Sample[T] | None]
) -> tuple[T, Freshness, str]:
    """(value, freshness, note) of one cached telemetry part (``pick`` reads it of the cache)."""
    v = call.commander.vehicle(drone_id)
    s = pick(v.telemetry)
    if s is None:
        raise VehicleNotReady(f"no {name.replace('_', ' ')} received from {drone_id} yet (state: {v.state})")
    age = float(s.age_s)
    stale = is_stale(v, age, v.telemetry.stale_limit_s(name))
    note = f" [STALE: {age:.0f} s old, link lost?]" if stale else ""
    return s.value, Freshness(drone_id=drone_id, age_s=round(age, 2), stale=stale), note


def _named(name: str) -> Callable[[TelemetryCache], Sample[object] | None]:
    """Read the part called ``name`` (the value and data tools present any part alike)."""

    def pick(cache: TelemetryCache) -> Sample[object] | None:
        found: Sample[object] | None = getattr(cache, name, None)
        return found

    return pick


def _value_tool(call: ToolCall, drone_id: str, name: str, label: str) -> ValueOut:
    got, fresh, note = read(call, drone_id, name, _named(name))
    val = plain(got)
    return ValueOut(**fresh, value=val).say(f"{drone_id} {label}: {val}{note}")


def _data_tool(call: ToolCall, drone_id: str, name: str) -> DataOut:
    got, fresh, note = read(call, drone_id, name, _named(name))
    data = plain(got)
    if not isinstance(data, dict):
        data = {"value": data}
    text = ", ".join(f"{k}={_short(v)}" for k, v in data.items())
    return DataOut(**fresh, data=data).say(f"{drone_id} {name}: {text}{note}")


def _value_reader(name: str, part: str, label: str, doc: str) -> None:
    """Declare the read tool ``name``: the cached telemetry part ``part`` as one value, said as ``label``."""

    async def read_value(call: ToolCall, drone_id: DroneId) -> ValueOut:
        return _value_tool(call, drone_id, part, label)

    read_value.__name__ = read_value.__qualname__ = name
    read_value.__doc__ = doc
    toolset.tool(read_only=True)(read_value)


def _data_reader(name: str, part: str, doc: str) -> None:
    """Declare the read tool ``name``: the fields of the cached telemetry part ``part``."""

    async def read_data(call: ToolCall, drone_id: DroneId) -> DataOut:
        return _data_tool(call, drone_id, part)

    read_data.__name__ = read_data.__qualname__ = name
    read_data.__doc__ = doc
    toolset.tool(read_only=True)(read_data)


def _short(v: object) -> str:
    if isinstance(v, float):
        return f"{v:.3g}"
    if isinstance(v, dict):
        return "{" + ", ".join(f"{k}={_short(x)}" for k, x in v.items()) + "}"
    return str(v)


@toolset.tool(read_only=True)
async def get_battery(call: ToolCall, drone_id: DroneId) -> BatteryOut:
    """Battery remaining_pct (0-100) and voltage_v."""
    b, fresh, note = read(call, drone_id, "battery", lambda t: t.battery)
    pct = plain(b.remaining_pct)
    volts = plain(b.voltage_v)
    pct_text = "unknown" if pct is None else f"{pct:.0f}%"
    volt_text = "" if volts is None else f", {volts:.2f} V"
    return BatteryOut(**fresh, remaining_pct=pct, voltage_v=volts).say(
        f"{drone_id} battery {pct_text}{volt_text}{note}"
    )


_value_reader(
    "get_flight_mode",
    "flight_mode",
    "flight mode",
    "Current flight mode name (e.g. GUIDED, AUTO, RTL, LAND).",
)

_data_reader("get_health", "health", "Sensor/arming health flags.")


@toolset.tool(read_only=True)
async def get_health_all_ok(call: ToolCall, drone_id: DroneId) -> ValueOut:
    """true when every health check passes and the drone is armable."""
    h, fresh, note = read(call, drone_id, "health", lambda t: t.health)
    flags = plain(h)
    if isinstance(flags, dict):
        failing = sorted(k for k, x in flags.items() if x is False)
        ok = not failing
    else:
        failing, ok = [], bool(flags)
    why = f" (failing: {', '.join(failing)})" if failing else ""
    return ValueOut(**fresh, value=ok).say(f"{drone_id} health {'all ok' if ok else 'NOT ok'}{why}{note}")


@toolset.tool(read_only=True)
async def get_speed(call: ToolCall, drone_id: DroneId) -> SpeedOut:
    """Velocity m/s north/east, climb (negative: descending) and ground speed."""
    vel, fresh, note = read(call, drone_id, "velocity_ned", lambda t: t.velocity_ned)
    n, e, d = float(vel.north_mps), float(vel.east_mps), float(vel.down_mps)
    gs = math.hypot(n, e)
    return SpeedOut(
        **fresh,
        north_mps=round(n, 2),
        east_mps=round(e, 2),
        climb_mps=round(-d, 2) + 0.0,  # never -0.0
        ground_speed_mps=round(gs, 2),
    ).say(f"{drone_id} ground speed {gs:.1f} m/s, climb {-d:.1f} m/s{note}")


@toolset.tool(read_only=True)
async def get_attitude(call: ToolCall, drone_id: DroneId) -> AttitudeOut:
    """Roll, pitch, yaw in degrees."""
    a, fresh, note = read(call, drone_id, "attitude", lambda t: t.attitude)
    r, p, y = float(a.roll_deg), float(a.pitch_deg), float(a.yaw_deg)
    return AttitudeOut(
        **fresh,
        roll_deg=round(r, 1),
        pitch_deg=round(p, 1),
        yaw_deg=round(y, 1),
    ).say(f"{drone_id} roll {r:.1f}, pitch {p:.1f}, yaw {y:.1f} deg{note}")


@toolset.tool(read_only=True)
async def get_gps_info(call: ToolCall, drone_id: DroneId) -> GpsOut:
    """GPS satellites and fix type."""
    g, fresh, note = read(call, drone_id, "gps_info", lambda t: t.gps_info)
    fix = plain(g.fix_type)
    return GpsOut(**fresh, num_satellites=int(g.num_satellites), fix_type=str(fix)).say(
        f"{drone_id} GPS {fix}, {g.num_satellites} satellites{note}"
    )


_value_reader("get_in_air", "in_air", "in air", "true when flying.")

_value_reader("get_armed", "armed", "armed", "true when the motors are armed.")

_value_reader(
    "get_landed_state", "landed_state", "landed state", "ON_GROUND, TAKING_OFF, IN_AIR, LANDING or UNKNOWN."
)

_data_reader("get_rc_status", "rc_status", "RC link: available, signal strength %.")

_value_reader("get_heading", "heading_deg", "heading deg", "Compass heading, degrees from north.")

_data_reader("get_imu", "imu", "IMU: acceleration m/s², angular rate rad/s, temperature °C.")

_data_reader("get_odometry", "odometry", "Odometry: body-frame position m, velocity m/s, orientation.")


@toolset.tool(read_only=True)
async def print_status_text(
    call: ToolCall,
    drone_id: DroneId,
    limit: Annotated[int, Field(ge=1, le=100, description="Newest N")] = 20,
) -> StatusTextOut:
    """Recent autopilot status messages, oldest first."""
    v = call.commander.vehicle(drone_id)
    texts = list(getattr(v.telemetry, "status_texts", None) or [])[-limit:]
    messages = [_status_text(t) for t in texts]
    lines = "; ".join(f"[{m['severity']}] {json.dumps(m['text'])}" for m in messages) or "none"
    return StatusTextOut(drone_id=drone_id, messages=messages).say(
        f"{drone_id} status texts ({VEHICLE_TEXT_LABEL}): {lines}"
    )


def _status_text(item: object) -> dict[str, JsonValue]:
    if isinstance(item, tuple | list) and len(item) == 3:
        t, severity, text = item
    else:
        t = getattr(item, "t", None)
        severity, text = getattr(item, "severity", ""), getattr(item, "text", str(item))
    return {
        "t": plain(t) if not hasattr(t, "isoformat") else t.isoformat(),
        "severity": str(plain(severity)),
        "text": clean_vehicle_text(str(text)),
    }


@toolset.tool(read_only=True)
async def get_telemetry(call: ToolCall, drone_id: DroneId) -> SnapshotOut:
    """Everything at once: all telemetry with each part's age_s, plus the current action."""
    v = call.commander.vehicle(drone_id)
    snap = surface_telemetry(plain_object(v.telemetry.snapshot()))
    op = call.commander.current_operation(drone_id)  # on a cluster node also a drone owned elsewhere
    state = str(plain(v.state))
    pos = snap.get("position") if isinstance(snap, dict) else None
    where = ""
    if isinstance(pos, dict):
        inner = pos.get("value", pos)
        if isinstance(inner, dict) and inner.get("alt_m") is not None:
            where = f", {inner['alt_m']:.1f} m above home"
    doing = f", {op['kind']} {op['status']}" if op is not None else ""
    return SnapshotOut(drone_id=drone_id, state=state, telemetry=snap, operation=op).say(
        f"{drone_id} {state}{where}{doing}"
    )
