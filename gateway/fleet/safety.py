"""Safety policy: pure checks run before anything is sent to a drone (no I/O, no clocks but lock times).

Every check returns quietly when allowed, or raises `SafetyRefusal(rule, message, **numbers)` whose
rule is a `Rule` member and whose message starts with the rule's name and states the numbers involved,
e.g. ``max_altitude: target altitude 150 m exceeds the limit of 120 m above home``. The audit table
records the refusal (rule, message, numbers) from the exception.

Who calls what: the Commander (`gateway.fleet.commander`), for every door, with the caller's ``via``:
- agents (MCP, and a node's own cluster commands) are judged with ``via="mcp"`` (the default): operator
  locks, `simulators_only`, the parameter deny list, pilot modes in the air, the kill restriction and
  the takeoff guard apply;
- operators (REST, the console) with ``via="rest"``: the limits still apply, those others do not.
- Agents only ever reach a `LockView` (read-only); locking and unlocking are operator verbs.
"""

from __future__ import annotations

import math
import re
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import asdict, dataclass, fields, replace
from datetime import UTC, datetime
from enum import StrEnum
from typing import Any, Literal, Protocol

from gateway.config import Settings
from gateway.errors import InvalidArgument, SafetyRefusal
from gateway.fleet import geo, param_limits
from gateway.fleet.geofence import FLEET, GeofenceSet, Violation, load_geofence_file
from gateway.fleet.param_limits import ParamLimit

Via = Literal["mcp", "rest"]


class PlannedPoint(Protocol):
    """A point of a formation leg as the policy judges it (`gateway.fleet.formation.LegPoint`)."""

    @property
    def lat(self) -> float: ...
    @property
    def lon(self) -> float: ...
    @property
    def alt_rel_m(self) -> float: ...


class PlannedSlot(Protocol):
    """One drone's part of a formation plan (`gateway.fleet.formation.SlotAssignment`)."""

    @property
    def drone_id(self) -> str: ...
    @property
    def legs(self) -> Sequence[PlannedPoint]: ...


class PlannedFormation(Protocol):
    """What the policy reads of a formation plan (`gateway.fleet.formation.FormationPlan`), so that the
    policy does not import the planner, which raises the policy's refusals."""

    @property
    def min_separation_m(self) -> float: ...
    @property
    def slots(self) -> Sequence[PlannedSlot]: ...


class Rule(StrEnum):
    """Names of the rules; they appear in refusals, audit rows and docs/safety.md."""

    OPERATOR_LOCK = "operator_lock"
    TAKEN_OVER = "taken_over"
    SIMULATORS_ONLY = "simulators_only"
    INVALID_INPUT = "invalid_input"
    MIN_ALTITUDE = "min_altitude"
    MAX_ALTITUDE = "max_altitude"
    HOME_UNKNOWN = "home_unknown"
    MAX_DISTANCE = "max_distance"
    KEEP_IN = "geofence_keep_in"
    KEEP_OUT = "geofence_keep_out"
    POSITION_UNKNOWN = "position_unknown"
    BATTERY_UNKNOWN = "battery_unknown"
    BATTERY_TAKEOFF = "min_battery_takeoff"
    BATTERY_LEG = "min_battery_leg"
    MAX_SPEED = "max_speed"
    PARAM_DENY = "param_deny"
    PARAM_LIMIT = "param_limit"
    PARAM_NOT_ALLOWED = "param_not_allowed"
    MODE_IN_AIR = "mode_deny_in_air"
    KILL_IN_AIR = "kill_in_air"
    MIN_SEPARATION = "min_separation"
    TAKEOFF_IN_PROGRESS = "takeoff_in_progress"
    DRONE_BUSY = "drone_busy"
    KILL_NOT_CONFIRMED = "kill_not_confirmed"
    MISSION_COMMAND = "mission_command_deny"


#: mission commands that would undo the safety layer from inside a mission: DO_SET_HOME (179),
#: DO_SET_PARAMETER (180), DO_FLIGHTTERMINATION (185), DO_FENCE_ENABLE (207), DO_MOTOR_TEST (209)
DENIED_MISSION_COMMANDS = {179: "DO_SET_HOME", 180: "DO_SET_PARAMETER", 185: "DO_FLIGHTTERMINATION",
                           207: "DO_FENCE_ENABLE", 209: "DO_MOTOR_TEST"}  # fmt: skip
#: NAV commands that fly to a position: a mission item of kind "other" with one is checked as a waypoint
POSITION_NAV_COMMANDS = frozenset({16, 17, 18, 19, 21, 22, 31, 82, 84, 85, 94})


# ------------------------------------------------------------------------------------------------
# inputs and outputs


@dataclass(frozen=True)
class VehicleContext:
    """What the policy needs to know about one vehicle, taken from its telemetry cache.

    ``home`` is (lat, lon, alt_amsl_m); ``position`` is (lat, lon, alt_rel_m, metres above home).
    None means unknown (never received, or stale).
    """

    vehicle_id: str
    is_simulator: bool
    armed: bool
    in_air: bool
    battery_pct: float | None
    home: tuple[float, float, float] | None
    position: tuple[float, float, float] | None

    @property
    def airborne(self) -> bool:
        """In the air as far as the policy is concerned: in_air, or armed and more than 1 m above home
        (a landed-state report can lag behind)."""
        if self.in_air:
            return True
        return bool(self.armed and self.position is not None and self.position[2] > 1.0)


