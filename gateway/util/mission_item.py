"""One MAVLink mission item as MISSION_ITEM_INT carries it: the gateway's wire encoding
(`gateway.fleet.missions.mission`) and the simulator's mission storage (`gateway.sim.mission`) hold the
same numbers; the command part is shared with a mission file's item (degrees instead of degE7)."""

from __future__ import annotations

from dataclasses import dataclass

#: pymavlink's MAV_FRAME_GLOBAL_RELATIVE_ALT, as a number here: its dialect module costs the gateway about
#: 10 MiB and is loaded only when a mission is judged or relayed (tests/test_lean_start.py checks both)
MAV_FRAME_GLOBAL_RELATIVE_ALT = 3


@dataclass(frozen=True)
class ItemCommand:
    """What every form of a mission item carries before its position: the command, its frame and the
    four parameters."""

    command: int
    frame: int = MAV_FRAME_GLOBAL_RELATIVE_ALT
    param1: float = 0.0
    param2: float = 0.0
    param3: float = 0.0
    param4: float = 0.0


@dataclass(frozen=True)
class ItemInt(ItemCommand):
    """x/y in degE7 (plain numbers in MAV_FRAME_MISSION), z in metres."""

    x: int = 0
    y: int = 0
    z: float = 0.0
    autocontinue: int = 1
