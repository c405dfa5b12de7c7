"""One MAVLink mission item as MISSION_ITEM_INT carries it: the gateway's wire encoding
(`gateway.fleet.missions.mission`) and the simulator's mission storage (`gateway.sim.mission`) hold the
same numbers."""

from __future__ import annotations

from dataclasses import dataclass

#: MAV_FRAME_GLOBAL_RELATIVE_ALT (pymavlink's name): a number here so that a start loads no MAVLink dialect
FRAME_GLOBAL_RELATIVE_ALT = 3


@dataclass(frozen=True)
class ItemInt:
    """x/y in degE7 (plain numbers in MAV_FRAME_MISSION), z in metres."""

    command: int
    frame: int = FRAME_GLOBAL_RELATIVE_ALT
    param1: float = 0.0
    param2: float = 0.0
    param3: float = 0.0
    param4: float = 0.0
    x: int = 0
    y: int = 0
    z: float = 0.0
    autocontinue: int = 1