@dataclass(frozen=True)
class Target:
    """A motion target: latitude, longitude (degrees), altitude in metres above home."""

    lat: float
    lon: float
    alt_rel_m: float


@dataclass(frozen=True)
class RunningOperation:
    """What the policy needs to know of a drone's running operation (the takeoff and busy rules)."""

    operation_id: str
    kind: str
    message: str
    target_alt_m: float | None = None


class MissionItemLike(Protocol):
    """The fields of `gateway.fleet.mission.MissionItem` the policy reads."""

    @property
    def lat(self) -> float: ...

    @property
    def lon(self) -> float: ...

    @property
    def alt_rel_m(self) -> float: ...

    @property
    def kind(self) -> str: ...

    @property
    def speed_mps(self) -> float | None: ...

    @property
    def command(self) -> int | None: ...


def refuse(rule: Rule | str, text: str, **numbers: Any) -> SafetyRefusal:
    """A refusal whose message starts with the rule name."""
    return SafetyRefusal(str(rule), f"{rule}: {text}", **numbers)


def fmt(value: float, digits: int = 1) -> str:
    """A number for messages: at most `digits` decimals, no trailing zeros."""
    text = f"{value:.{digits}f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


# ------------------------------------------------------------------------------------------------
# operator locks

_SCOPE_RE = re.compile(r"^(\*|[a-z0-9-]{1,32})$")
MAX_REASON_CHARS = 500


@dataclass(frozen=True)
class Lock:
    scope: str  # vehicle id, or "*" for the whole fleet
    reason: str
    by: str
    locked_at: datetime

    def to_record(self) -> dict[str, Any]:
        return {
            "scope": self.scope,
            "reason": self.reason,
            "by": self.by,
            "locked_at": self.locked_at.isoformat(),
        }


class LockView(Protocol):
    """What the MCP side may see of the locks: reading only."""

    def reason_for(self, vehicle_id: str) -> str | None: ...

    def takeover_for(self, vehicle_id: str) -> Lock | None: ...

    def locks_for(self, vehicle_id: str) -> list[Lock]: ...

    def all(self) -> list[Lock]: ...


class LockBook:
    """Operator locks on vehicles or the whole fleet ("*"). Owned by the REST layer, which persists
    `to_records()` and restores with `from_records()`; hand `view()` to everything else."""

    def __init__(self) -> None:
        self._locks: dict[str, Lock] = {}
        self._takeovers: dict[str, Lock] = {}  # vehicle id -> its takeover lock (gateway.fleet.takeover)

    def lock(self, scope: str, reason: str, by: str, at: datetime | None = None) -> Lock:
        """Lock a vehicle (or "*": the fleet). Locking again replaces the reason and who."""
        if not isinstance(scope, str) or not _SCOPE_RE.match(scope):
            raise InvalidArgument(
                f"lock scope must be a vehicle id ([a-z0-9-]{{1,32}}) or '*'; got {scope!r}"
            )
        if not isinstance(reason, str) or not reason.strip():
            raise InvalidArgument("a lock needs a reason (shown to agents and operators)")
        if len(reason) > MAX_REASON_CHARS:
            raise InvalidArgument(f"lock reason is {len(reason)} characters; the limit is {MAX_REASON_CHARS}")
        if not isinstance(by, str) or not by.strip():
            raise InvalidArgument("a lock needs the name of who set it")
        lock = Lock(scope, reason.strip(), by.strip(), at or datetime.now(UTC))
        self._locks[scope] = lock
        return lock

    def unlock(self, scope: str) -> Lock | None:
        """Remove a lock; returns it, or None when that scope was not locked (idempotent)."""
        return self._locks.pop(scope, None)

    def get(self, scope: str) -> Lock | None:
        return self._locks.get(scope)

    # Takeover locks: set by the gateway when a pilot, another ground station or a failsafe changed a
    # drone's mode (`gateway.fleet.takeover`); agents are refused until an operator releases the drone.
    # Kept apart from the operator's locks: unlocking one never lifts the other.
    def take_over(
        self, vehicle_id: str, reason: str, at: datetime | None = None, by: str = "autopilot"
    ) -> Lock:
        lock = Lock(vehicle_id, reason.strip()[:MAX_REASON_CHARS], by, at or datetime.now(UTC))
        self._takeovers[vehicle_id] = lock
        return lock

    def release(self, vehicle_id: str) -> Lock | None:
        """Lift a drone's takeover lock; returns it, or None when there was none (idempotent)."""
        return self._takeovers.pop(vehicle_id, None)

    def takeover_for(self, vehicle_id: str) -> Lock | None:
        return self._takeovers.get(vehicle_id)

    def takeovers(self) -> list[Lock]:
        return sorted(self._takeovers.values(), key=lambda lk: lk.scope)

    def locks_for(self, vehicle_id: str) -> list[Lock]:
        return [lk for key in (FLEET, vehicle_id) if (lk := self._locks.get(key)) is not None]

    def reason_for(self, vehicle_id: str) -> str | None:
        """Why this vehicle is locked (its takeover first, then the fleet lock), or None when it is not."""
        parts = []
        taken = self._takeovers.get(vehicle_id)
        if taken is not None:
            parts.append(f"drone {vehicle_id} was {taken.reason}; an operator must release it")
        for lk in self.locks_for(vehicle_id):
            what = "the fleet is locked" if lk.scope == FLEET else f"drone {vehicle_id} is locked"
            parts.append(f"{what} by {lk.by}: {lk.reason}")
        return "; ".join(parts) or None

    def all(self) -> list[Lock]:
        return sorted(self._locks.values(), key=lambda lk: (lk.scope != FLEET, lk.scope))

    def view(self) -> ReadOnlyLocks:
        return ReadOnlyLocks(self)

    def to_records(self) -> list[dict[str, Any]]:
        return [lk.to_record() for lk in self.all()]

    @classmethod
    def from_records(cls, records: Iterable[Mapping[str, Any]]) -> LockBook:
        book = cls()
        for rec in records:
            try:
                at = rec["locked_at"]
                when = at if isinstance(at, datetime) else datetime.fromisoformat(str(at))
                book.lock(rec["scope"], rec["reason"], rec["by"], at=when)
            except KeyError as exc:
                raise InvalidArgument(f"lock record lacks {exc.args[0]!r}: {dict(rec)!r}") from None
            except ValueError as exc:
                raise InvalidArgument(f"lock record has a bad locked_at: {exc}") from None
        return book


