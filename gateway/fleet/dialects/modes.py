"""Flight mode vocabulary shared by every autopilot: the common names a model or operator can say
without knowing the autopilot, and what a resolved mode is. Each dialect (gateway.fleet.dialects) maps
the common names onto its own modes and lists the modes it offers."""

from __future__ import annotations

from collections.abc import Collection, Mapping
from dataclasses import dataclass, field
from typing import Protocol

from gateway.errors import InvalidArgument

#: The common names, each with its synonyms. HOLD / LOITER: hover in place without a pilot; POSITION /
#: GUIDED: hover, waiting for position targets (goto); MISSION / AUTO: fly the uploaded mission.
COMMON_MODES: dict[str, tuple[str, ...]] = {
    "HOLD": ("LOITER",),
    "GUIDED": ("POSITION",),
    "RTL": ("RETURN", "RETURN_TO_LAUNCH"),
    "LAND": (),
    "MISSION": ("AUTO",),
    "TAKEOFF": (),
}
#: synonym -> common name
COMMON_SYNONYMS = {alias: name for name, aliases in COMMON_MODES.items() for alias in aliases}


@dataclass(frozen=True)
class AirUse:
    """Whether an agent may select a mode in the air, and why: what the mode needs (a pilot's throttle
    or sticks, a checked mission, nothing) and what it flies."""

    allowed: bool
    why: str


#: a mode the dialect does not list: the gateway does not know what it flies without a pilot
NOT_MODELLED = AirUse(False, "the gateway does not model what it flies without a pilot")


@dataclass(frozen=True)
class ModeChoice:
    """A requested mode resolved for one autopilot: ``requested`` is the common name when the request
    was one (or a synonym of one), else the autopilot's own; ``native`` is the autopilot's name."""

    requested: str
    native: str
    custom_mode: int  # HEARTBEAT.custom_mode once the vehicle is in it
    params: tuple[float, ...]  # MAV_CMD_DO_SET_MODE params 1..3
    #: whether an agent may select it in the air, and why (the dialect's `AIR_MODES`)
    in_air: AirUse = field(default_factory=lambda: NOT_MODELLED)
    #: a mode that flies a pattern: the parameters that set its radius (name, units per metre; the
    #: first one the vehicle has), and how many radii its far side lies from where it starts
    pattern_radius: tuple[tuple[str, float], ...] = ()
    pattern_reach: float = 0.0

    @property
    def is_hold(self) -> bool:
        """A hover in place: flown as the hold action in the air (never a mode that sinks without RC)."""
        return self.requested == "HOLD"


class ModeTable(Protocol):
    """The part of a dialect that names modes."""

    @property
    def name(self) -> str: ...

    def mode_names(self) -> list[str]: ...

    def resolve_mode(self, name: str) -> ModeChoice | None: ...


def canonical(name: str) -> str:
    """``name`` upper-cased, a synonym replaced by its common name."""
    wanted = name.strip().upper()
    return COMMON_SYNONYMS.get(wanted, wanted)


def native_name(
    name: str, common_to_native: Mapping[str, str], offered_native: Collection[str]
) -> tuple[str, str] | None:
    """``name`` as asked (`canonical`) and the autopilot's own name of that mode: a common mode it has,
    or one of its own it offers; None when it has no such mode."""
    wanted = canonical(name)
    native = common_to_native.get(wanted)
    if native is None:
        if wanted not in offered_native:
            return None
        native = wanted
    return wanted, native


def require_mode(name: object, table: ModeTable, vehicle_id: str) -> ModeChoice:
    """``table.resolve_mode(name)``, or InvalidArgument naming the modes this drone has."""
    if not isinstance(name, str) or not name.strip():
        raise InvalidArgument(f"mode must be a flight mode name; got {name!r}")
    choice = table.resolve_mode(name)
    if choice is None:
        raise InvalidArgument(
            f"mode '{name.strip()[:40]}' is not a mode of drone '{vehicle_id}' ({table.name}); "
            f"its modes: {', '.join(table.mode_names())}"
        )
    return choice
