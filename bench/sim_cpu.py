"""Simulator load: CPU and memory of one `fleet-gateway sim` process per number of vehicles.

Each vehicle gets a bare MAVLink client that requests the stream set the gateway asks for through MAVSDK
(GLOBAL_POSITION_INT 5 Hz, ATTITUDE 4 Hz, SYS_STATUS, GPS_RAW_INT, BATTERY_STATUS, EXTENDED_SYS_STATE,
HOME_POSITION 1 Hz). Prints one line per configuration. Run: .venv/bin/python bench/sim_cpu.py
"""

from __future__ import annotations

import asyncio
import contextlib
import os
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from tests.helpers import sim_process
from tests.helpers.raw import raw_mavlink

STREAMS = [(33, 5), (30, 4), (1, 1), (24, 1), (147, 1), (245, 1), (242, 1)]
MEASURE_S = 10.0


def _cpu_s(pid: int) -> float:
    with open(f"/proc/{pid}/stat") as fh:
        fields = fh.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def _rss_mb(pid: int) -> float:
    with open(f"/proc/{pid}/status") as fh:
        for line in fh:
            if line.startswith("VmRSS"):
                return int(line.split()[1]) / 1024
    return float("nan")


async def measure(count: int, speedup: float) -> str:
    async with sim_process(count, speedup=speedup) as sim, contextlib.AsyncExitStack() as stack:
        received = 0
        clients = []
        for url, sysid in zip(sim.urls, sim.sysids, strict=True):
            gcs = await stack.enter_async_context(raw_mavlink(url))
            gcs.target_system = sysid
            for msg_id, hz in STREAMS:
                await gcs.command(511, msg_id, 1e6 / hz)
            clients.append(gcs)
        await asyncio.sleep(2.0)
        before = sum(len(c.received) for c in clients)
        cpu0, t0 = _cpu_s(sim.pid), time.monotonic()
        await asyncio.sleep(MEASURE_S)
        cpu1, t1 = _cpu_s(sim.pid), time.monotonic()
        received = sum(len(c.received) for c in clients) - before
        pct = 100.0 * (cpu1 - cpu0) / (t1 - t0)
        return (
            f"vehicles={count:3d} speedup={speedup:4.1f}  CPU {pct:5.1f} % of one core "
            f"({pct / count:.2f} %/vehicle)  RSS {_rss_mb(sim.pid):5.1f} MB  "
            f"{received / (t1 - t0) / count:6.1f} msg/s per vehicle"
        )


async def main() -> None:
    for count, speedup in ((1, 1.0), (10, 1.0), (50, 1.0), (3, 5.0)):
        print(await measure(count, speedup), flush=True)


if __name__ == "__main__":
    asyncio.run(main())