def taken_over_text(vehicle_id: str, lock: Lock) -> str:
    """An agent's refusal on a taken-over drone: what happened, and what an operator must do."""
    return (
        f"drone {vehicle_id} was {lock.reason}. A pilot or ground station has control; the gateway sends "
        f"this drone nothing until an operator releases it (REST DELETE /api/v1/vehicles/{vehicle_id}/"
        f"takeover, `fleet-gateway drones release {vehicle_id}`, or the console). Do not retry; read-only "
        "tools still work"
    )


class ReadOnlyLocks:
    """A `LockView` over a `LockBook`: no lock or unlock here, by construction."""

    __slots__ = ("_all", "_locks_for", "_reason_for", "_takeover_for")

    def __init__(self, book: LockBook) -> None:
        # Bound methods only: the view keeps no attribute through which the book could be reached
        # by ordinary attribute access.
        self._reason_for = book.reason_for
        self._locks_for = book.locks_for
        self._all = book.all
        self._takeover_for = book.takeover_for

    def reason_for(self, vehicle_id: str) -> str | None:
        return self._reason_for(vehicle_id)

    def locks_for(self, vehicle_id: str) -> list[Lock]:
        return self._locks_for(vehicle_id)

    def all(self) -> list[Lock]:
        return self._all()

    def takeover_for(self, vehicle_id: str) -> Lock | None:
        return self._takeover_for(vehicle_id)


# ------------------------------------------------------------------------------------------------
# limits


@dataclass(frozen=True)
class Limits:
    """The numeric limits that apply to one vehicle (fleet settings with its overrides applied)."""

    max_altitude_m: float
    max_distance_m: float
    min_battery_takeoff_pct: float
    min_battery_leg_pct: float
    max_speed_mps: float
    min_altitude_m: float
    max_vertical_speed_mps: float

    @classmethod
    def from_settings(cls, settings: Settings) -> Limits:
        return cls(**{f.name: float(getattr(settings, f.name)) for f in fields(cls)})

    def with_overrides(self, overrides: Mapping[str, float]) -> Limits:
        known = {f.name for f in fields(self)}
        unknown = sorted(set(overrides) - known)
        if unknown:
            raise InvalidArgument(f"unknown vehicle limit(s) {unknown}; known: {sorted(known)}")
        values: dict[str, float] = {}
        for name, value in overrides.items():
            if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
                raise InvalidArgument(f"vehicle limit {name} must be a finite number; got {value!r}")
            if value < 0 or (value == 0 and name in _POSITIVE_LIMITS):
                raise InvalidArgument(f"vehicle limit {name} must be positive; got {value}")
            if name.endswith("_pct") and value > 100:
                raise InvalidArgument(f"vehicle limit {name} must be 0..100 %; got {value}")
            values[name] = float(value)
        merged = replace(self, **values)
        if merged.min_altitude_m >= merged.max_altitude_m:
            raise InvalidArgument(
                f"min_altitude_m {fmt(merged.min_altitude_m)} must be below max_altitude_m "
                f"{fmt(merged.max_altitude_m)}"
            )
        return merged


_POSITIVE_LIMITS = ("max_altitude_m", "max_distance_m", "max_speed_mps", "max_vertical_speed_mps")


def split_patterns(text: str) -> tuple[str, ...]:
    return tuple(p.strip().upper() for p in text.split(",") if p.strip())


_PARAM_NAME_RE = re.compile(r"^[A-Z0-9_]{1,16}$")


# ------------------------------------------------------------------------------------------------
# the policy


