"""Raw MAVLink through mavsdk_grpc's ``mavlink_direct`` plugin, for what MAVSDK's plugins do not give:

* ``LinkFacts``: what the vehicle's HEARTBEATs say (system id, autopilot, vehicle type, the real
  ArduPilot ``custom_mode``, armed) and when the last one came;
* ``CommandChannel``: COMMAND_LONG with its COMMAND_ACK (mode changes by number, CONDITION_YAW,
  MISSION_START, SET_MESSAGE_INTERVAL for every telemetry stream, REQUEST_MESSAGE for ids MAVSDK has no
  setter for). mavsdk_server logs "Received ack for not-existing command" for these ACKs: harmless
  while it has no command of the same id queued (it matches an ACK by command id alone).
"""

from __future__ import annotations

import asyncio
import json
import time
from collections.abc import Awaitable, Callable

from gateway.link.mavsdk_system import MavlinkMessage, System
from gateway.util.json_types import JsonObject

MAV_TYPE_GCS = 6
MAV_AUTOPILOT_INVALID = 8
MAV_MODE_FLAG_SAFETY_ARMED = 128
MAV_RESULT_ACCEPTED = 0
MAV_RESULT_IN_PROGRESS = 5
MAV_RESULT = {
    0: "ACCEPTED",
    1: "TEMPORARILY_REJECTED",
    2: "DENIED",
    3: "UNSUPPORTED",
    4: "FAILED",
    5: "IN_PROGRESS",
    6: "CANCELLED",
}
GCS_COMPID = 190  # mavsdk_server's own component id (--compid)
MAV_AUTOPILOT_ARDUPILOTMEGA = 3
MAV_AUTOPILOT_PX4 = 12


def autopilot_name(mav_autopilot: int) -> str:
    """The HEARTBEAT's MAV_AUTOPILOT as the gateway reports it."""
    if mav_autopilot == MAV_AUTOPILOT_ARDUPILOTMEGA:
        return "ardupilot"
    if mav_autopilot == MAV_AUTOPILOT_PX4:
        return "px4"
    return f"mav_autopilot_{mav_autopilot}"


class LinkFacts:
    """What the raw HEARTBEATs told us about the vehicle in the current session."""

    def __init__(self) -> None:
        self.last_heartbeat: float | None = None  # monotonic
        self.last_heartbeat_wall: float | None = None  # epoch seconds, for display
        self.sysid: int | None = None
        self.sysids_seen: set[int] = set()
        self.autopilot: int | None = None
        self.mav_type: int | None = None
        self.custom_mode: int | None = None
        self.armed: bool | None = None
        self.mode_changed_at: float = 0.0

    def heartbeat(self, system_id: int, fields: JsonObject) -> bool:  # json.loads of mavlink_direct
        """Record one HEARTBEAT; False (ignored) when it comes from another ground station.

        Sets ``sysid_changed`` when the sender's system id differs from the previous one."""
        if fields.get("type") == MAV_TYPE_GCS or fields.get("autopilot") == MAV_AUTOPILOT_INVALID:
            return False
        now = time.monotonic()
        self.last_heartbeat = now
        self.last_heartbeat_wall = time.time()
        self.sysids_seen.add(system_id)
        self.sysid_changed = self.sysid != system_id
        self.sysid = system_id
        self.autopilot = _number(fields, "autopilot")
        self.mav_type = _number(fields, "type")
        custom_mode = _number(fields, "custom_mode")
        if custom_mode != self.custom_mode:
            self.custom_mode = custom_mode
            self.mode_changed_at = now
        self.armed = bool(_number(fields, "base_mode") & MAV_MODE_FLAG_SAFETY_ARMED)
        return True

    sysid_changed = False


class NoAck(Exception):
    """No COMMAND_ACK came back after every attempt."""


class CommandChannel:
    """COMMAND_LONG out through mavlink_direct, COMMAND_ACK back matched by command id.

    ``pump(system)`` must run for the session (it reads the ACKs); ``send`` returns the MAV_RESULT.
    """

    def __init__(self, gcs_sysid: int) -> None:
        self.gcs_sysid = gcs_sysid
        self._waiting: dict[int, list[asyncio.Future[int]]] = {}

    async def pump(self, system: System) -> None:
        async for msg in system.mavlink_direct.message("COMMAND_ACK"):
            fields = json.loads(msg.fields_json)
            waiters = self._waiting.get(int(fields.get("command", -1)))
            while waiters:
                fut = waiters.pop(0)
                if not fut.done():
                    fut.set_result(int(fields.get("result", 4)))
                    break

    def cancel_all(self) -> None:
        for fut in (f for futs in self._waiting.values() for f in futs):
            if not fut.done():
                fut.cancel()
        self._waiting.clear()

    async def send(
        self,
        system: System,
        call: Callable[[Awaitable[object]], Awaitable[object]],
        target: int,
        command: int,
        params: tuple[float, ...],
        *,
        attempts: int = 3,
        wait_s: float = 1.5,
    ) -> int:
        """Send (and resend with a growing ``confirmation``) until an ACK; returns its MAV_RESULT.

        ``call`` wraps the gRPC send (timeout, error mapping). IN_PROGRESS waits for the final ACK."""
        p = [float(x) for x in params] + [0.0] * (7 - len(params))
        fields: dict[str, object] = {
            "target_system": target,
            "target_component": 1,
            "command": command,
            "confirmation": 0,
            **{f"param{i + 1}": p[i] for i in range(7)},
        }
        loop = asyncio.get_running_loop()
        for attempt in range(attempts):
            fields["confirmation"] = attempt
            fut: asyncio.Future[int] = loop.create_future()
            self._waiting.setdefault(command, []).append(fut)
            msg = MavlinkMessage("COMMAND_LONG", self.gcs_sysid, GCS_COMPID, target, 1, json.dumps(fields))
            try:
                await call(system.mavlink_direct.send_message(msg))
                deadline = loop.time() + wait_s
                while True:
                    result = await asyncio.wait_for(asyncio.shield(fut), max(0.05, deadline - loop.time()))
                    if result != MAV_RESULT_IN_PROGRESS:
                        return result
                    fut = loop.create_future()
                    self._waiting.setdefault(command, []).append(fut)
                    deadline = loop.time() + 10.0
            except TimeoutError:
                continue
            finally:
                waiting = self._waiting.get(command, [])
                if fut in waiting:
                    waiting.remove(fut)
        raise NoAck(f"no COMMAND_ACK after {attempts} attempts")


def _number(fields: JsonObject, name: str) -> int:
    """A HEARTBEAT field as mavlink_direct's JSON gives it (0 when it is missing or no number)."""
    value = fields.get(name, 0)
    return int(value) if isinstance(value, int | float) else 0
