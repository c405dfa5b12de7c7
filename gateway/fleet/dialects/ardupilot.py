"""ArduPilot (ArduCopter): what it does its own way.

* Modes are HEARTBEAT custom mode numbers; MAVSDK misnames them (OFFBOARD for GUIDED, HOLD for LOITER),
  so the HEARTBEAT's number is named here. HOLD / LOITER is flown as a GUIDED reposition to where the
  vehicle is: ArduCopter's LOITER and ALT_HOLD sink without RC throttle (MAVSDK#2039, ArduPilot#29458).
* Arm in GUIDED: ``is_armable`` is evaluated for the current mode, and arming in STABILIZE succeeds
  before the EKF uses GPS, after which a GUIDED takeoff fails and the vehicle disarms.
* "Ready" waits for EKF_STATUS_REPORT to show an absolute horizontal position (not constant-position
  mode): "PreArm: Need Position Estimate" comes well after GPS and home are fine.
* Missions: seq 0 is HOME (the autopilot overwrites it), user items are 1..N; MISSION_CURRENT.total
  leaves home out; MISSION_START while armed on the ground takes off (mission_raw.start_mission only
  switches to AUTO). A rejected mission fails the upload itself (MISSION_ACK error).
* The RTL altitude is RTL_ALT_M in metres from 4.7 on, RTL_ALT in centimetres before. It refuses
  HIGHRES_IMU and ODOMETRY streams (RAW_IMU instead).
"""

from __future__ import annotations

from collections.abc import Awaitable, Callable, Mapping, Sequence

from gateway.fleet.dialects.base import LinkOps, matches_any, reader
from gateway.fleet.dialects.mission_semantics import arducopter_mission
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

#: every ArduCopter mode, by HEARTBEAT custom_mode number (for naming what the vehicle reports)
ARDUCOPTER_MODES: dict[str, int] = {
    "STABILIZE": 0, "ACRO": 1, "ALT_HOLD": 2, "AUTO": 3, "GUIDED": 4, "LOITER": 5, "RTL": 6, "CIRCLE": 7,
    "LAND": 9, "DRIFT": 11, "SPORT": 13, "FLIP": 14, "AUTOTUNE": 15, "POSHOLD": 16, "BRAKE": 17, "THROW": 18,
    "AVOID_ADSB": 19, "GUIDED_NOGPS": 20, "SMART_RTL": 21, "FLOWHOLD": 22, "FOLLOW": 23, "ZIGZAG": 24,
    "SYSTEMID": 25, "AUTOROTATE": 26, "AUTO_RTL": 27, "TURTLE": 28,
}  # fmt: skip
ARDUCOPTER_MODE_NAMES = {number: name for name, number in ARDUCOPTER_MODES.items()}
#: common name -> ArduCopter mode (TAKEOFF: none; takeoff is a GUIDED command here)
COMMON_TO_NATIVE: dict[str, str] = {
    "HOLD": "GUIDED",
    "GUIDED": "GUIDED",
    "RTL": "RTL",
    "LAND": "LAND",
    "MISSION": "AUTO",
}
#: ArduCopter's own modes that set_flight_mode offers besides the common ones: the autonomous ones, and
#: the pilot modes an operator may want on the ground (agents may not select those in the air:
#: GATEWAY_MODE_DENY_IN_AIR). Modes that need sticks or special frames (ACRO, FLIP, THROW, TURTLE,
#: AUTOROTATE, ...) are left out.
OFFERED_NATIVE = ("BRAKE", "SMART_RTL", "CIRCLE", "STABILIZE", "ALT_HOLD", "POSHOLD")
#: whether an agent may select each offered mode in the air, and why. ArduCopter's pilot modes read the
#: throttle stick even under a GCS: without RC (SITL, a companion link) the throttle reads low and the
#: copter sinks to the ground and stays there armed (measured on SITL for LOITER, ALT_HOLD and CIRCLE:
#: 30 m to the ground 515 m from home). Mode::has_manual_throttle / ModeCircle::run use
#: get_pilot_desired_climb_rate.
_STICKS = "reads the pilot's throttle and sticks: without RC input it sinks to the ground and stays armed"
AIR_MODES: dict[str, AirUse] = {
    "GUIDED": AirUse(True, "holds where it is and flies only the targets the gateway checked"),
    "RTL": AirUse(True, "climbs to the return altitude (a governed parameter), flies home and lands"),
    "LAND": AirUse(True, "descends and lands where it is"),
    "AUTO": AirUse(True, "flies the mission the autopilot holds, checked when it starts"),
    "BRAKE": AirUse(True, "stops and holds position and altitude without RC input"),
    "SMART_RTL": AirUse(True, "retraces the path it flew, within the limits, back home"),
    "CIRCLE": AirUse(False, f"{_STICKS} (like LOITER); its circle's centre lies one CIRCLE_RADIUS ahead"),
    "STABILIZE": AirUse(False, _STICKS),
    "ALT_HOLD": AirUse(False, _STICKS),
    "POSHOLD": AirUse(False, _STICKS),
    "LOITER": AirUse(False, _STICKS),
}
#: ArduCopter's CIRCLE: AC_Circle puts the centre one radius ahead of the stopping point (the far side is
#: two radii away); CIRCLE_RADIUS in cm up to 4.6, CIRCLE_RADIUS_M in m from 4.7 (which answers the old
#: name with "does not exist" at once: the old name is tried first)
CIRCLE_RADIUS_PARAMS = (("CIRCLE_RADIUS", 100.0), ("CIRCLE_RADIUS_M", 1.0))
#: MAV_TYPE values flown by ArduCopter (quad, coaxial, heli, hexa, octo, tri, dodeca, deca)
COPTER_TYPES = frozenset({2, 3, 4, 13, 14, 15, 29, 35})
#: the modes the gateway's own commands put ArduCopter in, per operation kind (`commanded_modes`): every
#: motion is a GUIDED command (hold too), a landing LAND, a return RTL (which may end in LAND), a mission
#: AUTO (its RTL and LAND items are flown in AUTO)
GUIDED_KINDS = frozenset({"takeoff", "goto", "reposition", "move_to_relative", "set_yaw", "hold", "formation",
                          "fleet_climb"})  # fmt: skip
