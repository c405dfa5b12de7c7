"""Mission files of the ground stations, in and out: QGroundControl's ``.plan`` (JSON) and the plain-text
``QGC WPL 110`` that Mission Planner, MAVProxy and ArduPilot's own autotests use.

A file's items travel to the autopilot exactly as written (frame, command, the seven parameters); what
the gateway adds is the policy's reading of them, with the autopilot's own semantics:

* the home slot: a WPL file's line 0 and a ``.plan``'s ``plannedHomePosition`` are home, not flown; user
  item k is the file's item k (WPL seq k; the k-th item of a ``.plan``), which is what refusals name;
* ArduPilot reads latitude and longitude 0 of a position item as "where the vehicle is" and altitude 0
  as "the altitude of the previous item": the policy checks the position and altitude so resolved;
* frames: global (AMSL) altitudes are taken above home with the vehicle's home altitude; relative ones
  as they are; terrain ones are read as if above home here, and the policy treats them as unchecked
  (the gateway knows no terrain);
* what each command does is judged by the policy with the autopilot's semantics
  (`gateway.fleet.policy.mission_check`, the dialect's table in
  `gateway.fleet.dialects.mission_semantics`): positions, loiter radii, speed changes by speed type,
  jumps, harmless yaw/ROI/camera items; any other item is unchecked (refused for agents); a few that
  would undo the safety layer from inside a mission (DO_SET_PARAMETER, DO_FENCE_ENABLE,
  DO_FLIGHTTERMINATION, DO_SET_HOME, DO_MOTOR_TEST) are refused for everyone.

Complex ``.plan`` items (surveys, corridor scans, structure scans) carry no MAVLink items of their own in
every version; they are refused by name: export them from QGroundControl as a WPL file (File > Save As
waypoints) or convert them there to simple items.
"""

from __future__ import annotations

import json
import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Literal

from gateway.errors import InvalidArgument
from gateway.fleet.missions.mission import (
    MAV_FRAME_GLOBAL,
    MAX_ITEMS,
    Kind,
    MissionItem,
    RawItem,
)
from gateway.util.json_types import JsonMapping, JsonObject, JsonValue

FileFormat = Literal["plan", "waypoints"]
FORMATS: tuple[FileFormat, ...] = ("plan", "waypoints")
WPL_HEADER = "QGC WPL 110"

GLOBAL_FRAMES = {0, 5}  # GLOBAL, GLOBAL_INT: altitude above mean sea level
RELATIVE_FRAMES = {3, 6}  # GLOBAL_RELATIVE_ALT(_INT): above home
TERRAIN_FRAMES = {10, 11}  # GLOBAL_TERRAIN_ALT(_INT): above terrain
POSITION_FRAMES = GLOBAL_FRAMES | RELATIVE_FRAMES | TERRAIN_FRAMES

# NAV commands that fly to (or over) a position: checked as the gateway's own kinds
_KIND_OF: dict[int, Kind] = {
    16: "waypoint", 17: "waypoint", 18: "waypoint", 19: "loiter_time", 21: "land", 22: "takeoff",
    31: "waypoint", 82: "waypoint",
}  # fmt: skip
MAV_CMD_NAV_RETURN_TO_LAUNCH = 20
MAV_CMD_DO_CHANGE_SPEED = 178
AUTOPILOT_FIRMWARE = {"ardupilot": 3, "px4": 12}  # MAV_AUTOPILOT, a .plan's firmwareType


@dataclass(frozen=True)
class FileMission:
    """The items of a mission file (home excluded) and the home it names, if any."""

    items: list[RawItem]
    home: tuple[float, float, float] | None = None


def _number(value: object, where: str) -> float:
    if value is None:
        return math.nan  # QGC writes NaN parameters as null
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise InvalidArgument(f"{where}: expected a number, got {value!r}")
    return float(value)


def _raw(frame: int, command: int, params: Sequence[float], autocontinue: bool, where: str) -> RawItem:
    if not 0 <= command <= 65535:
        raise InvalidArgument(f"{where}: command {command} is not a MAV_CMD (0..65535)")
    if not 0 <= frame <= 255:
        raise InvalidArgument(f"{where}: frame {frame} is not a MAV_FRAME (0..255)")
    p = [float(v) for v in params]
    if frame in POSITION_FRAMES:
        lat, lon = p[4], p[5]
        if not (math.isfinite(lat) and math.isfinite(lon) and -90 <= lat <= 90 and -180 <= lon <= 180):
            raise InvalidArgument(f"{where}: latitude/longitude {lat}, {lon} out of range")
    return RawItem(command, frame, p[0], p[1], p[2], p[3], p[4], p[5], p[6], autocontinue)


