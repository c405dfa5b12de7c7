"""COMMAND_LONG / COMMAND_INT and parameter-protocol handling with ArduCopter's answers."""

from __future__ import annotations

import asyncio
import contextlib
import math
from typing import TYPE_CHECKING

from pymavlink.dialects.v20 import ardupilotmega as mav

from gateway.sim import telemetry
from gateway.sim.mission import FRAME_ABS, FRAME_REL
from gateway.sim.modes import Mode
from gateway.sim.params import ParamError

if TYPE_CHECKING:
    from gateway.sim.host import SimHost
    from gateway.sim.link import Link

ACCEPTED = mav.MAV_RESULT_ACCEPTED
DENIED = mav.MAV_RESULT_DENIED
FAILED = mav.MAV_RESULT_FAILED
UNSUPPORTED = mav.MAV_RESULT_UNSUPPORTED

FORCE_ARM_MAGIC = 2989
PARAM_READ_DELAY_S = 0.1
FORCE_DISARM_MAGIC = 21196

BANNER = ("ArduCopter V4.7.0-dev (82f560b8)", "8d1219c7c4c5404aaa1f6d2a48adfda4", "Frame: QUAD/PLUS")


class CommandHandler:
    def __init__(self, v: SimHost) -> None:
        self.v = v
        self._param_tasks: set[asyncio.Task] = set()

    # ------------------------------------------------------------------------------------------------
    def handle(self, link: Link, msg) -> None:
        is_int = msg.get_type() == "COMMAND_INT"
        cmd = msg.command
        handler = getattr(self, f"_cmd_{cmd}", None)
        after = None
        if handler is None:
            result = UNSUPPORTED
        else:
            try:
                out = handler(link, msg, is_int)
            except (ValueError, OverflowError):  # NaN / absurd parameters where a number is required
                out = FAILED
            result, after = out if isinstance(out, tuple) else (out, None)
        link.send(
            mav.MAVLink_command_ack_message(cmd, result, 0, 0, msg.get_srcSystem(), msg.get_srcComponent())
        )
        if after is not None:
            after()

    # -- arming ---------------------------------------------------------------------------------------
    def _cmd_400(self, link, msg, is_int):  # MAV_CMD_COMPONENT_ARM_DISARM
        v = self.v
        if msg.param1 == 1:
            ok, failures = v.flight.arm(force=round(msg.param2) == FORCE_ARM_MAGIC)
            if not ok:
                for failure in failures:  # one text per failing check, as ArduCopter 4.7
                    v.text(mav.MAV_SEVERITY_CRITICAL, f"Arm: {failure}")
                return FAILED
            return ACCEPTED
        if msg.param1 == 0:
            if not v.armed:
                return ACCEPTED
            if not v.landed and round(msg.param2) != FORCE_DISARM_MAGIC:
                return FAILED
            v.flight.disarm()
            return ACCEPTED
        return FAILED

    # -- modes and navigation -----------------------------------------------------------------------
    def _cmd_176(self, link, msg, is_int):  # MAV_CMD_DO_SET_MODE
        if not int(msg.param1) & mav.MAV_MODE_FLAG_CUSTOM_MODE_ENABLED:
            return ACCEPTED
        ok, _ = self.v.flight.set_mode(int(msg.param2))
        return ACCEPTED if ok else FAILED

    def _cmd_22(self, link, msg, is_int):  # MAV_CMD_NAV_TAKEOFF (p7 = altitude above home, m)
        alt = msg.z if is_int else msg.param7
        return ACCEPTED if self.v.flight.takeoff(alt) else FAILED

    def _cmd_21(self, link, msg, is_int):  # MAV_CMD_NAV_LAND
        return ACCEPTED if self.v.flight.set_mode(Mode.LAND)[0] else FAILED

    def _cmd_20(self, link, msg, is_int):  # MAV_CMD_NAV_RETURN_TO_LAUNCH
        return ACCEPTED if self.v.flight.set_mode(Mode.RTL)[0] else FAILED

    def _cmd_192(self, link, msg, is_int):  # MAV_CMD_DO_REPOSITION
        v = self.v
        change_mode = int(msg.param2) & mav.MAV_DO_REPOSITION_FLAGS_CHANGE_MODE
        if v.mode != Mode.GUIDED and not change_mode:
            return DENIED
        if is_int:
            lat, lon, alt, frame = msg.x / 1e7, msg.y / 1e7, msg.z, msg.frame
        else:  # ArduPilot converts COMMAND_LONG positions with a relative-altitude frame
            lat, lon, alt, frame = msg.param5, msg.param6, msg.param7, mav.MAV_FRAME_GLOBAL_RELATIVE_ALT
        if not (math.isfinite(lat) and math.isfinite(lon)) or not (-90 <= lat <= 90 and -180 <= lon <= 180):
            return DENIED
        if (lat == 0 and lon == 0) or not math.isfinite(alt):
            return DENIED
        if frame not in FRAME_ABS | FRAME_REL:
            return DENIED
        north, east = v.frame.to_ne(lat, lon)
        up = v.flight._alt_to_up(alt, frame)
        if not v.flight.destination_allowed(north, east, up):
            return FAILED  # outside the geofence
        if v.mode != Mode.GUIDED and not v.flight.set_mode(Mode.GUIDED)[0]:
            return FAILED
        yaw = msg.param4 % 360 if math.isfinite(msg.param4) else None
        v.flight.guided_goto(north, east, up, yaw)
        return ACCEPTED

    def _cmd_178(self, link, msg, is_int):  # MAV_CMD_DO_CHANGE_SPEED
        return ACCEPTED if self.v.flight.change_speed(int(msg.param1), msg.param2) else FAILED

    def _cmd_115(self, link, msg, is_int):  # MAV_CMD_CONDITION_YAW
        ok = msg.param4 in (0, 1) and self.v.flight.condition_yaw(
            msg.param1, msg.param2, msg.param3, msg.param4 == 1
        )
        return ACCEPTED if ok else FAILED

    def _cmd_300(self, link, msg, is_int):  # MAV_CMD_MISSION_START
        v = self.v
        if v.mode != Mode.AUTO and not v.flight.set_mode(Mode.AUTO)[0]:
            return FAILED
        if v.armed:
            v.auto_armed = True
            if not v.auto.running:
                v.flight.start_mission()
        return ACCEPTED

    def _cmd_224(self, link, msg, is_int):  # MAV_CMD_DO_SET_MISSION_CURRENT
        seq = int(msg.param1)
        if not self.v.flight.set_mission_current(seq):
            return FAILED
        return ACCEPTED, lambda: link.send(telemetry.mission_current(self.v))

    def _cmd_179(self, link, msg, is_int):  # MAV_CMD_DO_SET_HOME
        v = self.v
        if msg.param1 == 1:
            v.set_home_here()
            return ACCEPTED
        if is_int:
            lat, lon, alt = msg.x / 1e7, msg.y / 1e7, msg.z
        else:
            lat, lon, alt = msg.param5, msg.param6, msg.param7
        if not (math.isfinite(lat) and math.isfinite(lon) and math.isfinite(alt)) or (lat == 0 and lon == 0):
            return FAILED
        v.set_home((lat, lon, alt))
        return ACCEPTED

    def _cmd_193(self, link, msg, is_int):  # MAV_CMD_DO_PAUSE_CONTINUE
        v = self.v
        if v.mode not in (Mode.AUTO, Mode.GUIDED) or not v.flying:
            return FAILED
        if msg.param1 == 0:
            v.flight.target = v.flight.stopping_point()
            if v.mode == Mode.AUTO:
                v.auto.running = False
            return ACCEPTED
        if v.mode == Mode.AUTO and not v.auto.running and not v.auto.complete:
            v.flight.start_mission()
        return ACCEPTED

    def _cmd_246(self, link, msg, is_int):  # MAV_CMD_PREFLIGHT_REBOOT_SHUTDOWN
        v = self.v
        if round(msg.param1) not in (1, 3):
            return UNSUPPORTED  # shutdown / bootloader: not simulated
        if v.armed:
            return FAILED  # ArduPilot refuses to reboot while armed
        return ACCEPTED, v.reboot

    # -- messages and streams -------------------------------------------------------------------------
    def _cmd_511(self, link, msg, is_int):  # MAV_CMD_SET_MESSAGE_INTERVAL
        msg_id = int(msg.param1)
        link.rate_requests.append((msg_id, msg.param2))
        if not self.v.can_build(msg_id):
            self.v.text(mav.MAV_SEVERITY_INFO, f"No ap_message for mavlink id ({msg_id})")
            return DENIED
        link.streams.set_interval(msg_id, msg.param2)
        return ACCEPTED

    def _cmd_510(self, link, msg, is_int):  # MAV_CMD_GET_MESSAGE_INTERVAL
        msg_id = int(msg.param1)
        if not self.v.can_build(msg_id):
            return FAILED
        if msg_id == 0:
            interval_us = 1_000_000
        else:
            interval = link.streams.interval(msg_id)
            interval_us = -1 if interval is None else round(interval * 1e6)
        return ACCEPTED, lambda: link.send(mav.MAVLink_message_interval_message(msg_id, interval_us))

    def _cmd_512(self, link, msg, is_int):  # MAV_CMD_REQUEST_MESSAGE
        msg_id = int(msg.param1)
        if msg_id == mav.MAVLINK_MSG_ID_GPS_GLOBAL_ORIGIN or self.v.can_build(msg_id):
            out = self.v.build(msg_id)
            return ACCEPTED, (lambda: link.send(out)) if out is not None else None
        return FAILED

    def _cmd_520(self, link, msg, is_int):  # MAV_CMD_REQUEST_AUTOPILOT_CAPABILITIES
        out = telemetry.autopilot_version(self.v)
        return ACCEPTED, lambda: link.send(out)

    # ------------------------------------------------------------------------------------------------
    # parameters
    def param_request_list(self, link: Link) -> None:
        v = self.v
        for text in BANNER:
            v.text(mav.MAV_SEVERITY_INFO, text)
        task = asyncio.get_running_loop().create_task(self._send_all_params(link))
        self._param_tasks.add(task)
        task.add_done_callback(self._param_tasks.discard)

    async def _send_all_params(self, link: Link) -> None:
        with contextlib.suppress(Exception):
            for param in self.v.params:
                link.send(self.v.param_value(param, param.index))
                if param.index % 64 == 63:
                    await asyncio.sleep(0.005)

    def param_request_read(self, link: Link, msg) -> None:
        v = self.v
        if msg.param_index >= 0:
            param = v.params.by_index(msg.param_index)
            if param is not None:
                link.send(v.param_value(param, param.index))
            return
        param = v.params.find(_name(msg.param_id))
        if param is not None:  # unknown names get no reply at all, like ArduPilot
            # ArduPilot serves reads by name from a slow queue: ~100 ms (simulated) latency
            reply = v.param_value(param)
            asyncio.get_running_loop().call_later(PARAM_READ_DELAY_S / v.speedup, link.send, reply)

    def param_set(self, link: Link, msg) -> None:
        v = self.v
        name = _name(msg.param_id)
        if v.params.find(name) is None:
            return
        try:
            param = v.params.set(name, msg.param_value)
        except ParamError:
            return
        v.broadcast(v.param_value(param))


def _name(raw) -> str:
    if isinstance(raw, bytes):
        raw = raw.decode("ascii", "replace")
    return raw.split("\0", 1)[0]
