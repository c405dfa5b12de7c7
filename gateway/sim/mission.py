"""Mission storage and the MAVLink mission microservice as ArduPilot implements it.

* Upload: MISSION_COUNT -> the vehicle asks with MISSION_REQUEST (#40) for each seq -> MISSION_ACK.
  An item with the wrong seq gets MISSION_ACK INVALID_SEQUENCE (the transfer goes on). A count above
  the storage (``max_items``, counting home; unlimited unless set) is refused at once with MISSION_ACK
  NO_SPACE and "Only N items are supported", as ArduPilot's MissionItemProtocol does; the stored
  mission stays as it was.
* Seq 0 is always HOME: whatever is uploaded there is replaced; downloads return the current home.
* Download: MISSION_REQUEST_LIST -> MISSION_COUNT -> MISSION_REQUEST(_INT) -> MISSION_ITEM(_INT).

`AutoState` is how far AUTO has got through the stored mission (run by `gateway.sim.auto`).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, fields, replace

from pymavlink.dialects.v20 import ardupilotmega as mav

from gateway.util.mission_item import ItemCommand, ItemInt

# Accepted frames for items: absolute, relative to home, terrain (treated as relative).
FRAME_ABS = {mav.MAV_FRAME_GLOBAL, mav.MAV_FRAME_GLOBAL_INT}
FRAME_REL = {
    mav.MAV_FRAME_GLOBAL_RELATIVE_ALT,
    mav.MAV_FRAME_GLOBAL_RELATIVE_ALT_INT,
    mav.MAV_FRAME_GLOBAL_TERRAIN_ALT,
    mav.MAV_FRAME_GLOBAL_TERRAIN_ALT_INT,
}
TYPE_MISSION = mav.MAV_MISSION_TYPE_MISSION


@dataclass(frozen=True)
class Item(ItemInt):
    """One stored mission item, in MISSION_ITEM_INT terms (x/y in degE7)."""

    @property
    def lat(self) -> float:
        return self.x / 1e7

    @property
    def lon(self) -> float:
        return self.y / 1e7

    @classmethod
    def from_msg(cls, msg) -> Item:
        if msg.get_type() == "MISSION_ITEM":
            x, y = round(msg.x * 1e7), round(msg.y * 1e7)
        else:
            x, y = int(msg.x), int(msg.y)
        # the command part's fields are named as MAVLink names them in both messages
        command = {f.name: getattr(msg, f.name) for f in fields(ItemCommand)}
        return cls(**command, x=x, y=y, z=msg.z, autocontinue=msg.autocontinue)


@dataclass
class _Upload:
    link: object
    count: int
    mission_type: int
    items: list[Item]
    next_seq: int = 0
    last_request_t: float = 0.0
    retries: int = 0


class MissionStore:
    """The stored mission (index 0 = home) and the protocol handlers that change it."""

    UPLOAD_RETRY_S = 0.5
    UPLOAD_TIMEOUT_RETRIES = 8

    def __init__(
        self,
        home: Callable[[], tuple[float, float, float]],
        send: Callable[[object, object], None],
        on_uploaded: Callable[[int], None],
        text: Callable[[int, str], None],
    ) -> None:
        self._home = home  # (lat, lon, alt_amsl)
        self._send = send  # (link, msg)
        self._on_uploaded = on_uploaded
        self._text = text
        self.items: list[Item] = [Item(command=mav.MAV_CMD_NAV_WAYPOINT, frame=mav.MAV_FRAME_GLOBAL)]
        self.other: dict[int, list[Item]] = {mav.MAV_MISSION_TYPE_FENCE: [], mav.MAV_MISSION_TYPE_RALLY: []}
        self.max_items: int | None = None  # mission storage, home included; None: unlimited
        self._upload: _Upload | None = None
        self.now = 0.0

    # -- access -------------------------------------------------------------------------------------
    def count(self) -> int:
        return len(self.items)

    def item(self, seq: int) -> Item:
        if seq == 0:
            lat, lon, alt = self._home()
            return Item(
                command=mav.MAV_CMD_NAV_WAYPOINT,
                frame=mav.MAV_FRAME_GLOBAL,
                x=round(lat * 1e7),
                y=round(lon * 1e7),
                z=alt,
            )
        return self.items[seq]

    def replace(self, items: list[Item]) -> None:
        self.items = [self.items[0], *items[1:]] if items else [self.items[0]]

    # -- protocol -----------------------------------------------------------------------------------
    def handle(self, link, msg) -> bool:
        """Handle a mission-protocol message; returns False if the message is not one of them."""
        kind = msg.get_type()
        handler = {
            "MISSION_COUNT": self._on_count,
            "MISSION_ITEM_INT": self._on_item,
            "MISSION_ITEM": self._on_item,
            "MISSION_REQUEST_LIST": self._on_request_list,
            "MISSION_REQUEST_INT": self._on_request,
            "MISSION_REQUEST": self._on_request,
            "MISSION_CLEAR_ALL": self._on_clear_all,
            "MISSION_ACK": lambda _link, _msg: None,
        }.get(kind)
        if handler is None:
            return False
        handler(link, msg)
        return True

    def _ack(self, link, msg, result: int, mission_type: int) -> None:
        self._send(
            link,
            mav.MAVLink_mission_ack_message(
                msg.get_srcSystem(), msg.get_srcComponent(), result, mission_type
            ),
        )

    def _request(self, up: _Upload, target_sys: int, target_comp: int) -> None:
        self._send(
            up.link,
            mav.MAVLink_mission_request_message(target_sys, target_comp, up.next_seq, up.mission_type),
        )
        up.last_request_t = self.now

    def _on_count(self, link, msg) -> None:
        mission_type = getattr(msg, "mission_type", 0)
        limit = self.max_items if mission_type == TYPE_MISSION else None
        if limit is not None and msg.count > limit:
            self._ack(link, msg, mav.MAV_MISSION_NO_SPACE, mission_type)
            self._text(mav.MAV_SEVERITY_WARNING, f"Only {limit} items are supported")
            return
        if msg.count == 0:
            self._store(mission_type, [])
            self._ack(link, msg, mav.MAV_MISSION_ACCEPTED, mission_type)
            return
        self._upload = _Upload(link, msg.count, mission_type, [])
        self._upload_target = (msg.get_srcSystem(), msg.get_srcComponent())
        self._request(self._upload, *self._upload_target)

    def _on_item(self, link, msg) -> None:
        up = self._upload
        mission_type = getattr(msg, "mission_type", 0)
        if up is None or up.link is not link or mission_type != up.mission_type:
            self._ack(link, msg, mav.MAV_MISSION_DENIED, mission_type)
            return
        if msg.seq != up.next_seq:
            self._ack(link, msg, mav.MAV_MISSION_INVALID_SEQUENCE, mission_type)
            return
        up.items.append(Item.from_msg(msg))
        up.next_seq += 1
        up.retries = 0
        if up.next_seq < up.count:
            self._request(up, msg.get_srcSystem(), msg.get_srcComponent())
            return
        self._upload = None
        self._store(mission_type, up.items)
        self._ack(link, msg, mav.MAV_MISSION_ACCEPTED, mission_type)
        if mission_type == TYPE_MISSION:
            self._text(mav.MAV_SEVERITY_INFO, "Flight plan received")

    def _store(self, mission_type: int, items: list[Item]) -> None:
        if mission_type == TYPE_MISSION:
            self.replace(items)
            self._on_uploaded(len(self.items))
        else:
            self.other[mission_type] = list(items)

    def _on_request_list(self, link, msg) -> None:
        mission_type = getattr(msg, "mission_type", 0)
        count = len(self.items) if mission_type == TYPE_MISSION else len(self.other.get(mission_type, []))
        self._send(
            link,
            mav.MAVLink_mission_count_message(
                msg.get_srcSystem(), msg.get_srcComponent(), count, mission_type
            ),
        )

    def _on_request(self, link, msg) -> None:
        mission_type = getattr(msg, "mission_type", 0)
        items = self.items if mission_type == TYPE_MISSION else self.other.get(mission_type, [])
        if not 0 <= msg.seq < len(items):
            self._ack(link, msg, mav.MAV_MISSION_INVALID_SEQUENCE, mission_type)
            return
        item = self.item(msg.seq) if mission_type == TYPE_MISSION else items[msg.seq]
        ts, tc = msg.get_srcSystem(), msg.get_srcComponent()
        if msg.get_type() == "MISSION_REQUEST_INT":
            out = mav.MAVLink_mission_item_int_message(
                ts, tc, msg.seq, item.frame, item.command, 0, item.autocontinue,
                item.param1, item.param2, item.param3, item.param4, item.x, item.y, item.z, mission_type,
            )  # fmt: skip
        else:
            out = mav.MAVLink_mission_item_message(
                ts, tc, msg.seq, item.frame, item.command, 0, item.autocontinue,
                item.param1, item.param2, item.param3, item.param4, item.lat, item.lon, item.z, mission_type,
            )  # fmt: skip
        self._send(link, out)

    def _on_clear_all(self, link, msg) -> None:
        mission_type = getattr(msg, "mission_type", 0)
        self._store(mission_type, [])
        self._ack(link, msg, mav.MAV_MISSION_ACCEPTED, mission_type)

    def tick(self, now: float) -> None:
        """Re-request a lost item, and give up on a stalled upload (like ArduPilot's timeout)."""
        self.now = now
        up = self._upload
        if up is None or now - up.last_request_t < self.UPLOAD_RETRY_S:
            return
        up.retries += 1
        if up.retries > self.UPLOAD_TIMEOUT_RETRIES:
            self._upload = None
            return
        self._request(up, *self._upload_target)


def with_home(item: Item, lat: float, lon: float, alt: float) -> Item:
    return replace(item, x=round(lat * 1e7), y=round(lon * 1e7), z=alt)


@dataclass
class AutoState:
    """Mission execution state (the part MISSION_CURRENT reports)."""

    current: int = 0
    running: bool = False
    started: bool = False
    complete: bool = False
    phase: str = "idle"  # idle | goto | hold | land | rtl | loiter_unlim
    hold_until: float = 0.0
