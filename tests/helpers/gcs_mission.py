"""Another ground station stores a mission on the autopilot (pymavlink on the autopilot's second port: the
simulator's ``--gcs-base-port``, ArduCopter SITL's SERIAL1, PX4's GCS instance), as Mission Planner or
QGroundControl would: MISSION_COUNT, the autopilot asks for each item, MISSION_ITEM_INT, MISSION_ACK."""

from __future__ import annotations

import time
from dataclasses import dataclass

from pymavlink import mavutil

from tests.helpers.timing import scaled

mav = mavutil.mavlink


@dataclass(frozen=True)
class GcsItem:
    """One mission item as a ground station writes it (x, y in degrees; z in metres in ``frame``)."""

    command: int
    lat: float = 0.0
    lon: float = 0.0
    alt: float = 0.0
    frame: int = mav.MAV_FRAME_GLOBAL_RELATIVE_ALT
    params: tuple[float, float, float, float] = (0.0, 0.0, 0.0, 0.0)


#: the link per address, kept for the test run: PX4's GCS instance answers the first partner it heard
#: (its address and port), not a new one
_LINKS: dict[str, mavutil.mavfile] = {}


def connect(url: str) -> tuple[mavutil.mavfile, int]:
    """A pymavlink link on ``url`` (tcpout://host:port, tcp:host:port, udpout:...; opened once, kept)
    once the autopilot is heard; the autopilot's system id."""
    address = f"tcp:{url.removeprefix('tcpout://')}" if url.startswith("tcpout://") else url
    link = _LINKS.get(address)
    if link is None:
        link = _LINKS[address] = mavutil.mavlink_connection(address, source_system=250, source_component=190)
    deadline = time.monotonic() + scaled(20)
    while True:  # PX4's GCS instance answers once it heard us: say hello until it does
        link.mav.heartbeat_send(mav.MAV_TYPE_GCS, mav.MAV_AUTOPILOT_INVALID, 0, 0, 0)
        hb = link.recv_match(type="HEARTBEAT", blocking=True, timeout=1.0)
        if hb is not None and hb.type != mav.MAV_TYPE_GCS:
            return link, hb.get_srcSystem()
        if time.monotonic() > deadline:
            raise AssertionError(f"no HEARTBEAT from the autopilot on {address}")


def upload(url: str, items: list[GcsItem], *, home_slot: bool = True) -> None:
    """Store ``items`` (user items 1..N; with ``home_slot`` a home placeholder goes first, as ArduPilot
    expects) and wait for the autopilot's MISSION_ACK ACCEPTED."""
    link, target = connect(url)
    while link.recv_match(blocking=False) is not None:  # what an earlier upload left unread
        pass
    wire = ([GcsItem(mav.MAV_CMD_NAV_WAYPOINT, frame=mav.MAV_FRAME_GLOBAL)] if home_slot else []) + items
    link.mav.mission_count_send(target, 1, len(wire), mav.MAV_MISSION_TYPE_MISSION)
    deadline = time.monotonic() + scaled(30)
    while time.monotonic() < deadline:
        wanted = ["MISSION_REQUEST", "MISSION_REQUEST_INT", "MISSION_ACK"]
        msg = link.recv_match(type=wanted, blocking=True, timeout=1.0)
        if msg is None:
            continue
        if msg.get_type() == "MISSION_ACK" and msg.target_system == 250:
            if msg.type != mav.MAV_MISSION_ACCEPTED:
                raise AssertionError(f"the autopilot refused the mission: MISSION_ACK {msg.type}")
            return
        if msg.get_type() == "MISSION_ACK" or msg.target_system != 250:
            continue  # meant for another ground station (the gateway)
        item = wire[msg.seq]
        p1, p2, p3, p4 = item.params
        link.mav.mission_item_int_send(
            target, 1, msg.seq, item.frame, item.command, 0, 1, p1, p2, p3, p4,
            round(item.lat * 1e7), round(item.lon * 1e7), item.alt, mav.MAV_MISSION_TYPE_MISSION,
        )  # fmt: skip
    raise AssertionError("the autopilot never acknowledged the mission")
