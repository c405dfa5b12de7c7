"""A fenced node's last way to stop the drones it owned: one MAVLink command over the drone's own link.

A node that cannot renew its leases (PostgreSQL unreachable) stops its sidecars, so that no second node
can ever command its drones. Landing or returning is the one command that is safe to send twice (a
drone told to land by two nodes lands), so for an emergency stop the fenced node opens the drone's link
itself for a moment, sends ``MAV_CMD_NAV_LAND`` or ``MAV_CMD_NAV_RETURN_TO_LAUNCH`` (a COMMAND_LONG,
the same for ArduPilot and PX4), or, to hold, asks the drone where it is (``GLOBAL_POSITION_INT``) and
sends ``MAV_CMD_DO_REPOSITION`` there (a COMMAND_INT that switches to GUIDED on ArduPilot, to hold on
PX4: the gateway's own hold), waits briefly for its COMMAND_ACK, and closes the link again, so the
sidecar that the next owner starts finds it free.
"""

from __future__ import annotations

import asyncio
import math
import os
import time
import uuid
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, TypedDict
from urllib.parse import urlparse

from gateway.util.json_types import JsonMapping, JsonObject

# mavutil loads a dialect at import: by default "all" for MAVLink 1, while the gateway speaks MAVLink 2
# with ardupilotmega, the one dialect the container image ships (a missing one makes pymavlink try to
# generate it from XML, and the node dies at start). An operator's own choice is kept.
os.environ.setdefault("MAVLINK_DIALECT", "ardupilotmega")
os.environ.setdefault("MAVLINK20", "1")
from pymavlink import mavutil

from gateway.fleet.operations.views import ActionResult, OperationView

_MAVLINK = mavutil.mavlink
#: the stops a fenced node can send without its sidecar: the verb -> MAV_CMD
STOP_COMMANDS = {
    "land": _MAVLINK.MAV_CMD_NAV_LAND,
    "return_to_launch": _MAVLINK.MAV_CMD_NAV_RETURN_TO_LAUNCH,
    "hold": _MAVLINK.MAV_CMD_DO_REPOSITION,
}
SOURCE_SYSTEM = 245  # a ground station's id, as mavsdk_server uses
SOURCE_COMPONENT = 191  # not mavsdk_server's 190: the autopilot's log tells the two apart
RESEND_S = 0.3
MAV_RESULT = {0: "ACCEPTED", 1: "TEMPORARILY_REJECTED", 2: "DENIED", 3: "UNSUPPORTED", 4: "FAILED",
              5: "IN_PROGRESS", 6: "CANCELLED"}  # fmt: skip


@dataclass(frozen=True)
class StopTarget:
    """What a node remembers of a drone it owned when it fenced itself."""

    vehicle_id: str
    url: str
    sysid: int | None
    epoch: int


class DeviceOptions(TypedDict, total=False):
    """The options of pymavlink's ``mavlink_connection`` a drone's URL sets."""

    baud: int  # a serial link's
    retries: int  # a TCP link's: how often it tries to connect


def pymavlink_device(url: str) -> tuple[str, DeviceOptions, bool]:
    """The drone's URL (mavsdk_server syntax) as pymavlink's device, its options, and whether the link
    must first hear the drone to know where to send (we listen: ``udpin``, ``tcpin``)."""
    parts = urlparse(url)
    if parts.scheme == "serial":
        path, _, baud = (parts.path or parts.netloc).partition(":")
        return path, {"baud": int(baud) if baud else 57600}, False
    where = f"{parts.hostname}:{parts.port}"
    if parts.scheme == "tcpout":
        return f"tcp:{where}", {"retries": 1}, False
    if parts.scheme == "tcpin":
        return f"tcpin:{where}", {}, True
    if parts.scheme == "udpin":
        return f"udpin:{where}", {}, True
    if parts.scheme == "udpout":
        return f"udpout:{where}", {}, False
    raise ValueError(f"url: the scheme must be one of serial, tcpout, tcpin, udpin, udpout; got '{url}'")


def _heard(conn: Any, sysid: int | None, deadline: float) -> int | None:  # Any: pymavlink, untyped
    """The drone's system id once any of its messages arrives (None: nothing before the deadline). A
    link that serves one ground station at a time (a TCP port) has not served this one until it hears
    the drone: until then anything sent would wait in the connection and run whenever it is served."""
    while time.monotonic() < deadline:
        msg = conn.recv_match(blocking=True, timeout=max(0.05, deadline - time.monotonic()))
        if msg is None or msg.get_type() == "BAD_DATA":
            continue
        heard = msg.get_type() == "HEARTBEAT" if sysid is None else msg.get_srcSystem() == sysid
        if heard:
            return int(msg.get_srcSystem())
    return None


