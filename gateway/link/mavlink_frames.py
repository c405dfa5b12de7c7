"""MAVLink v1/v2 framing for the relay: a byte stream split into frames (bytes that are no frame are
dropped), each checked by CRC where its message is known, and the system a frame is addressed to.

What a message's frame needs for both (its CRC_EXTRA, where its ``target_system`` lies) is read from
`gateway.link.mavlink_messages`, not from pymavlink's dialect module: a drone relayed only for its raw
flight log (every drone, by default) costs the gateway no dialect. The CRC is the standard library's
(`x25`), not pymavlink's, which loads its package and the fastcrc extension (0.5 MiB of the gateway's
RSS with its first drone) for the same sum at the same speed."""

from __future__ import annotations

import binascii
from dataclasses import dataclass

from gateway.link.mavlink_messages import MESSAGES

STX_V1 = 0xFE
STX_V2 = 0xFD
#: the longest a partial frame may wait for its tail before its bytes count as noise
MAX_BUFFER = 64 * 1024
#: bytes before the payload: MAVLink 1, MAVLink 2
HEADER_V1 = 6
HEADER_V2 = 10


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
                header, sysid, msgid = HEADER_V2, buf[5], int.from_bytes(buf[7:10], "little")
            else:
                if len(buf) < 6:
                    break
                length = 8 + buf[1]
                header, sysid, msgid = HEADER_V1, buf[3], buf[5]
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


#: each byte with its bits in reverse order
_REVERSED = bytes(int(f"{i:08b}"[::-1], 2) for i in range(256))


def x25(data: bytes) -> int:
    """MAVLink's checksum (CRC-16/MCRF4XX: X.25's polynomial, bits least significant first, from
    0xFFFF, no final XOR) of ``data``: ``binascii.crc_hqx`` is the same polynomial most significant bit
    first, so it sums the bytes with their bits reversed and the sum is reversed back."""
    crc = binascii.crc_hqx(data.translate(_REVERSED), 0xFFFF)
    return (_REVERSED[crc & 0xFF] << 8) | _REVERSED[crc >> 8]


def _crc_ok(buf: bytearray, payload_end: int, msgid: int) -> bool:
    known = MESSAGES.get(msgid)
    if known is None:
        return True  # not in the dialect: relayed as framed, the receiver checks it
    crc = x25(bytes(buf[1:payload_end]) + bytes((known[0],)))
    return crc == int.from_bytes(buf[payload_end : payload_end + 2], "little")


def target_system(frame: Frame) -> int:
    """The system a frame is addressed to; 0 (everyone) when it has no target. A MAVLink 2 payload
    ends before its trailing zero bytes, so a target beyond its end is 0; a MAVLink 1 frame of a
    message whose target is a MAVLink 2 extension (COMMAND_ACK) has none."""
    known = MESSAGES.get(frame.msgid)
    if known is None or known[1] < 0:
        return 0
    data = frame.data
    header = HEADER_V2 if data[0] == STX_V2 else HEADER_V1
    offset = known[1]
    return data[header + offset] if offset < data[1] else 0
