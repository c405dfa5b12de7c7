"""PX4: what it does its own way (measured on PX4 1.16 SITL with SIH through mavsdk_server 4.0.5).

* Modes are main/sub modes packed in the HEARTBEAT's custom mode (main << 16 | sub << 24); MAVSDK
  names them well (HOLD, MISSION, RETURN_TO_LAUNCH...). HOLD and GUIDED are AUTO.LOITER (Hold), in
  which PX4 flies the gateway's reposition commands. The pilot modes (MANUAL, ALTCTL, POSCTL,
  STABILIZED, ACRO) need manual control input and OFFBOARD a setpoint stream: not offered.
* Missions have no home slot: PX4 flies seq 0 like any item (ArduPilot's placeholder there flew the
  drone back to home at ground level). PX4 acknowledges an upload, then checks the mission and says
  "Mission rejected: ..." in an EVENT / STATUSTEXT within about a second: that is the rejection. From
  the ground, switch to MISSION first (refused for a mission PX4 rejected) and only then arm.
* Arming in the current mode (Hold); readiness from MAVSDK's local position health.
* RTL climbs to RTL_RETURN_ALT, in metres. PX4 refuses RAW_IMU (HIGHRES_IMU instead) and explains
  refusals in EVENT messages.
* On the ground means EXTENDED_SYS_STATE's landed state ON_GROUND (its land detector), not merely
  "not in air": PX4 reports TAKING_OFF / LANDING between the two.
"""

from __future__ import annotations

from collections.abc import Awaitable, Callable, Mapping, Sequence

from gateway.errors import CommandFailed
from gateway.fleet.dialects.base import LinkOps, matches_any, reader
from gateway.fleet.dialects.mission_semantics import px4_mission
from gateway.fleet.dialects.modes import (
    COMMON_MODES,
    NOT_MODELLED,
    AirUse,
    ModeChoice,
    native_name,
)
from gateway.fleet.missions import mission
from gateway.fleet.missions.mission import DownloadedItem, MissionItem, WirePlan
from gateway.fleet.policy.mission_check import MissionSemantics
from gateway.fleet.policy.param_limits import ParamLimit
from gateway.link.telemetry import HealthValue, TelemetryCache

#: PX4 main / sub modes (px4_custom_mode.h); DO_SET_MODE takes them as param2 / param3
PX4_MODES: dict[str, tuple[int, int]] = {
    "MANUAL": (1, 0),
    "ALTCTL": (2, 0),
    "POSCTL": (3, 0),
    "AUTO.TAKEOFF": (4, 2),
    "AUTO.LOITER": (4, 3),
    "AUTO.MISSION": (4, 4),
    "AUTO.RTL": (4, 5),
    "AUTO.LAND": (4, 6),
    "ACRO": (5, 0),
    "OFFBOARD": (6, 0),
    "STABILIZED": (7, 0),
}
COMMON_TO_NATIVE: dict[str, str] = {
    "HOLD": "AUTO.LOITER",
    "GUIDED": "AUTO.LOITER",
    "RTL": "AUTO.RTL",
    "LAND": "AUTO.LAND",
    "MISSION": "AUTO.MISSION",
    "TAKEOFF": "AUTO.TAKEOFF",
}
#: the modes the gateway's own commands put PX4 in, per operation kind (`commanded_modes`): takeoff is
#: AUTO.TAKEOFF, after which PX4 holds by itself; every motion (goto, reposition, yaw, hold) is a
#: reposition flown in AUTO.LOITER; a return may end in AUTO.LAND; a mission is AUTO.MISSION, after
#: which PX4 holds (or returns, lands: its last item decides). A pilot's "Hold" during a goto leaves the
#: mode as it was (AUTO.LOITER): PX4 gives no sign of it in the HEARTBEAT.
LOITER_KINDS = frozenset({"goto", "reposition", "move_to_relative", "set_yaw", "hold", "formation",
                          "fleet_climb"})  # fmt: skip