def _send(target: StopTarget, command: int, within_s: float, hear_first: bool = False) -> str:
    device, options, listen_first = pymavlink_device(target.url)
    deadline = time.monotonic() + within_s
    conn = mavutil.mavlink_connection(
        device, source_system=SOURCE_SYSTEM, source_component=SOURCE_COMPONENT, **options
    )
    try:
        sysid = target.sysid
        if listen_first or hear_first or sysid is None:
            sysid = _heard(conn, sysid, deadline)
            if sysid is None:
                raise TimeoutError(f"nothing heard from {target.vehicle_id} within {within_s:g} s")
        send = _sender(conn, sysid, command, deadline)
        sent = 0
        while time.monotonic() < deadline:
            send()
            sent += 1
            until = min(deadline, time.monotonic() + RESEND_S)
            while time.monotonic() < until:
                ack = conn.recv_match(type="COMMAND_ACK", blocking=True, timeout=until - time.monotonic())
                if ack is not None and ack.command == command:
                    return MAV_RESULT.get(ack.result, str(ack.result))
        return f"no COMMAND_ACK after {sent} sends"
    finally:
        conn.close()


# Any: pymavlink, its connection untyped
def _sender(conn: Any, sysid: int, command: int, deadline: float) -> Callable[[], object]:
    """How to send ``command``: a COMMAND_LONG, or for a hold a reposition to where the drone is now."""
    if command != STOP_COMMANDS["hold"]:
        return lambda: conn.mav.command_long_send(sysid, 1, command, 0, 0, 0, 0, 0, 0, 0, 0)
    where = None
    while where is None and time.monotonic() < deadline:
        conn.mav.command_long_send(
            sysid, 1, _MAVLINK.MAV_CMD_REQUEST_MESSAGE, 0, _MAVLINK.MAVLINK_MSG_ID_GLOBAL_POSITION_INT,
            0, 0, 0, 0, 0, 0,
        )  # fmt: skip
        where = conn.recv_match(type="GLOBAL_POSITION_INT", blocking=True, timeout=RESEND_S)
    if where is None:
        raise TimeoutError("the drone did not say where it is (GLOBAL_POSITION_INT): nothing sent")
    lat, lon, alt_m = where.lat, where.lon, where.relative_alt / 1000.0
    return lambda: conn.mav.command_int_send(
        sysid, 1, _MAVLINK.MAV_FRAME_GLOBAL_RELATIVE_ALT_INT, command, 0, 0,
        -1, _MAVLINK.MAV_DO_REPOSITION_FLAGS_CHANGE_MODE, 0, math.nan, lat, lon, alt_m,
    )  # fmt: skip


async def send_stop(target: StopTarget, verb: str, within_s: float = 1.5, hear_first: bool = False) -> str:
    """Send the stop ``verb`` (land, return_to_launch, hold) straight to the drone; the autopilot's answer
    (``ACCEPTED``...) or ``no COMMAND_ACK ...``. Raises OSError/TimeoutError when the link cannot be
    opened (another process holds it, the drone is silent). ``hear_first``: send nothing before the
    drone is heard on this connection (its link may be held by another process)."""
    return await asyncio.to_thread(_send, target, STOP_COMMANDS[verb], within_s, hear_first)


def direct_stop_answer(drone_id: str, verb: str, node_id: str, why: str, facts: JsonMapping) -> JsonObject:
    """What a stop sent over the drone's own link by node ``node_id`` answers (``why``: why the node sent
    it itself, with the autopilot's answer): a hold's action, or a land or return's operation, which no
    node tracks (its id ``direct-...``; the drone's state shows when it lands)."""
    said = f"sent over the drone's own link by node {node_id}, {why}"
    if verb == "hold":
        return ActionResult(
            drone_id=drone_id,
            action="hold",
            message=f"hold (a reposition to where it is) {said}",
            facts=facts,
        ).model_dump(mode="json")
    return OperationView(
        operation_id=f"direct-{uuid.uuid4().hex[:12]}",
        drone_id=drone_id,
        kind=verb,
        status="sent",
        progress=0.0,
        message=f"{verb} {said}; not tracked: its state shows when it lands",
        elapsed_s=0.0,
        params=facts,
    ).model_dump(mode="json")
