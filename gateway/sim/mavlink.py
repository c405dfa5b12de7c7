"""pymavlink MAVLink 2 (ardupilotmega dialect) codec helpers shared by the simulator."""

from __future__ import annotations

from pymavlink.dialects.v20 import ardupilotmega as mav

MAVLink = mav.MAVLink
MAVLinkMessage = mav.MAVLink_message

# Protocol capability bits ArduCopter 4.7 reports (measured: 64495).
CAPABILITIES = 64495


class Codec:
    """One MAVLink 2 encoder (own sequence numbers) and one decoder, for one link."""

    def __init__(self, sysid: int, compid: int = 1) -> None:
        self._enc = mav.MAVLink(None, srcSystem=sysid, srcComponent=compid)
        self._dec = mav.MAVLink(None)
        self._dec.robust_parsing = True

    @property
    def sysid(self) -> int:
        return self._enc.srcSystem

    @sysid.setter
    def sysid(self, value: int) -> None:
        self._enc.srcSystem = value

    def encode(self, msg: MAVLinkMessage) -> bytes:
        buf = msg.pack(self._enc)
        self._enc.seq = (self._enc.seq + 1) % 256
        return buf

    def decode(self, data: bytes) -> list[MAVLinkMessage]:
        try:
            msgs = self._dec.parse_buffer(data)
        except mav.MAVError:
            return []
        return [m for m in (msgs or []) if m.get_type() != "BAD_DATA"]
