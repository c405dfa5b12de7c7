"""User mission items and their MAVLink (mission_raw) encoding, per autopilot.

ArduPilot keeps HOME at sequence 0 and overwrites whatever is uploaded there, so its wire mission is
``[home placeholder, item 1, ..., item N]`` and user item k is wire item k, as long as no item needs a
companion command. PX4 has no home slot: it flies seq 0 like any other item (a placeholder there sends
the drone back to home at ground level), so its wire mission is ``[item 1, ..., item N]`` (``home_slot``
False). An item with ``speed_mps`` is preceded by a DO_CHANGE_SPEED wire item; the
``WirePlan`` keeps the wire-to-user mapping so progress and ``set_current`` stay in user numbers.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Literal, Protocol

from pydantic import BaseModel, ConfigDict, Field, PrivateAttr, model_validator

from gateway.errors import InvalidArgument
from gateway.fleet.geo import check_lat_lon
from gateway.fleet.policy.mission_check import RawLike
from gateway.util.mission_item import MAV_FRAME_GLOBAL_RELATIVE_ALT, ItemCommand, ItemInt

# MAVLink ids
MAV_FRAME_GLOBAL = 0
MAV_FRAME_MISSION = 2
MAV_CMD_NAV_WAYPOINT = 16
MAV_CMD_NAV_LOITER_TIME = 19
MAV_CMD_NAV_RETURN_TO_LAUNCH = 20
MAV_CMD_NAV_LAND = 21
MAV_CMD_NAV_TAKEOFF = 22
MAV_CMD_DO_CHANGE_SPEED = 178

Kind = Literal["waypoint", "takeoff", "land", "rtl", "loiter_time", "other"]
_KIND_TO_CMD = {
    "waypoint": MAV_CMD_NAV_WAYPOINT,
    "takeoff": MAV_CMD_NAV_TAKEOFF,
    "land": MAV_CMD_NAV_LAND,
    "rtl": MAV_CMD_NAV_RETURN_TO_LAUNCH,
    "loiter_time": MAV_CMD_NAV_LOITER_TIME,
}
_CMD_TO_KIND = {v: k for k, v in _KIND_TO_CMD.items()}
MAX_ITEMS = 700


@dataclass(frozen=True)
class RawItem(ItemCommand):
    """One MAVLink mission item as a mission file or the autopilot holds it (x, y in degrees, except in
    MAV_FRAME_MISSION where they are plain numbers)."""

    x: float = 0.0
    y: float = 0.0
    z: float = 0.0
    autocontinue: bool = True


class MissionItem(BaseModel):
    """One user mission item (user numbering starts at 1). Altitudes are metres above home.

    ``land`` at lat=lon=0 lands where the vehicle is; ``rtl`` ignores the position. ``other`` only comes
    back from a download of a mission holding commands this API does not model (``command`` says which).
    """

    model_config = ConfigDict(extra="forbid")

    lat: float = Field(0.0, description="Latitude, degrees.")
    lon: float = Field(0.0, description="Longitude, degrees.")
    alt_rel_m: float = Field(0.0, ge=-100, le=10000, description="Altitude above home, metres.")
    kind: Kind = "waypoint"
    hold_s: float = Field(0.0, ge=0, le=3600, description="Waypoint hold / loiter time, seconds.")
    speed_mps: float | None = Field(None, gt=0, le=50, description="Ground speed from this item on.")
    command: int | None = Field(None, description="MAVLink command id (only for kind 'other').")
    # the MAVLink item exactly as a mission file (or the autopilot) has it: sent as is instead of one
    # built from the fields above, which then only say what the policy checks. Never from JSON input.
    _raw: RawItem | None = PrivateAttr(default=None)
    # downloaded: the DO_CHANGE_SPEED item sent before this one (folded into speed_mps above)
    _lead: tuple[RawItem, ...] = PrivateAttr(default=())

    @property
    def raw(self) -> RawItem | None:
        return self._raw

    @property
    def raw_items(self) -> tuple[RawItem, ...]:
        """The MAVLink items this item stands for, as the autopilot holds them (empty: built here)."""
        return (*self._lead, self._raw) if self._raw is not None else ()

    def attach_raw(self, raw: RawItem, lead: tuple[RawItem, ...] = ()) -> MissionItem:
        self._raw = raw
        self._lead = lead
        return self

    @model_validator(mode="after")
    def _check(self) -> MissionItem:
        for name in ("lat", "lon", "alt_rel_m", "hold_s"):
            if not math.isfinite(getattr(self, name)):
                raise ValueError(f"{name} must be a finite number")
        try:
            if self.kind in ("waypoint", "loiter_time") or (self.kind == "land" and (self.lat or self.lon)):
                check_lat_lon(self.lat, self.lon)
        except InvalidArgument as exc:  # pydantic reports ValueErrors as ValidationError
            raise ValueError(exc.message) from None
        if self.kind in ("waypoint", "loiter_time") and self.lat == 0 and self.lon == 0:
            raise ValueError(f"a {self.kind} item needs a position (lat/lon both 0 given)")
        if self.kind == "takeoff" and self.alt_rel_m <= 0:
            raise ValueError("a takeoff item needs alt_rel_m > 0")
        if self.kind == "other" and self.command is None:
            raise ValueError("kind 'other' needs the MAVLink command id")
        return self


@dataclass(frozen=True)
class WireItem(ItemInt):
    """One item of the mission as sent to the autopilot, at wire sequence ``seq``."""

    seq: int = field(kw_only=True)


class DownloadedItem(RawLike, Protocol):
    """A mission item as MAVSDK's mission_raw downloads it (its ``MissionItem``; x and y scaled by 1e7 in
    the global frames): the fields the checks read, and these."""

    @property
    def seq(self) -> int: ...
    @property
    def param4(self) -> float: ...
    @property
    def x(self) -> int: ...
    @property
    def y(self) -> int: ...
    @property
    def z(self) -> float: ...


@dataclass
class WirePlan:
    items: list[WireItem]
    user_to_wire: list[int]  # user index k (1-based) -> wire seq at user_to_wire[k-1]

    def user_index(self, wire_seq: int) -> int:
        """The user item a wire seq belongs to (a DO_CHANGE_SPEED counts for the item after it)."""
        for k, seq in enumerate(self.user_to_wire, start=1):
            if wire_seq <= seq:
                return k
        return len(self.user_to_wire)

    def wire_seq(self, user_index: int) -> int:
        return self.user_to_wire[user_index - 1]


def _deg7(value: float) -> int:
    return round(value * 1e7)


def encode(
    items: list[MissionItem], home: tuple[float, float, float] | None, *, home_slot: bool = True
) -> WirePlan:
    """Wire items 0..M for ``items``. With ``home_slot`` (ArduPilot), seq 0 is the home placeholder
    the autopilot replaces; without it (PX4), seq 0 is the first user item."""
    wire: list[WireItem] = []
    if home_slot:
        hlat, hlon, halt = home if home is not None else (0.0, 0.0, 0.0)
        wire.append(
            WireItem(MAV_CMD_NAV_WAYPOINT, MAV_FRAME_GLOBAL, x=_deg7(hlat), y=_deg7(hlon), z=halt, seq=0)
        )
    user_to_wire: list[int] = []
    for item in items:
        if item.raw is not None:
            user_to_wire.append(len(wire))
            wire.append(_wire_of(len(wire), item.raw))
            continue
        if item.speed_mps is not None:
            wire.append(
                WireItem(MAV_CMD_DO_CHANGE_SPEED, MAV_FRAME_MISSION, 1.0, item.speed_mps, -1.0, seq=len(wire))
            )
        seq = len(wire)
        cmd = item.command if item.kind == "other" else _KIND_TO_CMD[item.kind]
        assert cmd is not None
        wire.append(
            WireItem(
                cmd,
                MAV_FRAME_GLOBAL_RELATIVE_ALT,
                param1=item.hold_s if item.kind in ("waypoint", "loiter_time") else 0.0,
                x=_deg7(item.lat),
                y=_deg7(item.lon),
                z=item.alt_rel_m,
                seq=seq,
            )
        )
        user_to_wire.append(seq)
    return WirePlan(wire, user_to_wire)


def _scaled(frame: int) -> bool:
    return frame != MAV_FRAME_MISSION


def _wire_of(seq: int, raw: RawItem) -> WireItem:
    x, y = (_deg7(raw.x), _deg7(raw.y)) if _scaled(raw.frame) else (round(raw.x), round(raw.y))
    return WireItem(
        raw.command, raw.frame, raw.param1, raw.param2, raw.param3, raw.param4, x, y, raw.z, seq=seq
    )


def _raw_of(w: WireItem, autocontinue: bool) -> RawItem:
    x, y = (w.x / 1e7, w.y / 1e7) if _scaled(w.frame) else (float(w.x), float(w.y))
    return RawItem(w.command, w.frame, w.param1, w.param2, w.param3, w.param4, x, y, w.z, autocontinue)


def decode(wire: Sequence[DownloadedItem], *, home_slot: bool = True) -> tuple[list[MissionItem], WirePlan]:
    """User items from a downloaded mission_raw list (with ``home_slot``, seq 0, home, is dropped)."""
    items: list[MissionItem] = []
    user_to_wire: list[int] = []
    pending_speed: float | None = None
    kept: list[WireItem] = []
    lead: list[RawItem] = []
    for raw in sorted(wire, key=lambda w: w.seq):
        w = WireItem(
            int(raw.command),
            int(raw.frame),
            float(raw.param1),
            float(raw.param2),
            float(raw.param3),
            float(raw.param4),
            int(raw.x),
            int(raw.y),
            float(raw.z),
            seq=int(raw.seq),
        )
        kept.append(w)
        if home_slot and w.seq == 0:
            continue
        if w.command == MAV_CMD_DO_CHANGE_SPEED:
            pending_speed = w.param2 if w.param2 > 0 else None
            lead.append(_raw_of(w, bool(getattr(raw, "autocontinue", 1))))
            continue
        kind = _CMD_TO_KIND.get(w.command, "other")
        # model_construct: a mission written by another planner is reported as it is, not re-validated
        items.append(
            MissionItem.model_construct(
                lat=w.x / 1e7,
                lon=w.y / 1e7,
                alt_rel_m=w.z,
                kind=kind,  # type: ignore[arg-type]
                hold_s=w.param1 if kind in ("waypoint", "loiter_time") else 0.0,
                speed_mps=pending_speed,
                command=w.command if kind == "other" else None,
            )
        )
        items[-1].attach_raw(_raw_of(w, bool(getattr(raw, "autocontinue", 1))), tuple(lead))
        lead.clear()
        user_to_wire.append(w.seq)
        pending_speed = None
    return items, WirePlan(kept, user_to_wire)
