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

from pymavlink.dialects.v20 import ardupilotmega as mav

from gateway.fleet.policy.mission_check import (
    GLOBAL_FRAMES,
    HARMLESS,
    RELATIVE_FRAMES,
    MissionSemantics,
    Position,
)

RADIUS = 3  # the loiters' radius parameter

ARDUCOPTER_MISSION = MissionSemantics(
    autopilot="ArduCopter",
    positions={
        mav.MAV_CMD_NAV_WAYPOINT: Position("waypoint"),
        mav.MAV_CMD_NAV_LOITER_UNLIM: Position("waypoint", RADIUS),
        mav.MAV_CMD_NAV_LOITER_TURNS: Position("waypoint", RADIUS),
        mav.MAV_CMD_NAV_LOITER_TIME: Position("loiter_time", RADIUS),
        mav.MAV_CMD_NAV_LAND: Position("land"),
        mav.MAV_CMD_NAV_TAKEOFF: Position("takeoff"),
    },
    harmless=HARMLESS,
    position_frames=GLOBAL_FRAMES | RELATIVE_FRAMES,
    speed_types={0: "horizontal", 1: "horizontal", 2: "climb", 3: "descent"},
    jump_offset=0,
)

PX4_MISSION = MissionSemantics(
    autopilot="PX4",
    positions={
        mav.MAV_CMD_NAV_WAYPOINT: Position("waypoint"),
        mav.MAV_CMD_NAV_LOITER_UNLIM: Position("waypoint", RADIUS),
        mav.MAV_CMD_NAV_LOITER_TIME: Position("loiter_time", RADIUS),
        mav.MAV_CMD_NAV_LAND: Position("land"),
        mav.MAV_CMD_NAV_TAKEOFF: Position("takeoff"),
    },
    harmless=HARMLESS,
    position_frames=GLOBAL_FRAMES | RELATIVE_FRAMES,
    speed_any_type="horizontal",
    jump_offset=1,
    zero_position_is_here=False,
)
