"""MAVLink v1/v2 framing for the relay: a byte stream split into frames (bytes that are no frame are
dropped), each checked by CRC where its message is known, and the system a frame is addressed to."""

from __future__ import annotations

from dataclasses import dataclass

from pymavlink.dialects.v20 import ardupilotmega as mavlink
from pymavlink.generator.mavcrc import x25crc

STX_V1 = 0xFE
STX_V2 = 0xFD
#: the longest a partial frame may wait for its tail before its bytes count as noise
MAX_BUFFER = 64 * 1024
_TARGETED = {
    msgid: cls
    for msgid, cls in mavlink.mavlink_map.items()
    if "target_system" in getattr(cls, "fieldnames", ())
}


@dataclass(frozen=True)
class Frame:
    """One MAVLink frame as received, with what routing needs."""

    data: bytes
    sysid: int
    msgid: int


class FrameSplitter:
    """Cuts a byte stream (or datagrams) into MAVLink frames."""

    def __init__(self) -> None:
        self._buf = bytearray()

    def feed(self, data: bytes) -> list[Frame]:
        buf = self._buf
        buf += data
        frames: list[Frame] = []
        while buf:
            start = next((i for i, b in enumerate(buf) if b in (STX_V1, STX_V2)), len(buf))
            del buf[:start]
            if not buf:
                break
            if buf[0] == STX_V2:
                if len(buf) < 10:
                    break
                length = 12 + buf[1] + (13 if buf[2] & 0x01 else 0)
                header, sysid, msgid = 10, buf[5], int.from_bytes(buf[7:10], "little")
            else:
                if len(buf) < 6:
                    break
                length = 8 + buf[1]
                header, sysid, msgid = 6, buf[3], buf[5]
            if len(buf) < length:
                if len(buf) > MAX_BUFFER:
                    del buf[:1]
                    continue
                break
            payload_end = header + buf[1]
            if not _crc_ok(buf, payload_end, msgid):
                del buf[:1]  # a stray start byte: look for the next one
                continue
            frames.append(Frame(bytes(buf[:length]), sysid, msgid))
            del buf[:length]
        return frames


def _crc_ok(buf: bytearray, payload_end: int, msgid: int) -> bool:
    cls = mavlink.mavlink_map.get(msgid)
    if cls is None:
        return True  # not in the dialect: relayed as framed, the receiver checks it
    crc = x25crc(bytes(buf[1:payload_end]))
    crc.accumulate(bytes([cls.crc_extra]))
    return bool(crc.crc == int.from_bytes(buf[payload_end : payload_end + 2], "little"))


_DECODER = mavlink.MAVLink(None)
_DECODER.robust_parsing = True


def target_system(frame: Frame) -> int:
    """The system a frame is addressed to; 0 (everyone) when it has no target or cannot be read."""
    if frame.msgid not in _TARGETED:
        return 0
    try:
        msg = _DECODER.decode(bytearray(frame.data))
    except Exception:  # a frame the dialect cannot unpack (another version of the message): broadcast
        return 0
    return int(getattr(msg, "target_system", 0) or 0)


def decoded(frame: Frame) -> mavlink.MAVLink_message | None:
    """The frame's message as pymavlink reads it; None when the dialect cannot unpack it."""
    if frame.msgid not in mavlink.mavlink_map:
        return None
    try:
        msg: mavlink.MAVLink_message = _DECODER.decode(bytearray(frame.data))
        return msg
    except Exception:  # another version of the message
        return None