class SafetyPolicy:
    """All rules, configured from `Settings`, per-vehicle overrides, geofences and the operator locks."""

    def __init__(
        self,
        settings: Settings,
        locks: LockView | None = None,
        geofences: GeofenceSet | None = None,
        vehicle_limits: Mapping[str, Mapping[str, float]] | None = None,
    ) -> None:
        self.settings = settings
        self.locks: LockView = locks if locks is not None else LockBook().view()
        self.geofences = geofences if geofences is not None else GeofenceSet()
        self.fleet_limits = Limits.from_settings(settings)
        self.param_deny_patterns = split_patterns(settings.param_deny_patterns)
        self.param_allow_patterns = split_patterns(settings.agent_param_allow)
        self.mode_deny_in_air = frozenset(split_patterns(settings.mode_deny_in_air))
        self._overrides: dict[str, Limits] = {}
        merged = {**settings.vehicle_limits, **(vehicle_limits or {})}
        for vehicle_id, overrides in merged.items():
            self.set_vehicle_limits(vehicle_id, overrides)

    @classmethod
    def from_settings(cls, settings: Settings, locks: LockView | None = None) -> SafetyPolicy:
        """The policy with the geofence file named in settings loaded (the one file read here)."""
        fences = load_geofence_file(settings.geofence_file) if settings.geofence_file else None
        return cls(settings, locks=locks, geofences=fences)

    # --- configuration ---------------------------------------------------------------------------

    def set_vehicle_limits(self, vehicle_id: str, overrides: Mapping[str, float]) -> Limits:
        """Replace one vehicle's overrides (an empty mapping removes them)."""
        if not isinstance(vehicle_id, str) or not re.match(r"^[a-z0-9-]{1,32}$", vehicle_id):
            raise InvalidArgument(f"vehicle limits need a vehicle id ([a-z0-9-]{{1,32}}); got {vehicle_id!r}")
        if not overrides:
            self._overrides.pop(vehicle_id, None)
            return self.fleet_limits
        limits = self.fleet_limits.with_overrides(overrides)
        self._overrides[vehicle_id] = limits
        return limits

    def limits_for(self, vehicle_id: str) -> Limits:
        return self._overrides.get(vehicle_id, self.fleet_limits)

    def altitude_band(self, vehicle_ids: Iterable[str]) -> tuple[float, float]:
        """(lowest, highest) altitude above home allowed for all these vehicles together: pass it to
        `plan_formation(min_transit_alt_m=..., max_altitude_m=...)` so transit layers fit every drone."""
        limits = [self.limits_for(v) for v in vehicle_ids] or [self.fleet_limits]
        return max(lim.min_altitude_m for lim in limits), min(lim.max_altitude_m for lim in limits)

    def summary(self, vehicle_id: str | None = None) -> dict[str, Any]:
        """The rules in force (for a status tool or endpoint): limits, zones, deny lists, switches, locks."""
        zones = self.geofences.for_vehicle(vehicle_id) if vehicle_id else list(self.geofences)
        out: dict[str, Any] = {
            "limits": asdict(self.limits_for(vehicle_id) if vehicle_id else self.fleet_limits),
            "min_separation_m": self.settings.min_separation_m,
            "agents_may_kill": self.settings.agents_may_kill,
            "simulators_only": self.settings.simulators_only,
            "param_deny_patterns": list(self.param_deny_patterns),
            "agent_param_allow": list(self.param_allow_patterns),
            "mode_deny_in_air": sorted(self.mode_deny_in_air),
            "geofences": [{"name": z.name, "kind": z.kind, "scope": z.scope} for z in zones],
        }
        if vehicle_id:
            out["locked"] = self.locks.reason_for(vehicle_id)
        else:
            out["locks"] = [lk.to_record() for lk in self.locks.all()]
            out["vehicle_overrides"] = {v: asdict(lim) for v, lim in sorted(self._overrides.items())}
        return out

    # --- gates shared by every actuating check ---------------------------------------------------

    def check_actuation(self, ctx: VehicleContext, via: Via = "mcp") -> None:
        """Operator locks and the simulators-only switch: refuse any actuating command from an agent.
        Operators (via="rest") are not held by either."""
        _check_via(via)
        if via == "mcp":
            taken = self.locks.takeover_for(ctx.vehicle_id)
            if taken is not None:
                raise refuse(
                    Rule.TAKEN_OVER, taken_over_text(ctx.vehicle_id, taken), vehicle_id=ctx.vehicle_id
                )
            reason = self.locks.reason_for(ctx.vehicle_id)
            if reason is not None:
                raise refuse(
                    Rule.OPERATOR_LOCK,
                    f"{reason}. Only an operator can unlock it; read-only tools still work.",
                    vehicle_id=ctx.vehicle_id,
                    reason=reason,
                )
            if self.settings.simulators_only and not ctx.is_simulator:
                raise refuse(
                    Rule.SIMULATORS_ONLY,
                    f"drone {ctx.vehicle_id} is a real vehicle and this gateway lets agents command "
                    "simulators only (GATEWAY_SIMULATORS_ONLY)",
                    vehicle_id=ctx.vehicle_id,
                )

    def check_mode(self, ctx: VehicleContext, mode: str, via: Via = "mcp") -> None:
        """Flight mode changes: locks, simulators-only, and no pilot-stick modes in the air."""
        self.check_actuation(ctx, via)
        if not isinstance(mode, str) or not mode.strip():
            raise refuse(
                Rule.INVALID_INPUT, f"flight mode must be a name; got {mode!r}", vehicle_id=ctx.vehicle_id
            )
        name = mode.strip().upper()
        if via == "mcp" and ctx.airborne and name in self.mode_deny_in_air:
            raise refuse(
                Rule.MODE_IN_AIR,
                f"mode {name} needs a pilot's sticks; in the air without RC input the drone may descend or "
                "drift. Use hold (GUIDED), LAND or RTL instead",
                vehicle_id=ctx.vehicle_id,
                mode=name,
            )

    def check_arm(self, ctx: VehicleContext, via: Via = "mcp") -> None:
        """Arming: locks, simulators-only and the takeoff battery minimum."""
        self.check_actuation(ctx, via)
        self._check_battery(
            ctx, self.limits_for(ctx.vehicle_id).min_battery_takeoff_pct, Rule.BATTERY_TAKEOFF
        )

    # --- motion ----------------------------------------------------------------------------------

    def check_takeoff(self, ctx: VehicleContext, alt_rel_m: float, via: Via = "mcp") -> None:
        self.check_actuation(ctx, via)
        limits = self.limits_for(ctx.vehicle_id)
        _finite(ctx, "takeoff altitude", alt_rel_m)
        self._check_altitude(ctx, limits, "takeoff altitude", alt_rel_m)
        if not ctx.airborne:
            self._check_battery(ctx, limits.min_battery_takeoff_pct, Rule.BATTERY_TAKEOFF)

    def check_motion(self, ctx: VehicleContext, target: Target, via: Via = "mcp") -> None:
        """A goto, reposition or relative move to `target`: altitude band, distance from home, geofences
        (the target and the straight leg from the current position) and the battery minimum for a leg."""
        self.check_actuation(ctx, via)
        limits = self.limits_for(ctx.vehicle_id)
        self._check_point(ctx, limits, target, "target")
        self._check_leg(ctx, self._start_of(ctx), target)
        self._check_battery(ctx, limits.min_battery_leg_pct, Rule.BATTERY_LEG)

    def check_speed(self, ctx: VehicleContext, mps: float, via: Via = "mcp") -> None:
        self.check_actuation(ctx, via)
        _finite(ctx, "speed", mps)
        limit = self.limits_for(ctx.vehicle_id).max_speed_mps
        if mps <= 0:
            raise refuse(
                Rule.INVALID_INPUT,
                f"speed must be above 0 m/s; got {fmt(mps)} m/s",
                vehicle_id=ctx.vehicle_id,
                speed_mps=mps,
            )
        if mps > limit:
            raise refuse(
                Rule.MAX_SPEED,
                f"speed {fmt(mps)} m/s exceeds the limit of {fmt(limit)} m/s",
                vehicle_id=ctx.vehicle_id,
                speed_mps=mps,
                limit_mps=limit,
            )

    def check_mission(self, ctx: VehicleContext, items: Sequence[MissionItemLike], via: Via = "mcp") -> None:
        """A mission, item by item (user items numbered from 1), including each leg between positions.
        Battery: the takeoff minimum when starting on the ground, else the leg minimum."""
        self.check_actuation(ctx, via)
        limits = self.limits_for(ctx.vehicle_id)
        if not items:
            raise refuse(Rule.INVALID_INPUT, "the mission has no items", vehicle_id=ctx.vehicle_id)
        if ctx.airborne:
            self._check_battery(ctx, limits.min_battery_leg_pct, Rule.BATTERY_LEG)
        else:
            self._check_battery(ctx, limits.min_battery_takeoff_pct, Rule.BATTERY_TAKEOFF)
        previous = self._start_of(ctx)
        for number, item in enumerate(items, start=1):
            prefix = f"mission item {number}: "
            kind = item.kind
            speed = item.speed_mps
            if speed is not None:
                with _prefixed(prefix, item=number):
                    self.check_speed(ctx, speed, via)
            if kind == "rtl":
                previous = (ctx.home[0], ctx.home[1]) if ctx.home else None
                continue
            if kind == "other" and item.command not in POSITION_NAV_COMMANDS:
                denied = DENIED_MISSION_COMMANDS.get(item.command or 0)
                if denied is not None:
                    raise refuse(
                        Rule.MISSION_COMMAND,
                        f"{prefix}{denied} ({item.command}) is not accepted in a mission: it would change "
                        "what the safety layer relies on",
                        vehicle_id=ctx.vehicle_id,
                        item=number,
                        command=item.command,
                    )
                continue  # not a position (DO_JUMP, CONDITION_YAW, DO_SET_ROI, ...): passes through
            with _prefixed(prefix, item=number):
                if kind == "takeoff":
                    _finite(ctx, "takeoff altitude", item.alt_rel_m)
                    self._check_altitude(ctx, limits, "takeoff altitude", item.alt_rel_m)
                    continue
                target = Target(item.lat, item.lon, item.alt_rel_m)
                if kind == "land":  # altitude of a land item is not flown; only the place matters
                    self._check_horizontal(ctx, limits, target, "landing point")
                else:
                    self._check_point(ctx, limits, target, "waypoint")
                self._check_leg(ctx, previous, target)
            previous = (item.lat, item.lon)

    def check_formation(
        self, contexts: Mapping[str, VehicleContext], plan: PlannedFormation, via: Via = "mcp"
    ) -> None:
        """Every drone's legs of a formation plan (transit and final), and the plan's separation."""
        sep = self.settings.min_separation_m
        if plan.min_separation_m < sep:
            raise refuse(
                Rule.MIN_SEPARATION,
                f"the plan keeps {fmt(plan.min_separation_m)} m between drones, below the minimum "
                f"separation of {fmt(sep)} m",
                planned_m=plan.min_separation_m,
                limit_m=sep,
            )
        for slot in plan.slots:
            ctx = contexts.get(slot.drone_id)
            if ctx is None:
                raise refuse(
                    Rule.INVALID_INPUT,
                    f"no state for drone {slot.drone_id} in the formation",
                    vehicle_id=slot.drone_id,
                )
            self.check_actuation(ctx, via)
            limits = self.limits_for(ctx.vehicle_id)
            self._check_battery(ctx, limits.min_battery_leg_pct, Rule.BATTERY_LEG)
            previous = self._start_of(ctx)
            for leg_no, wp in enumerate(slot.legs, start=1):
                with _prefixed(f"formation, drone {slot.drone_id}, leg {leg_no}: ", leg=leg_no):
                    target = Target(wp.lat, wp.lon, wp.alt_rel_m)
                    self._check_point(ctx, limits, target, "leg target")
                    self._check_leg(ctx, previous, target)
                previous = (wp.lat, wp.lon)

    # --- sequencing: what is already running on the drone ------------------------------------------

    def check_takeoff_finished(
        self, ctx: VehicleContext, takeoff: RunningOperation | None, action: str, via: Via = "mcp"
    ) -> None:
        """No agent motion while a takeoff has not reached its altitude (the source paper's crash: goto
        sent mid-climb). Operators may interrupt their own or an agent's takeoff."""
        _check_via(via)
        if takeoff is None or via == "rest":
            return
        alt = fmt(ctx.position[2]) if ctx.position is not None else "?"
        target = "?" if takeoff.target_alt_m is None else fmt(takeoff.target_alt_m)
        raise refuse(
            Rule.TAKEOFF_IN_PROGRESS,
            f"{ctx.vehicle_id} is still taking off ({alt} of {target} m above home); {action} was not "
            f"sent. Wait for takeoff to finish: call monitor_flight(drone_id='{ctx.vehicle_id}'), then "
            f"send {action} again.",
            vehicle_id=ctx.vehicle_id,
            operation_id=takeoff.operation_id,
            alt_rel_m=None if ctx.position is None else round(ctx.position[2], 2),
            target_alt_m=takeoff.target_alt_m,
        )

    def check_not_busy(self, ctx: VehicleContext, running: RunningOperation | None, action: str) -> None:
        """A fleet command does not silently take over a drone still busy with its own operation."""
        if running is None:
            return
        raise refuse(
            Rule.DRONE_BUSY,
            f"{ctx.vehicle_id} is still running {running.kind} (operation {running.operation_id}: "
            f"{running.message}); wait for it (monitor_flight / monitor_fleet) or call fleet_hold before "
            f"{action}",
            vehicle_id=ctx.vehicle_id,
            operation_id=running.operation_id,
        )

    def check_stagger(self, stagger_m: float) -> None:
        """Drones returning home at altitudes closer than the minimum separation could meet."""
        sep = self.settings.min_separation_m
        if stagger_m < sep:
            raise refuse(
                Rule.MIN_SEPARATION,
                f"return altitudes {stagger_m:g} m apart are closer than the minimum separation of {sep:g} m",
                stagger_m=stagger_m,
                limit_m=sep,
            )

    # --- kill and parameters ---------------------------------------------------------------------

    def check_kill(self, ctx: VehicleContext, via: Via = "mcp") -> bool:
        """Kill motors; returns whether a human must confirm first. Operators: allowed. Agents: on the
        ground (= disarm) allowed; in the air refused unless `agents_may_kill`, and then allowed only
        once a human confirmed (MCP elicitation; `check_kill_confirmed`). No argument widens this."""
        _check_via(via)
        if via == "rest":
            return False
        self.check_actuation(ctx, via)
        if not ctx.airborne:
            return False
        if not self.settings.agents_may_kill:
            raise refuse(
                Rule.KILL_IN_AIR,
                f"drone {ctx.vehicle_id} is in the air; killing the motors drops it. Only an operator may "
                "do this (GATEWAY_AGENTS_MAY_KILL is off). Use land, hold or return_to_launch",
                vehicle_id=ctx.vehicle_id,
            )
        return True

    def check_kill_confirmed(self, ctx: VehicleContext, confirmed: bool, via: Via = "mcp") -> None:
        """An agent's kill is sent only once its confirmation came back accepted (an operator's at once)."""
        _check_via(via)
        if via == "mcp" and not confirmed:
            raise refuse(
                Rule.KILL_NOT_CONFIRMED,
                f"kill of {ctx.vehicle_id} was not confirmed; nothing sent",
                vehicle_id=ctx.vehicle_id,
            )

    def check_param_write(
        self,
        name: str,
        value: float | None = None,
        via: Via = "mcp",
        vehicle_id: str | None = None,
        protected: Sequence[str] = (),
        governed: Mapping[str, ParamLimit] | None = None,
    ) -> None:
        """An agent may write a parameter only when (1) it matches neither the deny list nor the
        dialect's ``protected`` patterns, and (2) it is ``governed`` by a policy limit and ``value`` keeps
        within it, or it matches the operator's allowlist (GATEWAY_AGENT_PARAM_ALLOW). Everything else
        (sensors, estimator sources, serial ports, ...) is refused: an allowlist misses no dangerous name.
        Operators (via="rest") may write any parameter."""
        _check_via(via)
        if not isinstance(name, str) or not _PARAM_NAME_RE.match(name.strip().upper()):
            raise refuse(
                Rule.INVALID_INPUT,
                f"parameter name must be 1-16 characters of A-Z, 0-9 and _; got {name!r}",
                vehicle_id=vehicle_id,
            )
        upper = name.strip().upper()
        if via != "mcp":
            return
        denied = param_limits.matches(upper, [*self.param_deny_patterns, *protected])
        if denied is not None:
            raise refuse(
                Rule.PARAM_DENY,
                f"parameter {upper} matches the protected pattern {denied.upper()}: agents may not change "
                "arming checks, fences, failsafes or system ids; ask an operator",
                vehicle_id=vehicle_id,
                param=upper,
                pattern=denied.upper(),
            )
        rule = param_limits.governing(governed or {}, upper)
        if rule is not None:
            if value is None:
                return
            limits = self.limits_for(vehicle_id) if vehicle_id else self.fleet_limits
            limit_value = getattr(limits, rule.limit)
            why = param_limits.beyond_limit(upper, float(value), rule, limit_value)
            if why is not None:
                raise refuse(
                    Rule.PARAM_LIMIT,
                    f"{why}; nothing was written",
                    vehicle_id=vehicle_id,
                    param=upper,
                    value=value,
                    limit=rule.limit,
                    limit_value=limit_value,
                )
            return
        if param_limits.matches(upper, self.param_allow_patterns) is None:
            raise refuse(
                Rule.PARAM_NOT_ALLOWED,
                f"agents may write only parameters that a limit governs ({', '.join(sorted(governed or {}))}"
                f") or that GATEWAY_AGENT_PARAM_ALLOW names; {upper} is neither, so nothing was written. An "
                "operator can write it over REST or add it to GATEWAY_AGENT_PARAM_ALLOW",
                vehicle_id=vehicle_id,
                param=upper,
            )

    # --- pieces ----------------------------------------------------------------------------------

    @staticmethod
    def _start_of(ctx: VehicleContext) -> tuple[float, float] | None:
        if ctx.position is not None:
            return (ctx.position[0], ctx.position[1])
        return None

    def _check_point(self, ctx: VehicleContext, limits: Limits, target: Target, what: str) -> None:
        for name, value in (("latitude", target.lat), ("longitude", target.lon)):
            _finite(ctx, f"{what} {name}", value)
        _finite(ctx, f"{what} altitude", target.alt_rel_m)
        _lat_lon(ctx, target.lat, target.lon)
        self._check_altitude(ctx, limits, f"{what} altitude", target.alt_rel_m)
        self._check_horizontal(ctx, limits, target, what)

    def _check_horizontal(self, ctx: VehicleContext, limits: Limits, target: Target, what: str) -> None:
        _finite(ctx, f"{what} latitude", target.lat)
        _finite(ctx, f"{what} longitude", target.lon)
        _lat_lon(ctx, target.lat, target.lon)
        if ctx.home is None:
            raise refuse(
                Rule.HOME_UNKNOWN,
                f"drone {ctx.vehicle_id} has no home position yet, so the distance limit of "
                f"{fmt(limits.max_distance_m)} m from home cannot be checked; wait for a GPS fix and home",
                vehicle_id=ctx.vehicle_id,
                limit_m=limits.max_distance_m,
            )
        distance = geo.horizontal_distance_m(ctx.home[0], ctx.home[1], target.lat, target.lon)
        if distance > limits.max_distance_m:
            raise refuse(
                Rule.MAX_DISTANCE,
                f"{what} is {fmt(distance)} m from home, beyond the limit of {fmt(limits.max_distance_m)} m; "
                f"nothing was sent: tell the user it cannot be flown, or choose a point within "
                f"{fmt(limits.max_distance_m)} m of home",
                vehicle_id=ctx.vehicle_id,
                distance_m=round(distance, 2),
                limit_m=limits.max_distance_m,
            )
        for v in self.geofences.check_target(ctx.vehicle_id, target.lat, target.lon):
            raise _geofence_refusal(ctx, v, what)

    def _check_leg(self, ctx: VehicleContext, start: tuple[float, float] | None, target: Target) -> None:
        zones = self.geofences.for_vehicle(ctx.vehicle_id)
        if not zones:
            return
        if start is None:
            raise refuse(
                Rule.POSITION_UNKNOWN,
                f"the position of drone {ctx.vehicle_id} is unknown, so the path to the target cannot be "
                f"checked against {len(zones)} geofence zone(s)",
                vehicle_id=ctx.vehicle_id,
            )
        for v in self.geofences.check_leg(ctx.vehicle_id, start, (target.lat, target.lon)):
            raise _geofence_refusal(ctx, v, "path")

    @staticmethod
    def _check_altitude(ctx: VehicleContext, limits: Limits, what: str, alt: float) -> None:
        if alt < 0:
            raise refuse(
                Rule.MIN_ALTITUDE,
                f"{what} {fmt(alt)} m is below home; altitudes are metres above home and must be at least "
                f"{fmt(limits.min_altitude_m)} m (use land to descend)",
                vehicle_id=ctx.vehicle_id,
                alt_rel_m=alt,
                limit_m=limits.min_altitude_m,
            )
        if alt < limits.min_altitude_m:
            raise refuse(
                Rule.MIN_ALTITUDE,
                f"{what} {fmt(alt)} m is below the minimum of {fmt(limits.min_altitude_m)} m above home "
                "(use land to descend)",
                vehicle_id=ctx.vehicle_id,
                alt_rel_m=alt,
                limit_m=limits.min_altitude_m,
            )
        if alt > limits.max_altitude_m:
            raise refuse(
                Rule.MAX_ALTITUDE,
                f"{what} {fmt(alt)} m exceeds the limit of {fmt(limits.max_altitude_m)} m above home; "
                f"nothing was sent: fly at most {fmt(limits.max_altitude_m)} m, or tell the user the limit",
                vehicle_id=ctx.vehicle_id,
                alt_rel_m=alt,
                limit_m=limits.max_altitude_m,
            )

    @staticmethod
    def _check_battery(ctx: VehicleContext, minimum: float, rule: Rule) -> None:
        purpose = "take off" if rule is Rule.BATTERY_TAKEOFF else "start a new leg"
        if minimum <= 0:
            return
        pct = ctx.battery_pct
        if pct is None or not math.isfinite(pct):
            raise refuse(
                Rule.BATTERY_UNKNOWN,
                f"battery level of drone {ctx.vehicle_id} is unknown; "
                f"{fmt(minimum)} % is needed to {purpose}",
                vehicle_id=ctx.vehicle_id,
                minimum_pct=minimum,
            )
        if pct < minimum:
            raise refuse(
                rule,
                f"battery {fmt(pct)} % is below the {fmt(minimum)} % needed to {purpose}; nothing was "
                + ("sent: tell the user" if not ctx.airborne else "sent: bring it home (return_to_launch)"),
                vehicle_id=ctx.vehicle_id,
                battery_pct=pct,
                minimum_pct=minimum,
            )