COMMANDED_MODES: dict[str, frozenset[str]] = {
    **{kind: frozenset({"AUTO.LOITER"}) for kind in LOITER_KINDS},
    "takeoff": frozenset({"AUTO.TAKEOFF", "AUTO.LOITER"}),
    "land": frozenset({"AUTO.LAND"}),
    "return_to_launch": frozenset({"AUTO.RTL", "AUTO.LAND"}),
    "mission": frozenset({"AUTO.MISSION"}),
}
SETTLED_MODES: dict[str, frozenset[str]] = {
    "mission": frozenset({"AUTO.MISSION", "AUTO.LOITER", "AUTO.RTL", "AUTO.LAND"}),
}
#: PX4's own names set_flight_mode offers: the autonomous modes (the others need a pilot or offboard)
OFFERED_NATIVE = ("AUTO.LOITER", "AUTO.RTL", "AUTO.LAND", "AUTO.MISSION", "AUTO.TAKEOFF")
#: whether an agent may select each offered mode in the air, and why (PX4's pilot modes MANUAL, ALTCTL,
#: POSCTL, STABILIZED and ACRO need manual control input and are not offered at all)
AIR_MODES: dict[str, AirUse] = {
    "AUTO.LOITER": AirUse(True, "holds where it is and flies only the targets the gateway checked"),
    "AUTO.RTL": AirUse(True, "climbs to RTL_RETURN_ALT (a governed parameter), flies home and lands"),
    "AUTO.LAND": AirUse(True, "descends and lands where it is"),
    "AUTO.MISSION": AirUse(True, "flies the mission the autopilot holds, checked when it starts"),
    "AUTO.TAKEOFF": AirUse(True, "climbs to MIS_TAKEOFF_ALT (a governed parameter) and holds"),
}
#: how PX4's mission feasibility checks begin their text when they reject a mission
MISSION_REJECTIONS = ("mission rejected", "geofence violation for waypoint", "geofence breach on path",
                      "waypoint above maximum", "first waypoint too far")  # fmt: skip
MISSION_VERDICT_S = 1.5
#: arming refusals that go away by themselves while PX4's estimator and GPS settle
ARM_WAIT_TEXTS = ("position estimate", "global position", "local position", "home position", "gps",
                  "estimator", "ekf", "initializ", "initialis", "heading", "attitude")  # fmt: skip
#: commander (arming checks, failsafes: COM_ARM_*, COM_*_ACT, ...), geofence, data link and RC loss,
#: circuit breakers, system ids, battery failsafe thresholds, failure detector
PROTECTED_PARAMS = (
    "COM_*", "GF_*", "NAV_DLL_*", "NAV_RCL_*", "CBRK_*", "MAV_SYS_ID", "MAV_COMP_ID", "BAT*_LOW_THR",
    "BAT*_CRIT_THR", "BAT*_EMERGEN_THR", "FD_*",
)  # fmt: skip
#: parameters that set what PX4 flies at, each mapped to the policy limit it could walk around (metres,
#: m/s) with its documented range
LIMIT_PARAMS: dict[str, ParamLimit] = {
    "MPC_XY_VEL_MAX": ParamLimit("max_speed_mps", "m/s", 1.0, 0.0, 20.0),
    "MPC_XY_CRUISE": ParamLimit("max_speed_mps", "m/s", 1.0, 0.0, 20.0),
    "MPC_VEL_MANUAL": ParamLimit("max_speed_mps", "m/s", 1.0, 0.0, 20.0),
    "MPC_XY_VEL_ALL": ParamLimit("max_speed_mps", "m/s", 1.0, -20.0, 20.0),  # negative: unused
    "MPC_Z_VEL_MAX_UP": ParamLimit("max_vertical_speed_mps", "m/s", 1.0, 0.5, 8.0),
    "MPC_Z_VEL_MAX_DN": ParamLimit("max_vertical_speed_mps", "m/s", 1.0, 0.5, 4.0),
    "MPC_Z_V_AUTO_UP": ParamLimit("max_vertical_speed_mps", "m/s", 1.0, 0.5, 8.0),
    "MPC_Z_V_AUTO_DN": ParamLimit("max_vertical_speed_mps", "m/s", 1.0, 0.5, 4.0),
    "MPC_Z_VEL_ALL": ParamLimit("max_vertical_speed_mps", "m/s", 1.0, -3.0, 8.0),  # negative: unused
    "MPC_TKO_SPEED": ParamLimit("max_vertical_speed_mps", "m/s", 1.0, 1.0, 5.0),
    "MPC_LAND_SPEED": ParamLimit("max_vertical_speed_mps", "m/s", 1.0, 0.6, 4.0),
    "MPC_LAND_CRWL": ParamLimit("max_vertical_speed_mps", "m/s", 1.0, 0.1, 4.0),
    "RTL_RETURN_ALT": ParamLimit("max_altitude_m", "m", 1.0, 0.0, 150.0),
    "RTL_DESCEND_ALT": ParamLimit("max_altitude_m", "m", 1.0, 2.0, 500.0),
    "MIS_TAKEOFF_ALT": ParamLimit("max_altitude_m", "m", 1.0, 0.0, 80.0),
    # governing no limit, written by agents only when GATEWAY_AGENT_PARAM_ALLOW names them, and then only
    # within PX4's own metadata (min/max of parameters.json that the PX4 build ships, PX4 1.16)
    "MPC_ACC_HOR": ParamLimit(None, "m/s^2", 1.0, 2.0, 15.0),
    "MPC_ACC_HOR_MAX": ParamLimit(None, "m/s^2", 1.0, 2.0, 15.0),
    "MPC_ACC_UP_MAX": ParamLimit(None, "m/s^2", 1.0, 2.0, 15.0),
    "MPC_ACC_DOWN_MAX": ParamLimit(None, "m/s^2", 1.0, 2.0, 15.0),
    "MPC_JERK_AUTO": ParamLimit(None, "m/s^3", 1.0, 1.0, 80.0),
    "MPC_JERK_MAX": ParamLimit(None, "m/s^3", 1.0, 0.5, 500.0),
    "NAV_ACC_RAD": ParamLimit(None, "m", 1.0, 0.05, 200.0),
    "MPC_YAWRAUTO_MAX": ParamLimit(None, "deg/s", 1.0, 5.0, 360.0),
}


