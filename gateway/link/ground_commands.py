"""What a ground station on the relay sends that commands the drone, as opposed to what only reads it.

A ground station sharing the drone's MAVLink through the relay (`gateway.link.relay`) asks for data all
the time (heartbeats, parameter and mission downloads, message rates, REQUEST_MESSAGE); a few messages
act on the drone: a new target, a mission change, a parameter write, a command. The relay notes each of
those (`gateway.link.contract.GroundCommand`), and the takeover watch reads them: while the gateway
flies the drone, any is a takeover (`gateway.fleet.policy.takeover`). Mode switches (SET_MODE,
MAV_CMD_DO_SET_MODE) are left to the HEARTBEAT the watch already judges, which names both modes.

Reading those frames takes pymavlink's dialect module (about 6 MiB of the gateway's memory): the relay
imports this module only when a ground station's frame comes.
"""

from __future__ import annotations

from pymavlink.dialects.v20 import ardupilotmega as mavlink

from gateway.link.contract import GroundCommand
from gateway.link.mavlink_frames import Frame

__all__ = ["GroundCommand", "acting", "not_a_ground_station"]

_DECODER = mavlink.MAVLink(None)
_DECODER.robust_parsing = True

#: messages that act on the drone whatever their fields say
ACTING_MESSAGES = frozenset(
    {
        mavlink.MAVLINK_MSG_ID_SET_POSITION_TARGET_GLOBAL_INT,
        mavlink.MAVLINK_MSG_ID_SET_POSITION_TARGET_LOCAL_NED,
        mavlink.MAVLINK_MSG_ID_SET_ATTITUDE_TARGET,
        mavlink.MAVLINK_MSG_ID_MANUAL_CONTROL,
        mavlink.MAVLINK_MSG_ID_RC_CHANNELS_OVERRIDE,
        mavlink.MAVLINK_MSG_ID_MISSION_SET_CURRENT,
        mavlink.MAVLINK_MSG_ID_MISSION_COUNT,  # a mission upload starts
        mavlink.MAVLINK_MSG_ID_MISSION_CLEAR_ALL,
        mavlink.MAVLINK_MSG_ID_MISSION_ITEM,
        mavlink.MAVLINK_MSG_ID_MISSION_ITEM_INT,
        mavlink.MAVLINK_MSG_ID_PARAM_SET,
        mavlink.MAVLINK_MSG_ID_SET_HOME_POSITION,
        mavlink.MAVLINK_MSG_ID_SET_GPS_GLOBAL_ORIGIN,
    }
)
#: messages whose ``command`` field says whether they act
COMMAND_MESSAGES = frozenset({mavlink.MAVLINK_MSG_ID_COMMAND_LONG, mavlink.MAVLINK_MSG_ID_COMMAND_INT})
#: MAV_CMD names by number, for the words of a takeover
_COMMAND_NAMES = {number: entry.name for number, entry in mavlink.enums["MAV_CMD"].items()}
#: commands that only ask for data (every MAV_CMD_REQUEST_* and MAV_CMD_GET_*, the message rates, the
#: pre-arm checks), or switch the mode (judged through the HEARTBEAT instead)
NOT_ACTING_COMMANDS = frozenset(
    {
        number
        for number, name in _COMMAND_NAMES.items()
        if name.startswith(("MAV_CMD_REQUEST_", "MAV_CMD_GET_"))
    }
    | {
        mavlink.MAV_CMD_SET_MESSAGE_INTERVAL,
        mavlink.MAV_CMD_RUN_PREARM_CHECKS,
        mavlink.MAV_CMD_DO_SET_MODE,
    }
)


def decoded(frame: Frame) -> mavlink.MAVLink_message | None:
    """The frame's message as pymavlink reads it; None when the dialect cannot unpack it."""
    if frame.msgid not in mavlink.mavlink_map:
        return None
    try:
        msg: mavlink.MAVLink_message = _DECODER.decode(bytearray(frame.data))
        return msg
    except Exception:  # another version of the message
        return None


def acting(frame: Frame, vehicle_sysids: set[int]) -> str | None:
    """What ``frame`` (from a ground station) does to the drone, in words; None when it only reads, is
    addressed to another system, or switches the mode."""
    if frame.msgid not in ACTING_MESSAGES and frame.msgid not in COMMAND_MESSAGES:
        return None
    msg = decoded(frame)
    if msg is None:
        return None
    target = int(getattr(msg, "target_system", 0) or 0)
    if target and vehicle_sysids and target not in vehicle_sysids:
        return None  # to another system (a camera, a gimbal, another drone): not this drone
    name = str(msg.get_type())
    if frame.msgid in COMMAND_MESSAGES:
        command = int(getattr(msg, "command", 0))
        if command in NOT_ACTING_COMMANDS:
            return None
        return f"{name} {_COMMAND_NAMES.get(command, str(command))}"
    return name


def not_a_ground_station(frame: Frame, vehicle_sysids: set[int]) -> str | None:
    """Why the peer of a ground station endpoint that sent ``frame`` is not a ground station (another
    vehicle: a HEARTBEAT from an autopilot; the drone itself, looped back: its own system id), in words;
    None when the frame says nothing against it."""
    if frame.sysid in vehicle_sysids:
        return f"its peer sends this drone's own system id {frame.sysid} back (a loop to the drone's link)"
    if frame.msgid != mavlink.MAVLINK_MSG_ID_HEARTBEAT:
        return None
    msg = decoded(frame)
    autopilot = int(getattr(msg, "autopilot", mavlink.MAV_AUTOPILOT_INVALID))
    if msg is None or autopilot == mavlink.MAV_AUTOPILOT_INVALID:
        return None
    name = (
        mavlink.enums["MAV_AUTOPILOT"][autopilot].name
        if autopilot in mavlink.enums["MAV_AUTOPILOT"]
        else autopilot
    )
    return f"its peer is another vehicle (system {frame.sysid} sends an autopilot's HEARTBEAT, {name})"


def is_heartbeat(frame: Frame) -> bool:
    return bool(frame.msgid == mavlink.MAVLINK_MSG_ID_HEARTBEAT)