def parse_plan(text: str) -> FileMission:
    """A QGroundControl ``.plan`` (JSON, plan version 1, mission version 2)."""
    try:
        doc = json.loads(text)
    except json.JSONDecodeError as exc:
        raise InvalidArgument(f"the .plan file is not valid JSON: {exc}") from None
    except RecursionError:
        raise InvalidArgument("the .plan file nests its JSON too deeply to be a mission") from None
    if not isinstance(doc, dict) or doc.get("fileType") != "Plan":
        raise InvalidArgument('the .plan file must be a JSON object with "fileType": "Plan"')
    mission = doc.get("mission")
    if not isinstance(mission, dict) or not isinstance(mission.get("items"), list):
        raise InvalidArgument('the .plan file has no "mission" with an "items" list')
    items = [_plan_item(entry, f"mission item {k}") for k, entry in enumerate(mission["items"], start=1)]
    _refuse_fence_and_rally(doc)
    home_raw = mission.get("plannedHomePosition")
    home = None
    if (
        isinstance(home_raw, list)
        and len(home_raw) == 3
        and all(isinstance(v, int | float) for v in home_raw)
    ):
        home = (float(home_raw[0]), float(home_raw[1]), float(home_raw[2]))
    return FileMission(_checked_count(items), home)


def _plan_item(entry: object, where: str) -> RawItem:
    """One SimpleItem of a .plan's mission."""
    if not isinstance(entry, dict):
        raise InvalidArgument(f"{where}: expected an object, got {entry!r}")
    kind = entry.get("type")
    if kind == "ComplexItem":
        raise InvalidArgument(
            f"{where} is a {entry.get('complexItemType', 'complex')} item, which the gateway does not "
            "expand: save the mission from QGroundControl as waypoints (WPL) and upload that"
        )
    if kind != "SimpleItem":
        raise InvalidArgument(f"{where}: type {kind!r} is neither SimpleItem nor ComplexItem")
    params = entry.get("params")
    if not isinstance(params, list) or len(params) != 7:
        raise InvalidArgument(f"{where}: params must be a list of 7 numbers (null for none)")
    command, frame = entry.get("command"), entry.get("frame")
    for name, number in (("command", command), ("frame", frame)):
        if isinstance(number, bool) or not isinstance(number, int):
            raise InvalidArgument(f"{where}: {name} must be an integer; got {json.dumps(number)[:40]}")
    assert isinstance(frame, int) and isinstance(command, int)
    values = [_number(v, f"{where} param{i + 1}") for i, v in enumerate(params)]
    return _raw(frame, command, values, bool(entry.get("autoContinue", True)), where)


def _refuse_fence_and_rally(doc: JsonMapping) -> None:
    """The items are all this parser reads: a .plan that still has a geofence or rally points is refused
    naming them, never stored without them (which would leave a drone without the fence its planner
    drew). The REST upload takes them out first (`gateway.fleet.missions.plan_extras.split_plan`): the
    geofence becomes the drone's zones, the rally points are kept."""
    fence = doc.get("geoFence")
    if isinstance(fence, dict):
        polygons, circles = _entries(fence.get("polygons")), _entries(fence.get("circles"))
        if polygons or circles:
            raise InvalidArgument(
                f"the .plan file has a geofence ({polygons} polygons, {circles} circles), which "
                "this upload does not apply; nothing was sent: upload the plan with PUT "
                "/api/v1/vehicles/{id}/mission, which makes it the drone's geofences"
            )
    rally = doc.get("rallyPoints")
    points = _entries(rally.get("points")) if isinstance(rally, dict) else 0
    if points:
        raise InvalidArgument(
            f"the .plan file has {points} rally points, which this upload does not keep; nothing was "
            "sent: upload the plan with PUT /api/v1/vehicles/{id}/mission, which keeps them"
        )


def _entries(value: JsonValue) -> int:
    """How many entries a .plan's list has (a value that is no list: 1 when it is there at all)."""
    return len(value) if isinstance(value, list | dict) else int(bool(value))