class PX4:
    """The PX4 dialect."""

    name = "PX4"
    first_user_seq = 0  # no home slot: the user's item 1 is seq 0
    skipped_streams = frozenset({"raw_imu"})
    estimate_from_ekf_report = False
    #: PX4 has its home and local position a moment before its heading: "Preflight Fail: no heading
    #: reference" (1-2 s on SIH, longer on a loaded machine) while arming says only "Resolve system health
    #: failures first". Its pre-arm bit is its arming checks for the current mode (commander's
    #: pre_flight_checks_pass); once it has passed, a later "not armable" is the mode's (LAND), not boot.
    ready_after_prearm_pass = True
    follows_events = True
    arming_mode: str | None = None
    mission_verdict_s = MISSION_VERDICT_S
    return_altitude_params = (("RTL_RETURN_ALT", 1.0),)
    protected_params = PROTECTED_PARAMS
    limit_params: Mapping[str, ParamLimit] = LIMIT_PARAMS

    @property
    def mission_semantics(self) -> MissionSemantics:
        return px4_mission()

    # --- link facts ----------------------------------------------------------------------------------
    def mode_name(self, custom_mode: int, mav_type: int) -> str | None:
        return None  # MAVSDK names PX4's modes

    def position_estimate_ok(self, health: HealthValue, ekf_flags: int | None) -> bool:
        return health.local_position_ok

    # --- flight modes --------------------------------------------------------------------------------
    def mode_names(self) -> list[str]:
        return [name for name in COMMON_MODES if name in COMMON_TO_NATIVE] + list(OFFERED_NATIVE)

    def resolve_mode(self, name: str) -> ModeChoice | None:
        names = native_name(name, COMMON_TO_NATIVE, OFFERED_NATIVE)
        if names is None:
            return None
        wanted, native = names
        main, sub = PX4_MODES[native]
        return ModeChoice(
            wanted,
            native,
            (main << 16) | (sub << 24),
            (1.0, float(main), float(sub)),
            in_air=AIR_MODES.get(native, NOT_MODELLED),
        )

    def native_mode(self, custom_mode: int) -> str:
        main, sub = (custom_mode >> 16) & 0xFF, (custom_mode >> 24) & 0xFF
        for name, (m, s) in PX4_MODES.items():
            if m == main and (s == sub or (s == 0 and main != 4)):
                return name
        return f"MODE_{main}.{sub}"

    def commanded_modes(self, kind: str, *, done: bool = False) -> frozenset[str]:
        if done and kind in SETTLED_MODES:
            return SETTLED_MODES[kind]
        return COMMANDED_MODES.get(kind, frozenset())

    # --- arming and the ground -----------------------------------------------------------------------
    def arming_will_pass(self, complaint: str) -> bool:
        return matches_any(complaint, ARM_WAIT_TEXTS)

    def on_ground(self, telemetry: TelemetryCache, *, fresh: bool = True) -> bool | None:
        read = reader(telemetry, fresh)
        landed = read("landed_state")
        if landed in ("ON_GROUND", "IN_AIR", "TAKING_OFF", "LANDING"):
            return bool(landed == "ON_GROUND")
        in_air = read("in_air")
        return None if in_air is None else not in_air

    async def set_yaw(self, link: LinkOps, heading_deg: float) -> None:
        # PX4 ignores CONDITION_YAW outside missions: a reposition to where it is, with the heading
        pos = link.telemetry.fresh("position")
        if pos is None:
            raise CommandFailed(f"cannot yaw drone '{link.id}': no current position", vehicle_id=link.id)
        goto = link.system.action.goto_location(pos.lat_deg, pos.lon_deg, pos.abs_alt_m, heading_deg)
        await link.call("set yaw", goto)

    # --- missions ------------------------------------------------------------------------------------
    def encode_mission(self, items: list[MissionItem], home: tuple[float, float, float] | None) -> WirePlan:
        return mission.encode(items, home, home_slot=False)

    def decode_mission(self, wire: Sequence[DownloadedItem]) -> tuple[list[MissionItem], WirePlan]:
        return mission.decode(wire, home_slot=False)

    def mission_rejection(self, text: str) -> bool:
        return text.strip().lower().startswith(MISSION_REJECTIONS)

    async def start_mission_on_ground(self, link: LinkOps, arm: Callable[[], Awaitable[None]]) -> None:
        # MISSION first: PX4 refuses the mode for a mission it rejected, before any motor turns
        await link.call("start mission", link.system.mission_raw.start_mission())
        await arm()
