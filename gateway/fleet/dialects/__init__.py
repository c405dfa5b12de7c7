"""Autopilot dialects: what differs between ArduPilot and PX4, behind one Protocol (``base.Dialect``).

``dialect_for(mav_autopilot)`` picks the dialect from the HEARTBEAT's autopilot; until one came (and for
autopilots without a dialect of their own) the ArduPilot dialect, whose MAVLink is the most common.
"""

from __future__ import annotations

from gateway.fleet.dialects.ardupilot import ArduPilot
from gateway.fleet.dialects.base import Dialect, LinkOps
from gateway.fleet.dialects.px4 import PX4
from gateway.fleet.param_limits import ParamLimit
from gateway.link.rawlink import MAV_AUTOPILOT_PX4

__all__ = [
    "ARDUPILOT", "DIALECTS", "PX4_DIALECT", "Dialect", "LinkOps", "dialect_for", "dialect_named",
    "limit_params", "protected_params",
]  # fmt: skip

ARDUPILOT: Dialect = ArduPilot()
PX4_DIALECT: Dialect = PX4()
DIALECTS: tuple[Dialect, ...] = (ARDUPILOT, PX4_DIALECT)


def dialect_for(mav_autopilot: int | None) -> Dialect:
    """The dialect of a HEARTBEAT's MAV_AUTOPILOT (None: not known yet)."""
    return PX4_DIALECT if mav_autopilot == MAV_AUTOPILOT_PX4 else ARDUPILOT


def dialect_named(autopilot: str | None) -> Dialect:
    """The dialect of an autopilot as the gateway reports it ("px4", "ardupilot"; None: not known yet),
    for a vehicle seen through another node's status."""
    return PX4_DIALECT if autopilot == "px4" else ARDUPILOT


def protected_params() -> tuple[str, ...]:
    """Every dialect's protected parameter patterns (for a vehicle whose autopilot is not known yet)."""
    return tuple(dict.fromkeys(p for d in DIALECTS for p in d.protected_params))


def limit_params() -> dict[str, ParamLimit]:
    """Every dialect's limit-governing parameters (for a vehicle whose autopilot is not known yet)."""
    return {name: rule for d in DIALECTS for name, rule in d.limit_params.items()}
