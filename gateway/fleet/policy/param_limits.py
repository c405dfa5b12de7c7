"""Autopilot parameters that govern a policy limit, and the agents' parameter allowlist.

A parameter such as ArduPilot's WPNAV_SPEED or PX4's MPC_XY_VEL_MAX sets what the autopilot itself flies
at; an agent that raises it walks around the gateway's own speed limit (measured before this rule: a goto
at 32 m/s against a 15 m/s limit). So each autopilot dialect maps those parameters to the policy limit
they govern, with the parameter's unit and its documented range, and an agent's write is checked against
both. Every other parameter is refused for agents unless the operator's allowlist names it: sensors,
estimator sources, serial ports, system ids, failsafes and arming checks stay out of reach by default,
including names nobody thought of yet.
"""

from __future__ import annotations

import fnmatch
import math
from collections.abc import Iterable, Mapping
from dataclasses import dataclass

#: the policy limits a parameter may govern, with the words a refusal uses for them
LIMIT_WORDS = {
    "max_speed_mps": ("horizontal speed", "m/s"),
    "max_vertical_speed_mps": ("vertical speed", "m/s"),
    "max_altitude_m": ("altitude above home", "m"),
    "max_distance_m": ("distance from home", "m"),
}


@dataclass(frozen=True)
class ParamLimit:
    """One parameter governed by a policy limit.

    ``scale`` is the parameter's units per policy unit (100 for cm/s against m/s); ``low`` and ``high``
    are the parameter's own documented range in its units (``high`` None: only the policy bounds it).
    """

    limit: str
    unit: str
    scale: float = 1.0
    low: float = 0.0
    high: float | None = None


def governing(table: Mapping[str, ParamLimit], name: str) -> ParamLimit | None:
    return table.get(name.upper())


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


def beyond_limit(name: str, value: float, rule: ParamLimit, limit_value: float) -> str | None:
    """Why writing ``value`` to ``name`` breaks its range or its policy limit, or None when it does not.
    The words name the value in the parameter's units and in the policy's."""
    what, policy_unit = LIMIT_WORDS[rule.limit]
    if not math.isfinite(value):
        return f"{name} must be a finite number; got {value!r}"
    if value < rule.low:
        return (
            f"{name} {_num(value)} {rule.unit} is below its range; accepted: {_num(rule.low)} to "
            f"{_num(min(rule.high or math.inf, limit_value * rule.scale))} {rule.unit}"
        )
    ceiling = limit_value * rule.scale
    if rule.high is not None and rule.high < ceiling:
        if value > rule.high:
            return (
                f"{name} {_num(value)} {rule.unit} is above the autopilot's range for it; accepted: "
                f"{_num(rule.low)} to {_num(rule.high)} {rule.unit}"
            )
        return None
    if value > ceiling:
        converted = f" ({_num(value / rule.scale)} {policy_unit})" if rule.scale != 1.0 else ""
        return (
            f"{name} {_num(value)} {rule.unit}{converted} would let the autopilot exceed the {rule.limit} "
            f"limit of {_num(limit_value)} {policy_unit} ({what}); accepted: {_num(rule.low)} to "
            f"{_num(ceiling)} {rule.unit}"
        )
    return None