COMMANDED_MODES: dict[str, frozenset[str]] = {
    **{kind: frozenset({"GUIDED"}) for kind in GUIDED_KINDS},
    "land": frozenset({"LAND"}),
    "return_to_launch": frozenset({"RTL", "LAND"}),
    "mission": frozenset({"AUTO"}),
}
EKF_POS_HORIZ_ABS = 16
EKF_CONST_POS_MODE = 128
MAV_CMD_CONDITION_YAW = 115
MAV_CMD_MISSION_START = 300
#: arming refusals that go away by themselves while the autopilot initialises (retried within the cap)
ARM_WAIT_TEXTS = ("position estimate", "ekf", "gps", "waiting", "initialis", "initializ", "heading", "gyros",
                  "accels", "ahrs", "home", "alt estimate")  # fmt: skip
#: arming checks, fences, failsafes, battery failsafe thresholds, system ids (4.x and 4.7 names)
PROTECTED_PARAMS = (
    "ARMING_*", "FENCE_*", "FS_*", "BATT*_FS_*", "BATT*_LOW_*", "BATT*_CRT_*", "SYSID_*", "MAV_SYSID",
    "MAV_GCS_SYSID", "BRD_SAFETY*", "FLTMODE_GCSBLOCK", "RC_FS_*", "THR_FS*",
)  # fmt: skip
#: parameters that set what ArduCopter flies at, each mapped to the policy limit it could walk around, in
#: its own units with its documented range (both naming generations: 4.7 moved several to metres)
LIMIT_PARAMS: dict[str, ParamLimit] = {
    "WPNAV_SPEED": ParamLimit("max_speed_mps", "cm/s", 100.0, 20.0, 2000.0),
    "RTL_SPEED": ParamLimit("max_speed_mps", "cm/s", 100.0, 0.0, 2000.0),  # 0: WPNAV_SPEED
    "RTL_SPEED_MS": ParamLimit("max_speed_mps", "m/s", 1.0, 0.0, 20.0),
    "LOIT_SPEED": ParamLimit("max_speed_mps", "cm/s", 100.0, 20.0, 3500.0),
    "LOIT_SPEED_MS": ParamLimit("max_speed_mps", "m/s", 1.0, 0.2, 35.0),
    "WPNAV_SPEED_UP": ParamLimit("max_vertical_speed_mps", "cm/s", 100.0, 10.0, 1000.0),
    "WPNAV_SPEED_DN": ParamLimit("max_vertical_speed_mps", "cm/s", 100.0, 10.0, 500.0),
    "PILOT_SPEED_UP": ParamLimit("max_vertical_speed_mps", "cm/s", 100.0, 50.0, 500.0),
    "PILOT_SPEED_DN": ParamLimit("max_vertical_speed_mps", "cm/s", 100.0, 0.0, 500.0),  # 0: _UP
    "LAND_SPEED": ParamLimit("max_vertical_speed_mps", "cm/s", 100.0, 30.0, 200.0),
    "LAND_SPD_MS": ParamLimit("max_vertical_speed_mps", "m/s", 1.0, 0.3, 2.0),
    "LAND_SPEED_HIGH": ParamLimit("max_vertical_speed_mps", "cm/s", 100.0, 0.0, 500.0),
    "LAND_SPD_HIGH_MS": ParamLimit("max_vertical_speed_mps", "m/s", 1.0, 0.0, 5.0),
    "RTL_ALT": ParamLimit("max_altitude_m", "cm", 100.0, 0.0, 300000.0),  # 0: return at the altitude flown
    "RTL_ALT_M": ParamLimit("max_altitude_m", "m", 1.0, 0.0, 3000.0),
    "RTL_ALT_FINAL": ParamLimit("max_altitude_m", "cm", 100.0, 0.0, 1000.0),
    "RTL_ALT_FINAL_M": ParamLimit("max_altitude_m", "m", 1.0, 0.0, 10.0),
    # mode_rtl.cpp compute_return_target: target = max(RTL_ALT, current altitude + RTL_CLIMB_MIN)
    "RTL_CLIMB_MIN": ParamLimit("max_altitude_m", "cm", 100.0, 0.0, 3000.0, "added"),
    "RTL_CLIMB_MIN_M": ParamLimit("max_altitude_m", "m", 1.0, 0.0, 30.0, "added"),
    "PILOT_TKOFF_ALT": ParamLimit("max_altitude_m", "cm", 100.0, 0.0, 1000.0),
    # AC_Circle: the centre lies one radius ahead of where CIRCLE starts, so the far side is two away
    "CIRCLE_RADIUS": ParamLimit("max_distance_m", "cm", 100.0, 0.0, 200000.0, "diameter"),
    "CIRCLE_RADIUS_M": ParamLimit("max_distance_m", "m", 1.0, 0.0, 2000.0, "diameter"),
    # governing no limit, written by agents only when GATEWAY_AGENT_PARAM_ALLOW names them, and then
    # only within the @Range of ArduPilot's parameter docs (AC_WPNav.cpp, AC_Loiter.cpp, AC_Circle.cpp,
    # Parameters.cpp; the 4.7 metre names are the centimetre ranges / 100)
    "WPNAV_ACCEL": ParamLimit(None, "cm/s/s", 1.0, 50.0, 500.0),
    "WPNAV_ACCEL_Z": ParamLimit(None, "cm/s/s", 1.0, 50.0, 500.0),
    "WPNAV_ACCEL_C": ParamLimit(None, "cm/s/s", 1.0, 0.0, 500.0),
    "WPNAV_JERK": ParamLimit(None, "m/s/s/s", 1.0, 1.0, 20.0),
    "WPNAV_RADIUS": ParamLimit(None, "cm", 1.0, 5.0, 1000.0),
    "WP_YAW_BEHAVIOR": ParamLimit(None, "", 1.0, 0.0, 3.0),
    "LOIT_ACC_MAX": ParamLimit(None, "cm/s/s", 1.0, 100.0, 981.0),
    "LOIT_ACC_MAX_M": ParamLimit(None, "m/s/s", 1.0, 1.0, 9.81),
    "LOIT_BRK_ACCEL": ParamLimit(None, "cm/s/s", 1.0, 25.0, 250.0),
    "LOIT_BRK_ACC_M": ParamLimit(None, "m/s/s", 1.0, 0.25, 2.5),
    "LOIT_BRK_JERK": ParamLimit(None, "cm/s/s/s", 1.0, 500.0, 5000.0),
    "LOIT_BRK_JRK_M": ParamLimit(None, "m/s/s/s", 1.0, 5.0, 50.0),
    "LOIT_BRK_DELAY": ParamLimit(None, "s", 1.0, 0.0, 2.0),
    "CIRCLE_RATE": ParamLimit(None, "deg/s", 1.0, -90.0, 90.0),
}


