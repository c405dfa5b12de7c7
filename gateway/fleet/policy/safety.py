"""Safety policy: pure checks run before anything is sent to a drone (no I/O, no clocks but lock times).

Every check returns quietly when allowed, or raises `SafetyRefusal(rule, message, **numbers)` whose
rule is a `Rule` member and whose message starts with the rule's name and states the numbers involved,
e.g. ``max_altitude: target altitude 150 m exceeds the limit of 120 m above home``. The audit table
records the refusal (rule, message, numbers) from the exception.

Who calls what: the Commander (`gateway.fleet.commands.commander`), for every door, with the caller's ``via``:
- agents (MCP, and a node's own cluster commands) are judged with ``via="mcp"`` (the default): operator
  locks, `simulators_only`, the parameter deny list, pilot modes in the air, the kill restriction and
  the takeoff guard apply;
- operators (REST, the console) with ``via="rest"``: the limits still apply, those others do not.
- Agents only ever reach a `LockView` (read-only); locking and unlocking are operator verbs.
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import asdict
from typing import TYPE_CHECKING

from gateway.config import Settings
from gateway.errors import InvalidArgument
from gateway.fleet.policy import param_limits, patterns
from gateway.fleet.policy.geofence import GeofenceSet, load_geofence_file
from gateway.fleet.policy.mission_check import MissionSemantics, Unchecked
from gateway.fleet.policy.mission_rules import check_items
from gateway.fleet.policy.operator_locks import LockBook, LockView, taken_over_text
from gateway.fleet.policy.param_limits import ParamLimit
from gateway.fleet.policy.safety_checks import (
    check_altitude,
    check_battery,
    check_leg,
    check_point,
    require_finite,
    start_of,
)
from gateway.fleet.policy.safety_inputs import (
    MissionItemLike,
    PlannedFormation,
    RunningOperation,
    Target,
    VehicleContext,
)
from gateway.fleet.policy.safety_rules import (
    Rule,
    Via,
    fmt,
    prefixed,
    refuse,
)
from gateway.fleet.policy.vehicle_limits import Limits, split_patterns
from gateway.util.json_types import JsonObject, json_list

if TYPE_CHECKING:
    from gateway.fleet.dialects.modes import ModeChoice

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

    def summary(self, vehicle_id: str | None = None) -> JsonObject:
        """The rules in force (for a status tool or endpoint): limits, zones, deny lists, switches, locks."""
        zones = self.geofences.for_vehicle(vehicle_id) if vehicle_id else list(self.geofences)
        out: JsonObject = {
            "limits": asdict(self.limits_for(vehicle_id) if vehicle_id else self.fleet_limits),
            "min_separation_m": self.settings.min_separation_m,
            "agents_may_kill": self.settings.agents_may_kill,
            "simulators_only": self.settings.simulators_only,
            "param_deny_patterns": json_list(self.param_deny_patterns),
            "agent_param_allow": json_list(self.param_allow_patterns),
            "mode_deny_in_air": json_list(sorted(self.mode_deny_in_air)),
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
                raise ctx.refuse(Rule.TAKEN_OVER, taken_over_text(ctx.vehicle_id, taken))
            reason = self.locks.reason_for(ctx.vehicle_id)
            if reason is not None:
                raise ctx.refuse(
                    Rule.OPERATOR_LOCK,
                    f"{reason}. Only an operator can unlock it; read-only tools still work.",
                    reason=reason,
                )
            if self.settings.simulators_only and not ctx.is_simulator:
                raise ctx.refuse(
                    Rule.SIMULATORS_ONLY,
                    f"drone {ctx.vehicle_id} is a real vehicle and this gateway lets agents command "
                    "simulators only (GATEWAY_SIMULATORS_ONLY)",
                )

    def check_mode(self, ctx: VehicleContext, mode: str, via: Via = "mcp") -> None:
        """Flight mode changes: locks, simulators-only, and no pilot-stick modes in the air."""
        self.check_actuation(ctx, via)
        if not isinstance(mode, str) or not mode.strip():
            raise ctx.refuse(Rule.INVALID_INPUT, f"flight mode must be a name; got {mode!r}")
        name = mode.strip().upper()
        if via == "mcp" and ctx.airborne and name in self.mode_deny_in_air:
            raise ctx.refuse(
                Rule.MODE_IN_AIR,
                f"mode {name} needs a pilot's sticks; in the air without RC input the drone may descend or "
                "drift. Use hold (GUIDED), LAND or RTL instead",
                mode=name,
            )

    def check_mode_choice(
        self, ctx: VehicleContext, choice: ModeChoice, via: Via = "mcp", pattern_radius_m: float | None = None
    ) -> None:
        """A mode by what it needs (agents: only the modes the dialect lists as flyable without a pilot,
        in the air) and what it flies (a pattern's extent, for everyone): `gateway.fleet.policy.patterns`."""
        patterns.check_air_mode(ctx, choice, via)
        patterns.check_pattern(self.geofences, ctx, self.limits_for(ctx.vehicle_id), choice, pattern_radius_m)

    def check_arm(self, ctx: VehicleContext, via: Via = "mcp") -> None:
        """Arming: locks, simulators-only and the takeoff battery minimum."""
        self.check_actuation(ctx, via)
        check_battery(ctx, self.limits_for(ctx.vehicle_id).min_battery_takeoff_pct, Rule.BATTERY_TAKEOFF)

    # --- motion ----------------------------------------------------------------------------------

    def check_takeoff(self, ctx: VehicleContext, alt_rel_m: float, via: Via = "mcp") -> None:
        self.check_actuation(ctx, via)
        limits = self.limits_for(ctx.vehicle_id)
        require_finite(ctx, "takeoff altitude", alt_rel_m)
        check_altitude(ctx, limits, "takeoff altitude", alt_rel_m)
        if not ctx.airborne:
            check_battery(ctx, limits.min_battery_takeoff_pct, Rule.BATTERY_TAKEOFF)

    def check_motion(self, ctx: VehicleContext, target: Target, via: Via = "mcp") -> None:
        """A goto, reposition or relative move to `target`: altitude band, distance from home, geofences
        (the target and the straight leg from the current position) and the battery minimum for a leg."""
        self.check_actuation(ctx, via)
        limits = self.limits_for(ctx.vehicle_id)
        check_point(self.geofences, ctx, limits, target, "target")
        check_leg(self.geofences, ctx, start_of(ctx), (target.lat, target.lon))
        check_battery(ctx, limits.min_battery_leg_pct, Rule.BATTERY_LEG)

    def check_speed(self, ctx: VehicleContext, mps: float, via: Via = "mcp") -> None:
        self.check_actuation(ctx, via)
        require_finite(ctx, "speed", mps)
        limit = self.limits_for(ctx.vehicle_id).max_speed_mps
        if mps <= 0:
            raise ctx.refuse(
                Rule.INVALID_INPUT,
                f"speed must be above 0 m/s; got {fmt(mps)} m/s",
                speed_mps=mps,
            )
        if mps > limit:
            raise ctx.refuse(
                Rule.MAX_SPEED,
                f"speed {fmt(mps)} m/s exceeds the limit of {fmt(limit)} m/s",
                speed_mps=mps,
                limit_mps=limit,
            )

    def check_mission(
        self,
        ctx: VehicleContext,
        items: Sequence[MissionItemLike],
        via: Via = "mcp",
        semantics: MissionSemantics | None = None,
        starts: Iterable[int] = (1,),
    ) -> list[Unchecked]:
        """A mission, item by item (user items numbered from 1), including each leg between positions
        and the leg from where the drone is to each item it may start from (``starts``), with the
        autopilot's ``semantics`` for items a file or the autopilot holds (`mission_rules.check_items`).
        Battery: the takeoff minimum when starting on the ground, else the leg minimum. Returns the items
        the gateway cannot check (refused for agents; an operator's mission is then marked unchecked)."""
        self.check_actuation(ctx, via)
        limits = self.limits_for(ctx.vehicle_id)
        if not items:
            raise ctx.refuse(Rule.INVALID_INPUT, "the mission has no items")
        if ctx.airborne:
            check_battery(ctx, limits.min_battery_leg_pct, Rule.BATTERY_LEG)
        else:
            check_battery(ctx, limits.min_battery_takeoff_pct, Rule.BATTERY_TAKEOFF)
        for number, item in enumerate(items, start=1):
            if getattr(item, "raw", None) is None and item.speed_mps is not None:
                with prefixed(f"mission item {number}: ", item=number):
                    self.check_speed(ctx, item.speed_mps, via)
        return check_items(self.geofences, ctx, limits, items, via, semantics, starts)

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
            check_battery(ctx, limits.min_battery_leg_pct, Rule.BATTERY_LEG)
            previous = start_of(ctx)
            for leg_no, wp in enumerate(slot.legs, start=1):
                with prefixed(f"formation, drone {slot.drone_id}, leg {leg_no}: ", leg=leg_no):
                    target = Target(wp.lat, wp.lon, wp.alt_rel_m)
                    check_point(self.geofences, ctx, limits, target, "leg target")
                    check_leg(self.geofences, ctx, previous, (target.lat, target.lon))
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
        raise ctx.refuse(
            Rule.TAKEOFF_IN_PROGRESS,
            f"{ctx.vehicle_id} is still taking off ({alt} of {target} m above home); {action} was not "
            f"sent. Wait for takeoff to finish: call monitor_flight(drone_id='{ctx.vehicle_id}'), then "
            f"send {action} again.",
            operation_id=takeoff.operation_id,
            alt_rel_m=None if ctx.position is None else round(ctx.position[2], 2),
            target_alt_m=takeoff.target_alt_m,
        )

    def check_not_busy(self, ctx: VehicleContext, running: RunningOperation | None, action: str) -> None:
        """A fleet command does not silently take over a drone still busy with its own operation."""
        if running is None:
            return
        raise ctx.refuse(
            Rule.DRONE_BUSY,
            f"{ctx.vehicle_id} is still running {running.kind} (operation {running.operation_id}: "
            f"{running.message}); wait for it (monitor_flight / monitor_fleet) or call fleet_hold before "
            f"{action}",
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
            raise ctx.refuse(
                Rule.KILL_IN_AIR,
                f"drone {ctx.vehicle_id} is in the air; killing the motors drops it. Only an operator may "
                "do this (GATEWAY_AGENTS_MAY_KILL is off). Use land, hold or return_to_launch",
            )
        return True

    def check_kill_confirmed(self, ctx: VehicleContext, confirmed: bool, via: Via = "mcp") -> None:
        """An agent's kill is sent only once its confirmation came back accepted (an operator's at once)."""
        _check_via(via)
        if via == "mcp" and not confirmed:
            raise ctx.refuse(
                Rule.KILL_NOT_CONFIRMED,
                f"kill of {ctx.vehicle_id} was not confirmed; nothing sent",
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
        if rule is not None and rule.limit is not None:
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
                f"agents may write only parameters that a limit governs "
                f"({', '.join(param_limits.governed_names(governed or {}))}"
                f") or that GATEWAY_AGENT_PARAM_ALLOW names; {upper} is neither, so nothing was written. An "
                "operator can write it over REST or add it to GATEWAY_AGENT_PARAM_ALLOW",
                vehicle_id=vehicle_id,
                param=upper,
            )
        documented = param_limits.documented(governed or {}, upper)
        if documented is not None and value is not None:
            why = param_limits.outside_range(upper, float(value), documented)
            if why is not None:
                raise refuse(
                    Rule.PARAM_RANGE, f"{why}; nothing was written", vehicle_id=vehicle_id, param=upper,
                    value=value, low=documented.low, high=documented.high,
                )  # fmt: skip


# ------------------------------------------------------------------------------------------------
# helpers


def _check_via(via: str) -> None:
    if via not in ("mcp", "rest"):
        raise InvalidArgument(f"via must be 'mcp' or 'rest'; got {via!r}")
