"""Autopilot dialects, found through a registry keyed by the autopilot a HEARTBEAT names (MAV_AUTOPILOT).

``register(MAV_AUTOPILOT_..., dialect)`` adds one (ArduPilot's and PX4's are registered here). Two
look-ups: ``dialect_for`` gives what is read through a dialect (link facts, modes, landed state) for
any autopilot, and ``flying_dialect`` the dialect commands are sent through, or `NoDialect` saying in
one line which autopilot it is and what the operator can do. Before the first HEARTBEAT (autopilot not
known yet) both give ArduPilot's, whose MAVLink is the most common; nothing is flown before a HEARTBEAT
anyway, except an operator's recovery commands. An autopilot with no dialect registered is read through
``Unsupported`` and never flown as another autopilot.
"""

from __future__ import annotations

from gateway.errors import NoDialect
from gateway.fleet.dialects.ardupilot import ArduPilot
from gateway.fleet.dialects.base import Dialect, DialectReads, LinkOps
from gateway.fleet.dialects.px4 import PX4
from gateway.fleet.dialects.unsupported import Unsupported, autopilot_label
from gateway.fleet.policy.param_limits import ParamLimit
from gateway.link.rawlink import MAV_AUTOPILOT_ARDUPILOTMEGA, MAV_AUTOPILOT_PX4, autopilot_name

__all__ = [
    "ARDUPILOT", "PX4_DIALECT", "Dialect", "DialectReads", "LinkOps", "autopilot_number", "dialect_for",
    "dialect_named",
    "dialects", "flying_dialect", "limit_params", "protected_params", "register",
]  # fmt: skip

ARDUPILOT: Dialect = ArduPilot()
PX4_DIALECT: Dialect = PX4()

MAV_AUTOPILOT_GENERIC = 0

_REGISTRY: dict[int, Dialect] = {}
_UNSUPPORTED: dict[int, Unsupported] = {}


def register(mav_autopilot: int, dialect: Dialect) -> None:
    """Fly the autopilot a HEARTBEAT names ``mav_autopilot`` with ``dialect`` (replacing any before)."""
    _REGISTRY[mav_autopilot] = dialect


register(MAV_AUTOPILOT_ARDUPILOTMEGA, ARDUPILOT)
register(MAV_AUTOPILOT_PX4, PX4_DIALECT)


def dialects() -> tuple[Dialect, ...]:
    """Every registered dialect, once each."""
    return tuple(dict.fromkeys(_REGISTRY.values()))


def dialect_for(mav_autopilot: int | None) -> DialectReads:
    """What is read through the dialect of a HEARTBEAT's MAV_AUTOPILOT (None: not known yet, read as
    ArduPilot); an autopilot no dialect is registered for is read through ``Unsupported``."""
    if mav_autopilot is None:
        return ARDUPILOT
    dialect = _REGISTRY.get(mav_autopilot)
    if dialect is not None:
        return dialect
    return _UNSUPPORTED.setdefault(mav_autopilot, Unsupported(mav_autopilot))


def flying_dialect(mav_autopilot: int | None, vehicle_id: str) -> Dialect:
    """The dialect commands to drone ``vehicle_id`` are sent through; NoDialect (nothing is sent) when
    its autopilot has none registered."""
    if mav_autopilot is None:
        return ARDUPILOT
    dialect = _REGISTRY.get(mav_autopilot)
    if dialect is None:
        raise NoDialect(
            f"drone '{vehicle_id}' runs autopilot {autopilot_label(mav_autopilot)}, which this gateway has "
            "no dialect for, so it sends it no command (its telemetry and status are still shown): fly "
            "it from its own ground station, or connect a drone running ArduPilot or PX4",
            vehicle_id=vehicle_id,
            autopilot=autopilot_name(mav_autopilot),
        )
    return dialect


def autopilot_number(autopilot: str | None) -> int | None:
    """The MAV_AUTOPILOT of an autopilot as the gateway reports it (`autopilot_name`: "ardupilot",
    "px4", "mav_autopilot_<n>"; None: not known yet), for a vehicle seen through another node's status."""
    if autopilot is None:
        return None
    number = next((n for n in _REGISTRY if autopilot_name(n) == autopilot), None)
    if number is None:
        tail = autopilot.removeprefix("mav_autopilot_")
        number = int(tail) if tail.isdigit() else MAV_AUTOPILOT_GENERIC
    return number


def dialect_named(autopilot: str | None) -> DialectReads:
    """`dialect_for` the autopilot as the gateway reports it (`autopilot_number`)."""
    return dialect_for(autopilot_number(autopilot))


def protected_params() -> tuple[str, ...]:
    """Every dialect's protected parameter patterns (for a vehicle whose autopilot is not known yet)."""
    return tuple(dict.fromkeys(p for d in dialects() for p in d.protected_params))


def limit_params() -> dict[str, ParamLimit]:
    """Every dialect's limit-governing parameters (for a vehicle whose autopilot is not known yet)."""
    return {name: rule for d in dialects() for name, rule in d.limit_params.items()}
