"""Builders of the telemetry messages a simulated ArduCopter streams, from the vehicle's true state."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from pymavlink.dialects.v20 import ardupilotmega as mav

from gateway.sim.mavlink import CAPABILITIES

if TYPE_CHECKING:
    from gateway.sim.host import SimHost

S = mav  # MAV_SYS_STATUS_* bit names live in the dialect module

# SYS_STATUS bit sets measured on ArduCopter SITL (present / enabled / healthy evolve with the boot).
_BASE = (
    S.MAV_SYS_STATUS_SENSOR_3D_GYRO
    | S.MAV_SYS_STATUS_SENSOR_3D_ACCEL
    | S.MAV_SYS_STATUS_SENSOR_3D_MAG
    | S.MAV_SYS_STATUS_SENSOR_ABSOLUTE_PRESSURE
    | S.MAV_SYS_STATUS_SENSOR_ANGULAR_RATE_CONTROL
    | S.MAV_SYS_STATUS_SENSOR_ATTITUDE_STABILIZATION
    | S.MAV_SYS_STATUS_SENSOR_YAW_POSITION
    | S.MAV_SYS_STATUS_SENSOR_MOTOR_OUTPUTS
    | S.MAV_SYS_STATUS_SENSOR_RC_RECEIVER
    | S.MAV_SYS_STATUS_SENSOR_BATTERY
    | S.MAV_SYS_STATUS_PREARM_CHECK
    | S.MAV_SYS_STATUS_SENSOR_PROPULSION
)
_POS_CTRL = S.MAV_SYS_STATUS_SENSOR_Z_ALTITUDE_CONTROL | S.MAV_SYS_STATUS_SENSOR_XY_POSITION_CONTROL
_ALWAYS_PRESENT = (
    _BASE | _POS_CTRL | S.MAV_SYS_STATUS_GEOFENCE | S.MAV_SYS_STATUS_AHRS | S.MAV_SYS_STATUS_LOGGING
)
_HEALTH_EXTRA = S.MAV_SYS_STATUS_GEOFENCE | S.MAV_SYS_STATUS_LOGGING | S.MAV_SYS_STATUS_SENSOR_PROXIMITY


def sys_status(v: SimHost) -> mav.MAVLink_message:
    t = v.t
    present = _ALWAYS_PRESENT | S.MAV_SYS_STATUS_TERRAIN
    enabled = _BASE | S.MAV_SYS_STATUS_TERRAIN | S.MAV_SYS_STATUS_AHRS
    health = (_BASE & ~S.MAV_SYS_STATUS_PREARM_CHECK & ~S.MAV_SYS_STATUS_SENSOR_3D_MAG) | _HEALTH_EXTRA
    health |= S.MAV_SYS_STATUS_TERRAIN | S.MAV_SYS_STATUS_AHRS
    if t >= v.timeline.mag_ok:
        health |= S.MAV_SYS_STATUS_SENSOR_3D_MAG
    if v.gps_detected:
        present |= S.MAV_SYS_STATUS_SENSOR_GPS
        enabled |= S.MAV_SYS_STATUS_SENSOR_GPS
        if v.gps_has_fix:
            health |= S.MAV_SYS_STATUS_SENSOR_GPS
    if v.origin_set:
        enabled |= _POS_CTRL
        if v.position_ok:
            health |= _POS_CTRL
    if v.params.get("FENCE_ENABLE") > 0:
        enabled |= S.MAV_SYS_STATUS_GEOFENCE
    if v.flight.fence_breaches:
        health &= ~S.MAV_SYS_STATUS_GEOFENCE
    if v.armed:
        enabled |= S.MAV_SYS_STATUS_LOGGING
    if v.boot_state.prearm_bit():
        health |= S.MAV_SYS_STATUS_PREARM_CHECK
    if v.battery.failsafe:
        health &= ~S.MAV_SYS_STATUS_SENSOR_BATTERY
    b = v.battery
    return mav.MAVLink_sys_status_message(
        present, enabled, health, 0, round(b.voltage * 1000), round(b.current * 100), round(b.remaining_pct),
        0, 0, 0, 0, 0, 0, 0, 0, 0,
    )  # fmt: skip


def gps_raw_int(v: SimHost) -> mav.MAVLink_message:
    if not v.gps_has_fix:
        return mav.MAVLink_gps_raw_int_message(
            round(v.t * 1e6) if v.gps_detected else 0, 1 if v.gps_detected else 0, 0, 0, 0,
            65535, 65535, 0, 0, 0, 0, 0, 0, 0, 0, 0,
        )  # fmt: skip
    lat, lon, alt = v.gps_position()
    cog = math.degrees(math.atan2(v.body.ve, v.body.vn)) % 360 if v.body.ground_speed > 0.2 else 0
    return mav.MAVLink_gps_raw_int_message(
        round(v.t * 1e6), 6, round(lat * 1e7), round(lon * 1e7), round(alt * 1000),
        121, 200, round(v.body.ground_speed * 100), round(cog * 100), 10,
        round(alt * 1000), 300, 300, 0, 0, 0,
    )  # fmt: skip


def global_position_int(v: SimHost) -> mav.MAVLink_message:
    if not v.origin_set:
        return mav.MAVLink_global_position_int_message(v.time_boot_ms, 0, 0, 0, 0, 0, 0, 0, 0)
    lat, lon, alt = v.position()
    home_alt = v.home[2] if v.home else v.frame.alt0
    b = v.body
    return mav.MAVLink_global_position_int_message(
        v.time_boot_ms, round(lat * 1e7), round(lon * 1e7), round(alt * 1000), round((alt - home_alt) * 1000),
        round(b.vn * 100), round(b.ve * 100), round(-b.vu * 100), round(b.yaw * 100) % 36000,
    )  # fmt: skip


def local_position_ned(v: SimHost) -> mav.MAVLink_message | None:
    if not v.origin_set:
        return None
    b = v.body
    return mav.MAVLink_local_position_ned_message(v.time_boot_ms, b.north, b.east, -b.up, b.vn, b.ve, -b.vu)


def attitude(v: SimHost) -> mav.MAVLink_message:
    roll, pitch = v.body.attitude()
    roll += v.noise(0.0005)
    pitch += v.noise(0.0005)
    yaw = math.radians(((v.body.yaw + 180.0) % 360.0) - 180.0)
    return mav.MAVLink_attitude_message(
        v.time_boot_ms, roll, pitch, yaw, v.noise(0.0002), v.noise(0.0002), math.radians(v.body.yaw_rate)
    )


def vfr_hud(v: SimHost) -> mav.MAVLink_message:
    _, _, alt = v.position()
    throttle = 0 if not v.armed or v.landed else 39
    return mav.MAVLink_vfr_hud_message(
        v.body.ground_speed, v.body.ground_speed, round(v.body.yaw) % 360, throttle, alt, v.body.vu
    )


def home_position(v: SimHost) -> mav.MAVLink_message | None:
    if v.home is None:
        return None
    lat, lon, alt = v.home
    north, east = v.frame.to_ne(lat, lon)
    return mav.MAVLink_home_position_message(
        round(lat * 1e7), round(lon * 1e7), round(alt * 1000), north, east, -(alt - v.frame.alt0),
        [math.nan] * 4, 0.0, 0.0, 0.0, round(v.t * 1e6),
    )  # fmt: skip


def gps_global_origin(v: SimHost) -> mav.MAVLink_message | None:
    if not v.origin_set:
        return None
    f = v.frame
    return mav.MAVLink_gps_global_origin_message(
        round(f.lat0 * 1e7), round(f.lon0 * 1e7), round(f.alt0 * 1000), round(v.t * 1e6)
    )


def extended_sys_state(v: SimHost) -> mav.MAVLink_message:
    return mav.MAVLink_extended_sys_state_message(mav.MAV_VTOL_STATE_MC, v.landed_state())


def battery_status(v: SimHost) -> mav.MAVLink_message:
    b = v.battery
    cells = [round(b.voltage * 1000)] + [65535] * 9
    return mav.MAVLink_battery_status_message(
        0, 0, 0, 32767, cells, round(b.current * 100), round(b.consumed_mah), round(b.consumed_wh * 36),
        round(b.remaining_pct), 0, b.charge_state(), [0, 0, 0, 0], 0, 0,
    )  # fmt: skip


def mission_current(v: SimHost) -> mav.MAVLink_message:
    total = max(0, v.mission.count() - 1)
    if total == 0:
        state = mav.MISSION_STATE_NO_MISSION
    elif v.auto.complete:
        state = mav.MISSION_STATE_COMPLETE
    elif v.mode_is_auto and v.auto.running:
        state = mav.MISSION_STATE_ACTIVE
    elif v.auto.started:
        state = mav.MISSION_STATE_PAUSED
    else:
        state = mav.MISSION_STATE_NOT_STARTED
    return mav.MAVLink_mission_current_message(v.auto.current, total, state, 1 if v.mode_is_auto else 0)


def raw_imu(v: SimHost) -> mav.MAVLink_message:
    n = v.noise
    acc = (round(n(3)), round(n(3)), round(-1000 + n(3)))
    gyro = (round(n(2)), round(n(2)), round(n(2)))
    mag = (230 + round(n(2)), 10 + round(n(2)), 400 + round(n(2)))
    return mav.MAVLink_raw_imu_message(round(v.t * 1e6), *acc, *gyro, *mag, 0, 0)


def scaled_imu(v: SimHost, msg_id: int) -> mav.MAVLink_message:
    n = v.noise
    cls = mav.MAVLink_scaled_imu2_message if msg_id == 116 else mav.MAVLink_scaled_imu3_message
    return cls(
        v.time_boot_ms, round(n(3)), round(n(3)), round(-1000 + n(3)), round(n(2)), round(n(2)), round(n(2)),
        230, 10, 400, 0,
    )  # fmt: skip


def scaled_pressure(v: SimHost, msg_id: int) -> mav.MAVLink_message:
    _, _, alt = v.position()
    press = 1013.25 * (1 - 2.25577e-5 * alt) ** 5.25588
    cls = mav.MAVLink_scaled_pressure_message if msg_id == 29 else mav.MAVLink_scaled_pressure2_message
    return cls(v.time_boot_ms, press + v.noise(0.01), 0.0, 3100, 0)


def rc_channels(v: SimHost) -> mav.MAVLink_message:
    chans = [1500, 1500, 1000, 1500] + [1000] * 4 + [0] * 10
    return mav.MAVLink_rc_channels_message(v.time_boot_ms, 16, *chans, 255)


def servo_output_raw(v: SimHost) -> mav.MAVLink_message:
    pwm = 1000 if not v.armed else (1100 if v.landed else 1500)
    outs = [pwm] * 4 + [0] * 12
    return mav.MAVLink_servo_output_raw_message(round(v.t * 1e6) & 0xFFFFFFFF, 0, *outs)


def simstate(v: SimHost) -> mav.MAVLink_message:
    roll, pitch = v.body.attitude()
    lat, lon, _ = v.position()
    return mav.MAVLink_simstate_message(
        roll, pitch, math.radians(((v.body.yaw + 180) % 360) - 180), 0.0, 0.0, -9.80665, 0.0, 0.0,
        math.radians(v.body.yaw_rate), round(lat * 1e7), round(lon * 1e7),
    )  # fmt: skip


def ahrs(v: SimHost) -> mav.MAVLink_message:
    return mav.MAVLink_ahrs_message(0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)


def ahrs2(v: SimHost) -> mav.MAVLink_message:
    roll, pitch = v.body.attitude()
    lat, lon, alt = v.position()
    yaw = math.radians(((v.body.yaw + 180) % 360) - 180)
    return mav.MAVLink_ahrs2_message(roll, pitch, yaw, alt, round(lat * 1e7), round(lon * 1e7))


def system_time(v: SimHost) -> mav.MAVLink_message:
    return mav.MAVLink_system_time_message(round(v.wall_epoch_us()), v.time_boot_ms)


def ekf_status_report(v: SimHost) -> mav.MAVLink_message:
    flags = 0
    if v.t >= v.timeline.ekf_init:
        flags |= mav.EKF_ATTITUDE | mav.EKF_VELOCITY_VERT | mav.EKF_POS_VERT_ABS | mav.EKF_POS_VERT_AGL
    if v.position_ok:
        flags |= (
            mav.EKF_VELOCITY_HORIZ
            | mav.EKF_POS_HORIZ_REL
            | mav.EKF_POS_HORIZ_ABS
            | mav.EKF_PRED_POS_HORIZ_REL
            | mav.EKF_PRED_POS_HORIZ_ABS
        )
    return mav.MAVLink_ekf_status_report_message(flags, 0.01, 0.02, 0.01, 0.01, 0.0, 0.0)


def vibration(v: SimHost) -> mav.MAVLink_message:
    return mav.MAVLink_vibration_message(round(v.t * 1e6), 0.01, 0.01, 0.01, 0, 0, 0)


def power_status(v: SimHost) -> mav.MAVLink_message:
    return mav.MAVLink_power_status_message(5000, 0, 0)


def meminfo(v: SimHost) -> mav.MAVLink_message:
    return mav.MAVLink_meminfo_message(65535, 65535, 131072)


def nav_controller_output(v: SimHost) -> mav.MAVLink_message:
    bearing, dist, alt_err = v.nav_output()
    return mav.MAVLink_nav_controller_output_message(
        0.0, 0.0, round(bearing), round(bearing), min(65535, round(dist)), alt_err, 0.0, 0.0
    )


def autopilot_version(v: SimHost) -> mav.MAVLink_message:
    version = 0x04070000 if v.params.firmware == "4.7" else 0x04060000
    uid2 = list(v.uid2)
    return mav.MAVLink_autopilot_version_message(
        CAPABILITIES, version, 0, 0, 0, list(b"82f560b8"), [0] * 8, [0] * 8, 0, 0, 0, uid2,
    )  # fmt: skip


def attitude_quaternion(v: SimHost) -> mav.MAVLink_message:
    roll, pitch = v.body.attitude()
    yaw = math.radians(v.body.yaw)
    cr, sr = math.cos(roll / 2), math.sin(roll / 2)
    cp, sp = math.cos(pitch / 2), math.sin(pitch / 2)
    cy, sy = math.cos(yaw / 2), math.sin(yaw / 2)
    q = (cr * cp * cy + sr * sp * sy, sr * cp * cy - cr * sp * sy, cr * sp * cy + sr * cp * sy,
         cr * cp * sy - sr * sp * cy)  # fmt: skip
    return mav.MAVLink_attitude_quaternion_message(
        v.time_boot_ms, *q, 0.0, 0.0, math.radians(v.body.yaw_rate), [0.0, 0.0, 0.0, 0.0]
    )


def scaled_imu1(v: SimHost) -> mav.MAVLink_message:
    n = v.noise
    return mav.MAVLink_scaled_imu_message(
        v.time_boot_ms, round(n(3)), round(n(3)), round(-1000 + n(3)), round(n(2)), round(n(2)), round(n(2)),
        230, 10, 400, 0,
    )  # fmt: skip


def highres_imu(v: SimHost) -> mav.MAVLink_message:
    n = v.noise
    _, _, alt = v.position()
    press = 1013.25 * (1 - 2.25577e-5 * alt) ** 5.25588
    return mav.MAVLink_highres_imu_message(
        round(v.t * 1e6), n(0.03), n(0.03), -9.80665 + n(0.03), n(0.002), n(0.002), n(0.002),
        0.23, 0.01, 0.4, press, 0.0, alt, 31.0, 0x1FFF, 0,
    )  # fmt: skip


def position_target_global_int(v: SimHost) -> mav.MAVLink_message | None:
    target = v.flight.target
    if v.mode != 4 or target is None or not v.flying:  # only while GUIDED has a position target
        return None
    lat, lon = v.frame.to_latlon(target[0], target[1])
    alt = v.frame.alt0 + target[2]
    return mav.MAVLink_position_target_global_int_message(
        v.time_boot_ms, mav.MAV_FRAME_GLOBAL, 0xFF8, round(lat * 1e7), round(lon * 1e7), alt, *([0.0] * 8)
    )


def fence_status(v: SimHost) -> mav.MAVLink_message | None:
    if v.params.get("FENCE_ENABLE") <= 0:
        return None
    breaches = v.flight.fence_breaches
    kind = mav.FENCE_BREACH_MAXALT if breaches & 1 else (mav.FENCE_BREACH_BOUNDARY if breaches else 0)
    return mav.MAVLink_fence_status_message(1 if breaches else 0, 0, kind, 0, 0)


# Message ids ArduCopter knows (SET_MESSAGE_INTERVAL is ACCEPTED) but that a SITL copter without the
# matching hardware or state never sends: third baro, GPS2/RTK, rangefinder, wind, terrain, ESC, RPM ...
KNOWN_SILENT = frozenset({35, 83, 85, 124, 127, 128, 132, 133, 136, 143, 168, 194, 226, 246, 11030, 12964})

# msg id -> builder(vehicle) (builders return None when the message is not available yet).
BUILDERS = {
    1: sys_status,
    26: scaled_imu1,
    31: attitude_quaternion,
    87: position_target_global_int,
    105: highres_imu,
    162: fence_status,
    2: system_time,
    24: gps_raw_int,
    27: raw_imu,
    29: lambda v: scaled_pressure(v, 29),
    30: attitude,
    32: local_position_ned,
    33: global_position_int,
    36: servo_output_raw,
    42: mission_current,
    49: gps_global_origin,
    62: nav_controller_output,
    65: rc_channels,
    74: vfr_hud,
    116: lambda v: scaled_imu(v, 116),
    125: power_status,
    129: lambda v: scaled_imu(v, 129),
    137: lambda v: scaled_pressure(v, 137),
    147: battery_status,
    148: autopilot_version,
    152: meminfo,
    163: ahrs,
    164: simstate,
    178: ahrs2,
    193: ekf_status_report,
    241: vibration,
    242: home_position,
    245: extended_sys_state,
}
