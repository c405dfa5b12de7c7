"""The numeric limits that apply to one vehicle: the fleet's settings with that vehicle's overrides
applied, each override checked."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, fields, replace

from gateway.config import Settings
from gateway.errors import InvalidArgument
from gateway.fleet.policy.safety_rules import fmt


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
