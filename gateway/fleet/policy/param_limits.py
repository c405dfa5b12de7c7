"""Autopilot parameters by their effect, and the agents' parameter allowlist.

A parameter such as ArduPilot's WPNAV_SPEED or PX4's MPC_XY_VEL_MAX sets what the autopilot itself flies
at; an agent that raises it walks around the gateway's own speed limit (measured before this rule: a goto
at 32 m/s against a 15 m/s limit). So each autopilot dialect maps those parameters to the policy limit
they govern, with the parameter's unit, its documented range and its effect, and an agent's write is
checked against both:

* ``absolute``: the value is the speed, altitude or distance flown (WPNAV_SPEED, RTL_ALT): at most the
  limit;
* ``added``: the autopilot adds the value to the state the vehicle is in when it acts (ArduCopter's
  RTL_CLIMB_MIN: the return climbs that much above the altitude RTL starts from). The vehicle may be
  anywhere the limits let it fly, at the limit too, so every value above zero can carry it past the
  limit: only zero is accepted;
* ``diameter``: the value is a radius the vehicle flies a pattern with, whose far side lies two radii
  from where the pattern starts (ArduCopter's CIRCLE_RADIUS: the centre is one radius ahead): at most
  half the limit. Entering the pattern in the air is judged by its real extent
  (`gateway.fleet.policy.patterns`).

Parameters that govern no limit but that the operator's allowlist lets agents write are listed too,
with their documented range only (``limit`` None): a value outside the autopilot's own range is refused,
and an allowlisted name the dialect knows no range for is refused as well (the gateway cannot say what
it does). Every other parameter is refused for agents unless the operator's allowlist names it: sensors,
estimator sources, serial ports, system ids, failsafes and arming checks stay out of reach by default,
including names nobody thought of yet.
"""

from __future__ import annotations

import fnmatch
import math
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from typing import Literal

#: the policy limits a parameter may govern, with the words a refusal uses for them
LIMIT_WORDS = {
    "max_speed_mps": ("horizontal speed", "m/s"),
    "max_vertical_speed_mps": ("vertical speed", "m/s"),
    "max_altitude_m": ("altitude above home", "m"),
    "max_distance_m": ("distance from the origin", "m"),
}

Effect = Literal["absolute", "added", "diameter"]


@dataclass(frozen=True)
class ParamLimit:
    """One parameter's documented range and, when it governs one, the policy limit it could walk around.

    ``limit`` is the policy limit (None: the range alone bounds it); ``scale`` is the parameter's units
    per policy unit (100 for cm/s against m/s); ``low`` and ``high`` are the autopilot's documented range
    in its units (``high`` None: only the policy bounds it); ``effect`` says how the value acts (module
    docstring)."""

    limit: str | None
    unit: str
    scale: float = 1.0
    low: float = 0.0
    high: float | None = None
    effect: Effect = "absolute"

    def ceiling(self, limit_value: float) -> float:
        """The highest value, in the parameter's units, whose effect keeps within ``limit_value``."""
        if self.effect == "added":
            return 0.0
        if self.effect == "diameter":
            return limit_value * self.scale / 2.0
        return limit_value * self.scale


def governing(table: Mapping[str, ParamLimit], name: str) -> ParamLimit | None:
    """The rule of a parameter that governs a policy limit, or None."""
    rule = table.get(name.upper())
    return rule if rule is not None and rule.limit is not None else None


def documented(table: Mapping[str, ParamLimit], name: str) -> ParamLimit | None:
    """The entry of ``name`` in the dialect's table (its documented range), or None."""
    return table.get(name.upper())


def governed_names(table: Mapping[str, ParamLimit]) -> list[str]:
    return sorted(name for name, rule in table.items() if rule.limit is not None)


def matches(name: str, patterns: Iterable[str]) -> str | None:
    """The first glob pattern (case-insensitive) that ``name`` matches, or None."""
    upper = name.upper()
    for pattern in patterns:
        if fnmatch.fnmatchcase(upper, pattern.upper()):
            return pattern
    return None


def _num(value: float) -> str:
    text = f"{value:.2f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def _accepted(low: float, high: float, unit: str) -> str:
    return f"{_num(low)} {unit}" if high <= low else f"{_num(low)} to {_num(high)} {unit}"


def outside_range(name: str, value: float, rule: ParamLimit) -> str | None:
    """Why ``value`` is outside the autopilot's documented range for ``name``, or None."""
    if not math.isfinite(value):
        return f"{name} must be a finite number; got {value!r}"
    high = math.inf if rule.high is None else rule.high
    if rule.low <= value <= high:
        return None
    top = "" if rule.high is None else f" to {_num(rule.high)}"
    return (
        f"{name} {_num(value)} {rule.unit} is outside the autopilot's documented range for it; accepted: "
        f"{_num(rule.low)}{top} {rule.unit}"
    ).replace("  ", " ")


def beyond_limit(name: str, value: float, rule: ParamLimit, limit_value: float) -> str | None:
    """Why writing ``value`` to ``name`` breaks its range or, by its effect, its policy limit, or None
    when it does not. The words name the value, the effect and the accepted range."""
    assert rule.limit is not None
    what, policy_unit = LIMIT_WORDS[rule.limit]
    if not math.isfinite(value):
        return f"{name} must be a finite number; got {value!r}"
    ceiling = rule.ceiling(limit_value)
    top = min(math.inf if rule.high is None else rule.high, ceiling)
    if value < rule.low:
        accepted = _accepted(rule.low, top, rule.unit)
        return f"{name} {_num(value)} {rule.unit} is below its range; accepted: {accepted}"
    if rule.high is not None and rule.high < ceiling:
        if value > rule.high:
            return (
                f"{name} {_num(value)} {rule.unit} is above the autopilot's range for it; accepted: "
                f"{_accepted(rule.low, rule.high, rule.unit)}"
            )
        return None
    if value <= ceiling:
        return None
    in_policy = value / rule.scale
    converted = f" ({_num(in_policy)} {policy_unit})" if rule.scale != 1.0 else ""
    limit_words = f"the {rule.limit} limit of {_num(limit_value)} {policy_unit} ({what})"
    accepted = _accepted(rule.low, top, rule.unit)
    if rule.effect == "added":
        return (
            f"{name} {_num(value)} {rule.unit}{converted} is added by the autopilot to where the vehicle is "
            f"when it acts: from {_num(limit_value)} {policy_unit}, as far as an agent may fly, it would go "
            f"to {_num(limit_value + in_policy)} {policy_unit}, beyond {limit_words}; accepted: {accepted}"
        )
    if rule.effect == "diameter":
        return (
            f"{name} {_num(value)} {rule.unit}{converted} is a radius whose pattern reaches two radii "
            f"({_num(2 * in_policy)} {policy_unit}) from where it starts, beyond {limit_words}; accepted: "
            f"{accepted}"
        )
    return (
        f"{name} {_num(value)} {rule.unit}{converted} would let the autopilot exceed {limit_words}; "
        f"accepted: {accepted}"
    )