class ArduPilot:
    """The ArduCopter dialect (also used for a link whose autopilot is not known yet)."""

    name = "ArduCopter"
    first_user_seq = 1  # home holds seq 0
    # no HIGHRES_IMU or ODOMETRY; no BATTERY_STATUS either: MAVSDK takes the battery from SYS_STATUS,
    # which ArduPilot fills from the same first battery monitor (one message a second fewer)
    skipped_streams = frozenset({"imu", "odometry", "battery"})
    #: MAVSDK's health says "local position ok" once the EKF has an origin, seconds before it uses GPS
    #: (the autopilot refuses to arm until then): EKF_STATUS_REPORT says when it does
    estimate_from_ekf_report = True
    #: ArduPilot's pre-arm bit is evaluated for the current mode and lags a mode change (STABILIZE arms
    #: before GUIDED): the EKF report decides instead
    ready_after_prearm_pass = False
    follows_events = False
    arming_mode: str | None = "GUIDED"
    mission_verdict_s = 0.0
    #: 4.7 replaced RTL_ALT (centimetres) with RTL_ALT_M (metres); it answers RTL_ALT with "does not
    #: exist" at once, while older versions do not answer RTL_ALT_M at all: the old name is tried first
    return_altitude_params = (("RTL_ALT", 100.0), ("RTL_ALT_M", 1.0))
    protected_params = PROTECTED_PARAMS
    limit_params: Mapping[str, ParamLimit] = LIMIT_PARAMS

    @property
    def mission_semantics(self) -> MissionSemantics:
        return arducopter_mission()

    # --- link facts ----------------------------------------------------------------------------------
    def mode_name(self, custom_mode: int, mav_type: int) -> str | None:
        if mav_type not in COPTER_TYPES:
            return None  # not a copter: MAVSDK's names
        return ARDUCOPTER_MODE_NAMES.get(custom_mode, f"MODE_{custom_mode}")

    def position_estimate_ok(self, health: HealthValue, ekf_flags: int | None) -> bool:
        if ekf_flags is None:
            return health.local_position_ok
        return bool(ekf_flags & EKF_POS_HORIZ_ABS) and not ekf_flags & EKF_CONST_POS_MODE

    # --- flight modes --------------------------------------------------------------------------------
    def mode_names(self) -> list[str]:
        common = [name for name in COMMON_MODES if name in COMMON_TO_NATIVE]
        return common + [name for name in OFFERED_NATIVE if name not in common]

    def resolve_mode(self, name: str) -> ModeChoice | None:
        names = native_name(name, COMMON_TO_NATIVE, OFFERED_NATIVE)
        if names is None:
            return None
        wanted, native = names
        number = ARDUCOPTER_MODES[native]
        pattern = CIRCLE_RADIUS_PARAMS if native == "CIRCLE" else ()
        return ModeChoice(
            wanted,
            native,
            number,
            (1.0, float(number)),
            in_air=AIR_MODES.get(native, NOT_MODELLED),
            pattern_radius=pattern,
            pattern_reach=2.0 if pattern else 0.0,
        )

    def native_mode(self, custom_mode: int) -> str:
        return ARDUCOPTER_MODE_NAMES.get(custom_mode, f"MODE_{custom_mode}")

    def commanded_modes(self, kind: str, *, done: bool = False) -> frozenset[str]:
        return COMMANDED_MODES.get(kind, frozenset())

    # --- arming and the ground -----------------------------------------------------------------------
    def arming_will_pass(self, complaint: str) -> bool:
        return matches_any(complaint, ARM_WAIT_TEXTS)

    def on_ground(self, telemetry: TelemetryCache, *, fresh: bool = True) -> bool | None:
        in_air = reader(telemetry, fresh)("in_air")
        return None if in_air is None else not in_air

    async def set_yaw(self, link: LinkOps, heading_deg: float) -> None:
        # CONDITION_YAW: p1 angle, p2 rate (0 = default), p3 direction (0 = shortest), p4 0 = absolute
        await link.command_long(MAV_CMD_CONDITION_YAW, heading_deg, 0, 0, 0, what="set yaw")

    # --- missions ------------------------------------------------------------------------------------
    def encode_mission(self, items: list[MissionItem], home: tuple[float, float, float] | None) -> WirePlan:
        return mission.encode(items, home, home_slot=True)

    def decode_mission(self, wire: Sequence[DownloadedItem]) -> tuple[list[MissionItem], WirePlan]:
        return mission.decode(wire, home_slot=True)

    def mission_rejection(self, text: str) -> bool:
        return False  # ArduPilot refuses in the MISSION_ACK: the upload itself fails

    async def start_mission_on_ground(self, link: LinkOps, arm: Callable[[], Awaitable[None]]) -> None:
        await arm()  # in GUIDED
        await link.command_long(MAV_CMD_MISSION_START, 0, 0, what="start mission")
