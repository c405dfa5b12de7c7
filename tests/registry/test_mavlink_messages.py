"""The relay's table of MAVLink messages (gateway/link/mavlink_messages.py) against pymavlink's dialect:
the module is what the generator writes from the installed pymavlink, and for every message with a
target, the relay's CRC check passes and its target_system is what pymavlink decodes."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest
from pymavlink.dialects.v20 import ardupilotmega as mavlink
from pymavlink.generator.mavcrc import x25crc

from gateway.link.mavlink_frames import FrameSplitter, target_system, x25
from gateway.link.mavlink_messages import MESSAGES

ROOT = Path(__file__).resolve().parents[2]
TARGETED = sorted(
    (msgid, cls) for msgid, cls in mavlink.mavlink_map.items() if "target_system" in cls.fieldnames
)


def test_the_table_is_what_the_installed_pymavlink_says() -> None:
    done = subprocess.run(
        [sys.executable, str(ROOT / "scripts" / "gen_mavlink_messages.py"), "--check"],
        capture_output=True,
        text=True,
        check=False,
    )
    assert done.returncode == 0, done.stdout + done.stderr
    assert set(MESSAGES) == set(mavlink.mavlink_map)


def v2_frame(msgid: int, cls: Any, payload: bytes) -> bytes:
    header = bytes([0xFD, len(payload), 0, 0, 0, 1, 1]) + msgid.to_bytes(3, "little")
    crc = x25crc(header[1:] + payload)
    crc.accumulate(bytes([cls.crc_extra]))
    return header + payload + crc.crc.to_bytes(2, "little")


@pytest.mark.parametrize(("msgid", "cls"), TARGETED, ids=[cls.msgname for _, cls in TARGETED])
def test_target_system_is_what_pymavlink_decodes(msgid: int, cls: Any) -> None:
    size = cls.unpacker.size
    payload = bytes((i * 7 + 3) % 251 + 1 for i in range(size))  # no zero byte: nothing is cut
    offset = MESSAGES[msgid][1]
    for sent in (payload, payload[:offset]):  # whole, and cut before the target (MAVLink 2 drops zeros)
        data = v2_frame(msgid, cls, sent)
        [frame] = FrameSplitter().feed(data)  # the CRC check passes with the table's CRC_EXTRA
        decoder = mavlink.MAVLink(None)
        decoder.robust_parsing = True
        expected = decoder.decode(bytearray(data)).target_system
        assert target_system(frame) == expected
    assert target_system(FrameSplitter().feed(v2_frame(msgid, cls, payload))[0]) != 0


def test_the_relays_checksum_is_pymavlinks() -> None:
    """`x25` (the standard library's CRC with the bits reversed) sums as pymavlink does, and a frame
    with one byte changed is not taken."""
    for n in range(0, 300, 7):
        data = bytes((i * 31 + n) % 256 for i in range(n))
        assert x25(data) == x25crc(data).crc, n
    cls = mavlink.mavlink_map[mavlink.MAVLINK_MSG_ID_COMMAND_LONG]
    good = v2_frame(mavlink.MAVLINK_MSG_ID_COMMAND_LONG, cls, bytes(range(1, cls.unpacker.size + 1)))
    assert len(FrameSplitter().feed(good)) == 1
    bad = bytearray(good)
    bad[12] ^= 0x01
    assert FrameSplitter().feed(bytes(bad)) == []
