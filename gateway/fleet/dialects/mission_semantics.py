"""The mission commands and frames each autopilot's dialect models, with that autopilot's meaning
(`gateway.fleet.policy.mission_check.MissionSemantics`); anything else is unchecked (refused for agents).

ArduCopter (ArduCopter/mode_auto.cpp, AP_Mission): NAV_WAYPOINT stops at the point; NAV_LOITER_UNLIM,
NAV_LOITER_TURNS and NAV_LOITER_TIME carry a radius in param3 (LOITER_TURNS circles it; the others are
counted by it too, whatever the version does with it); DO_CHANGE_SPEED's speed type (param1) sets the
horizontal speed (0 airspeed, 1 ground speed), the climb rate (2) or the descent rate (3); DO_JUMP's
param1 is the sequence number with home at 0, which is the user's item number. NAV_SPLINE_WAYPOINT
(its curve leaves the straight legs), NAV_GUIDED_ENABLE, NAV_ATTITUDE_TIME, NAV_SCRIPT_TIME,
DO_AUX_FUNCTION, DO_SET_MODE, DO_PARACHUTE, NAV_CONTINUE_AND_CHANGE_ALT and any other command are not
modelled; terrain frames neither (the gateway knows no terrain).

PX4 (navigator/mission_block.cpp, navigator_main.cpp): a multicopter hovers at a loiter's point (the
radius is for fixed wings) but the radius is counted all the same; DO_CHANGE_SPEED's speed, of any speed
type, becomes the cruise (horizontal) speed; DO_JUMP's param1 is the 0-based sequence number (user item
param1 + 1). NAV_LOITER_TURNS is not flown by a PX4 multicopter: unchecked.
"""

from __future__ import annotations

import functools

from gateway.fleet.policy.mission_check import MissionSemantics, Position

RADIUS = 3  # the loiters' radius parameter

# The tables are built when a mission is first judged: pymavlink's dialect, which names the commands
# and frames, is a large module (about 10 MiB) that a gateway flying no mission never needs.


@functools.cache
def harmless() -> frozenset[int]:
    """Harmless on both autopilots: yaw, waits, region of interest, camera and gimbal items."""
    from pymavlink.dialects.v20 import ardupilotmega as mav

    return frozenset({
        mav.MAV_CMD_CONDITION_YAW, mav.MAV_CMD_CONDITION_DELAY, mav.MAV_CMD_CONDITION_DISTANCE,
        mav.MAV_CMD_NAV_DELAY, mav.MAV_CMD_DO_SET_ROI, mav.MAV_CMD_DO_SET_ROI_LOCATION,
        mav.MAV_CMD_DO_SET_ROI_NONE, mav.MAV_CMD_DO_SET_ROI_WPNEXT_OFFSET, mav.MAV_CMD_DO_DIGICAM_CONFIGURE,
        mav.MAV_CMD_DO_DIGICAM_CONTROL, mav.MAV_CMD_DO_MOUNT_CONFIGURE, mav.MAV_CMD_DO_MOUNT_CONTROL,
        mav.MAV_CMD_DO_SET_CAM_TRIGG_DIST, mav.MAV_CMD_DO_SET_CAM_TRIGG_INTERVAL,
        mav.MAV_CMD_DO_GIMBAL_MANAGER_PITCHYAW, mav.MAV_CMD_IMAGE_START_CAPTURE,
        mav.MAV_CMD_IMAGE_STOP_CAPTURE,
        mav.MAV_CMD_VIDEO_START_CAPTURE, mav.MAV_CMD_VIDEO_STOP_CAPTURE, mav.MAV_CMD_DO_CONTROL_VIDEO,
    })  # fmt: skip


@functools.cache
def position_frames() -> frozenset[int]:
    """Frames of position items: altitude above mean sea level or above home (plain and _INT)."""
    from pymavlink.dialects.v20 import ardupilotmega as mav

    return frozenset({
        mav.MAV_FRAME_GLOBAL, mav.MAV_FRAME_GLOBAL_INT,
        mav.MAV_FRAME_GLOBAL_RELATIVE_ALT, mav.MAV_FRAME_GLOBAL_RELATIVE_ALT_INT,
    })  # fmt: skip


@functools.cache
def shared_positions() -> dict[int, Position]:
    """Position items both autopilots fly the same way (ArduCopter adds NAV_LOITER_TURNS)."""
    from pymavlink.dialects.v20 import ardupilotmega as mav

    return {
        mav.MAV_CMD_NAV_WAYPOINT: Position("waypoint"),
        mav.MAV_CMD_NAV_LOITER_UNLIM: Position("waypoint", RADIUS),
        mav.MAV_CMD_NAV_LOITER_TIME: Position("loiter_time", RADIUS),
        mav.MAV_CMD_NAV_LAND: Position("land"),
        mav.MAV_CMD_NAV_TAKEOFF: Position("takeoff"),
    }


@functools.cache
def arducopter_mission() -> MissionSemantics:
    from pymavlink.dialects.v20 import ardupilotmega as mav

    return MissionSemantics(
        autopilot="ArduCopter",
        positions=shared_positions() | {mav.MAV_CMD_NAV_LOITER_TURNS: Position("waypoint", RADIUS)},
        harmless=harmless(),
        position_frames=position_frames(),
        speed_types={0: "horizontal", 1: "horizontal", 2: "climb", 3: "descent"},
        jump_offset=0,
    )


@functools.cache
def px4_mission() -> MissionSemantics:
    return MissionSemantics(
        autopilot="PX4",
        positions=shared_positions(),
        harmless=harmless(),
        position_frames=position_frames(),
        speed_any_type="horizontal",
        jump_offset=1,
        zero_position_is_here=False,
    )