def parse_wpl(text: str) -> FileMission:
    """A ``QGC WPL 110`` file: tab (or space) separated, line 0 home."""
    lines = [line for line in text.replace("\r\n", "\n").split("\n") if line.strip()]
    if not lines or not lines[0].strip().startswith("QGC WPL"):
        raise InvalidArgument(
            f"a waypoint file begins with '{WPL_HEADER}'; got {lines[0][:40]!r}"
            if lines
            else "the waypoint file is empty"
        )
    if lines[0].split()[-1] != "110":
        raise InvalidArgument(
            f"waypoint file version {lines[0].split()[-1]!r} is not supported; use {WPL_HEADER}"
        )
    home = None
    items: list[RawItem] = []
    for line_no, line in enumerate(lines[1:], start=2):
        cols = line.split()
        if len(cols) != 12:
            raise InvalidArgument(f"line {line_no}: expected 12 columns, got {len(cols)}")
        try:
            seq, _current, frame, command = (int(c) for c in cols[:4])
            params = [float(c) for c in cols[4:11]]
            autocontinue = bool(int(cols[11]))
        except ValueError:
            raise InvalidArgument(f"line {line_no}: not a waypoint line: {line[:80]!r}") from None
        if seq == 0 and home is None and not items:
            home = (params[4], params[5], params[6])
            continue
        if seq != len(items) + 1:
            raise InvalidArgument(f"line {line_no}: sequence number {seq}, expected {len(items) + 1}")
        items.append(_raw(frame, command, params, autocontinue, f"mission item {seq}"))
    return FileMission(_checked_count(items), home)


def _checked_count(items: list[RawItem]) -> list[RawItem]:
    if not items:
        raise InvalidArgument("the mission file has no items (besides home)")
    if len(items) > MAX_ITEMS:
        raise InvalidArgument(f"a mission holds at most {MAX_ITEMS} items; the file has {len(items)}")
    return items


def parse(text: str, fmt: FileFormat | None = None) -> FileMission:
    """Either format; without ``fmt`` it is told from the text (JSON object: .plan, else WPL)."""
    if fmt is None:
        fmt = "plan" if text.lstrip().startswith("{") else "waypoints"
    if fmt not in FORMATS:
        raise InvalidArgument(f"format {fmt!r} is not one of {', '.join(FORMATS)}")
    return parse_plan(text) if fmt == "plan" else parse_wpl(text)


def mission_items(
    mission: FileMission,
    home: tuple[float, float, float] | None,
    position: tuple[float, float, float] | None,
    *,
    zero_is_here: bool = True,
) -> list[MissionItem]:
    """The file's items as the gateway's mission items: each carries the file's item unchanged (sent as
    is), and the position, altitude above home and kind the policy checks, read as ArduPilot reads them
    (``zero_is_here`` False: latitude/longitude 0 are taken as written, as PX4 does).

    ``home`` is the vehicle's (lat, lon, alt AMSL) and ``position`` its (lat, lon, alt above home), for
    items at 0, 0 or altitude 0 and for global frames; unknown ones leave such items unresolvable.
    """
    out: list[MissionItem] = []
    last = position
    for k, raw in enumerate(mission.items, start=1):
        kind = _KIND_OF.get(raw.command)
        if raw.command == MAV_CMD_NAV_RETURN_TO_LAUNCH:
            item = MissionItem(kind="rtl")
            last = (home[0], home[1], 0.0) if home else None
        elif kind is not None and raw.frame in POSITION_FRAMES:
            lat, lon = (
                (raw.x, raw.y)
                if (raw.x, raw.y) != (0.0, 0.0) or not zero_is_here
                else ((last[0], last[1]) if last else (0.0, 0.0))
            )
            if raw.frame in GLOBAL_FRAMES and raw.z != 0.0:
                if home is None:
                    raise InvalidArgument(
                        f"mission item {k}: its altitude is above mean sea level (frame {raw.frame}) and the "
                        "vehicle's home altitude is not known yet"
                    )
                alt = raw.z - home[2]
            elif raw.z == 0.0 and kind not in ("takeoff", "land"):
                alt = last[2] if last else 0.0
            else:
                alt = raw.z
            if kind in ("waypoint", "loiter_time") and (lat, lon) == (0.0, 0.0) and zero_is_here:
                raise InvalidArgument(
                    f"mission item {k}: at latitude/longitude 0 it flies where the vehicle is, which is not "
                    "known yet (no position)"
                )
            item = MissionItem.model_construct(
                lat=lat, lon=lon, alt_rel_m=alt, kind=kind, hold_s=0.0, speed_mps=None, command=None
            )
            if kind != "land":
                last = (lat, lon, alt)
        else:
            speed = raw.param2 if raw.command == MAV_CMD_DO_CHANGE_SPEED and raw.param2 > 0 else None
            item = MissionItem.model_construct(
                lat=0.0,
                lon=0.0,
                alt_rel_m=0.0,
                kind="other",
                hold_s=0.0,
                speed_mps=speed,
                command=raw.command,
            )
        item.attach_raw(raw)
        out.append(item)
    return out


