"""What the ground station relay (gateway/link/relay.py) costs per MAVLink frame: cutting a stream into
frames, checking each CRC and reading the target system of the addressed ones, as the relay does for
every frame from a drone; then what writing each frame to a flight's raw log costs on top
(gateway/fleet/missions/raw_tlog.py, into a temporary folder). A drone streams about 100-200 frames a
second at the gateway's rates.

    .venv/bin/python -m bench.relay_frames [--frames 20000]

Prints CPU microseconds per frame (process time, so a busy machine does not inflate it much).
"""

from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path

from pymavlink.dialects.v20 import ardupilotmega as mavlink

from gateway.fleet.missions.raw_tlog import RawTlog
from gateway.link.mavlink_frames import FrameSplitter, target_system


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--frames", type=int, default=20000)
    args = parser.parse_args()
    mav = mavlink.MAVLink(None, srcSystem=1, srcComponent=1)
    mix = [  # a drone's usual traffic: telemetry without a target, an addressed ACK
        mavlink.MAVLink_heartbeat_message(2, 3, 81, 4, 3, 3),
        mavlink.MAVLink_global_position_int_message(1, -353632610, 1491652300, 584000, 10000, 0, 0, 0, 9000),
        mavlink.MAVLink_attitude_message(1, 0.1, 0.2, 0.3, 0.0, 0.0, 0.0),
        mavlink.MAVLink_command_ack_message(176, 0, 0, 0, 255, 190),
    ]
    one_round = b"".join(bytes(m.pack(mav)) for m in mix)
    stream = one_round * max(1, args.frames // len(mix))
    splitter = FrameSplitter()
    frames = 0
    started = time.process_time()
    for i in range(0, len(stream), 512):  # as it comes off a socket
        for frame in splitter.feed(stream[i : i + 512]):
            target_system(frame)
            frames += 1
    cpu = time.process_time() - started
    print(f"relay: {frames} frames, {cpu / frames * 1e6:.1f} CPU us per frame (split, CRC, target)")
    print(f"relay: at 200 frames/s per drone, {cpu / frames * 200 * 100:.2f} % of one core per drone")

    with tempfile.TemporaryDirectory() as folder:
        raw = RawTlog(Path(folder), "bench", 1 << 40)
        raw.open(1)
        datas = [f.data for f in FrameSplitter().feed(stream)]
        started = time.process_time()
        for data in datas:
            raw.frame(data)
        raw.close()
        cpu = time.process_time() - started
        size = (Path(folder) / "bench-flight-1.tlog").stat().st_size
    print(f"flight raw log: {len(datas)} frames, {cpu / len(datas) * 1e6:.2f} CPU us per frame written")
    print(f"flight raw log: {size / len(datas):.1f} bytes per frame on disk with its time stamp")


if __name__ == "__main__":
    main()