# ------------------------------------------------------------------------------------------------
# helpers


def _check_via(via: str) -> None:
    if via not in ("mcp", "rest"):
        raise InvalidArgument(f"via must be 'mcp' or 'rest'; got {via!r}")


def _finite(ctx: VehicleContext, name: str, value: Any) -> None:
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
        raise refuse(
            Rule.INVALID_INPUT, f"{name} must be a finite number; got {value!r}", vehicle_id=ctx.vehicle_id
        )


def _lat_lon(ctx: VehicleContext, lat: float, lon: float) -> None:
    try:
        geo.check_lat_lon(lat, lon)
    except InvalidArgument as exc:
        raise refuse(Rule.INVALID_INPUT, exc.message, vehicle_id=ctx.vehicle_id) from None


def _geofence_refusal(ctx: VehicleContext, v: Violation, what: str) -> SafetyRefusal:
    if v.kind == "keep_in" and v.breach == "target":
        text = f"{what} is {fmt(v.metres)} m outside keep-in zone '{v.zone}'"
        rule = Rule.KEEP_IN
    elif v.kind == "keep_in":
        text = f"the straight path to the target leaves keep-in zone '{v.zone}' for {fmt(v.metres)} m"
        rule = Rule.KEEP_IN
    elif v.breach == "target":
        text = f"{what} is inside keep-out zone '{v.zone}' ({fmt(v.metres)} m from its edge)"
        rule = Rule.KEEP_OUT
    elif v.metres < 0.05:
        text = f"the straight path to the target touches keep-out zone '{v.zone}'"
        rule = Rule.KEEP_OUT
    else:
        text = f"the straight path to the target crosses keep-out zone '{v.zone}' for {fmt(v.metres)} m"
        rule = Rule.KEEP_OUT
    nxt = (
        "choose a point clear of the zone, or tell the user"
        if v.breach == "target"
        else "fly around the zone in legs that stay clear of it, or tell the user"
    )
    text = f"{text}; nothing was sent: {nxt}"
    return refuse(rule, text, vehicle_id=ctx.vehicle_id, zone=v.zone, metres=round(v.metres, 2))


class _prefixed:
    """Re-raise a refusal with a prefix after the rule name (e.g. the mission item) and extra numbers."""

    def __init__(self, prefix: str, **numbers: Any) -> None:
        self.prefix = prefix
        self.numbers = numbers

    def __enter__(self) -> None:
        return None

    def __exit__(self, exc_type: Any, exc: BaseException | None, tb: Any) -> None:
        if isinstance(exc, SafetyRefusal):
            head = f"{exc.rule}: "
            body = exc.message[len(head) :] if exc.message.startswith(head) else exc.message
            details = {k: v for k, v in exc.details.items() if k != "rule"}
            raise SafetyRefusal(exc.rule, f"{head}{self.prefix}{body}", **details, **self.numbers) from None