def held_items(
    items: Sequence[MissionItem],
    home: tuple[float, float, float] | None,
    position: tuple[float, float, float] | None,
    *,
    zero_is_here: bool = True,
) -> list[MissionItem]:
    """The mission an autopilot holds (downloaded, each item carrying its MAVLink items) as the policy
    reads it: every MAVLink item one user item, numbered as the autopilot numbers them (ArduPilot: its
    sequence number), positions and altitudes resolved as `mission_items` does. Items without MAVLink
    items (a simulator's, a test's) are returned as they are."""
    if not items or not all(item.raw_items for item in items):
        return list(items)
    return mission_items(FileMission(raw_items(items)), home, position, zero_is_here=zero_is_here)


def raw_items(items: Sequence[MissionItem]) -> list[RawItem]:
    """The MAVLink items of downloaded mission items (each carries the ones it was decoded from)."""
    out: list[RawItem] = []
    for k, item in enumerate(items, start=1):
        if not item.raw_items:
            raise InvalidArgument(f"mission item {k} has no MAVLink item to export")
        out.extend(item.raw_items)
    return out


def _json_number(value: float) -> float | int | None:
    if not math.isfinite(value):
        return None
    return int(value) if value == int(value) and abs(value) < 2**53 else value


def write_plan(
    items: Sequence[RawItem], home: tuple[float, float, float] | None, autopilot: str | None = None
) -> str:
    """A QGroundControl ``.plan`` holding ``items`` as simple items."""
    simple: list[JsonValue] = []
    for k, raw in enumerate(items, start=1):
        params = [raw.param1, raw.param2, raw.param3, raw.param4, raw.x, raw.y, raw.z]
        entry: JsonObject = {
            "autoContinue": raw.autocontinue,
            "command": raw.command,
            "doJumpId": k,
            "frame": raw.frame,
            "params": [_json_number(v) for v in params],
            "type": "SimpleItem",
        }
        if raw.frame in POSITION_FRAMES:
            entry["Altitude"] = _json_number(raw.z)
            entry["AltitudeMode"] = (
                0 if raw.frame in GLOBAL_FRAMES else (3 if raw.frame in TERRAIN_FRAMES else 1)
            )
            entry["AMSLAltAboveTerrain"] = None
        simple.append(entry)
    doc = {
        "fileType": "Plan",
        "geoFence": {"circles": [], "polygons": [], "version": 2},
        "groundStation": "fleet-gateway",
        "mission": {
            "cruiseSpeed": 15,
            "firmwareType": AUTOPILOT_FIRMWARE.get(autopilot or "", 0),
            "hoverSpeed": 5,
            "items": simple,
            "plannedHomePosition": list(home) if home else [0, 0, 0],
            "vehicleType": 2,
            "version": 2,
        },
        "rallyPoints": {"points": [], "version": 2},
        "version": 1,
    }
    return json.dumps(doc, indent=2) + "\n"


def _wpl_number(value: float) -> str:
    return f"{value:.8f}" if math.isfinite(value) else "nan"


def write_wpl(items: Sequence[RawItem], home: tuple[float, float, float] | None) -> str:
    """A ``QGC WPL 110`` file: line 0 home (a waypoint at home, global frame), then the items."""
    hlat, hlon, halt = home if home else (0.0, 0.0, 0.0)
    lines = [WPL_HEADER]
    rows = [(0, 1, MAV_FRAME_GLOBAL, 16, 0.0, 0.0, 0.0, 0.0, hlat, hlon, halt, True)]
    rows += [
        (k, 0, r.frame, r.command, r.param1, r.param2, r.param3, r.param4, r.x, r.y, r.z, r.autocontinue)
        for k, r in enumerate(items, start=1)
    ]
    for seq, current, frame, command, *values, auto in rows:
        numbers = "\t".join(_wpl_number(float(v)) for v in values)
        lines.append(f"{seq}\t{current}\t{frame}\t{command}\t{numbers}\t{int(bool(auto))}")
    return "\n".join(lines) + "\n"


def write(
    fmt: FileFormat, items: Sequence[RawItem], home: tuple[float, float, float] | None, autopilot: str | None
) -> str:
    if fmt == "plan":
        return write_plan(items, home, autopilot)
    if fmt == "waypoints":
        return write_wpl(items, home)
    raise InvalidArgument(f"format {fmt!r} is not one of {', '.join(FORMATS)}")
