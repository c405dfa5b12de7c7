"""An autopilot the gateway has no dialect for (its HEARTBEAT names one no dialect is registered for,
e.g. MAV_AUTOPILOT_GENERIC): what can be read of it without knowing its ways, and nothing to fly it with.

Its telemetry is MAVSDK's (mode names too), its landed state is MAVSDK's in_air, and no mode, mission
layout or parameter is assumed: flown as ArduPilot it could be sent a mode number or a mission layout
that means something else to it. So it is shown (list_drones, status, telemetry) and every command to
it is refused by ``gateway.fleet.dialects.flying_dialect`` with `NoDialect`.
"""

from __future__ import annotations

from collections.abc import Mapping

from gateway.fleet.dialects.base import reader
from gateway.fleet.dialects.modes import ModeChoice
from gateway.fleet.policy.mission_check import MissionSemantics
from gateway.fleet.policy.param_limits import ParamLimit
from gateway.link.telemetry import HealthValue, TelemetryCache


def autopilot_label(mav_autopilot: int) -> str:
    """E.g. "MAV_AUTOPILOT_GENERIC (0)", named by MAVLink's common.xml (pymavlink); a number it does
    not define is shown as "MAV_AUTOPILOT 99"."""
    from pymavlink.dialects.v20 import common  # only when a refusal is written: a large module

    entry = common.enums["MAV_AUTOPILOT"].get(mav_autopilot)
    if entry is None or entry.name.endswith("_ENUM_END"):
        return f"MAV_AUTOPILOT {mav_autopilot}"
    return f"{entry.name} ({mav_autopilot})"


class Unsupported:
    """The reads of an autopilot no dialect is registered for; it implements ``DialectReads`` only."""

    first_user_seq = 0
    skipped_streams: frozenset[str] = frozenset()
    estimate_from_ekf_report = False
    ready_after_prearm_pass = False
    follows_events = False
    return_altitude_params: tuple[tuple[str, float], ...] = ()
    protected_params: tuple[str, ...] = ()
    limit_params: Mapping[str, ParamLimit] = {}
    #: no mission command is modelled for an autopilot without a dialect: every file item is unchecked
    mission_semantics = MissionSemantics("this autopilot", {}, frozenset(), frozenset())

    def __init__(self, mav_autopilot: int) -> None:
        self.mav_autopilot = mav_autopilot
        self.name = autopilot_label(mav_autopilot)

    def mode_name(self, custom_mode: int, mav_type: int) -> str | None:
        return None  # MAVSDK's name of the mode

    def position_estimate_ok(self, health: HealthValue, ekf_flags: int | None) -> bool:
        return health.local_position_ok

    def mode_names(self) -> list[str]:
        return []

    def resolve_mode(self, name: str) -> ModeChoice | None:
        return None

    def native_mode(self, custom_mode: int) -> str:
        return f"custom mode {custom_mode}"

    def commanded_modes(self, kind: str, *, done: bool = False) -> frozenset[str]:
        return frozenset()  # it is commanded nothing, so no mode is judged

    def on_ground(self, telemetry: TelemetryCache, *, fresh: bool = True) -> bool | None:
        in_air = reader(telemetry, fresh)("in_air")
        return None if in_air is None else not in_air
