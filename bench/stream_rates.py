"""Telemetry rates at rest: what the gateway asks each autopilot for, against what arrives.

One drone, disarmed on the ground, a real ArduCopter SITL (``eval "$(../shared/sitl/install)"``; real time)
or with ``--sim`` the project's simulator. Once the drone is ready and has settled, the updates the
gateway's cache received per stream are counted over a window (``/metrics``,
``fleet_gateway_telemetry_messages_total``) and set beside the rate asked for
(``gateway.link.telemetry_feed.STREAM_RATES_HZ``, sent as MAV_CMD_SET_MESSAGE_INTERVAL by MAVSDK's
set_rate_*), with the CPU of the gateway and of the drone's sidecar over the same window. Streams the
gateway takes from another (heading from the attitude, in_air from the landed state, armed and the
flight mode from the HEARTBEAT) are listed with the stream they come with.

What the sidecar parses is counted on the wire: the drone's MAVLink link runs through a counting proxy
(``LinkCounter``, the gateway's sidecar connects to it and it to the autopilot), and every message the
autopilot sends is listed by name with its rate over the same window, asked for or not: a simulator
that streamed more than ArduPilot (defaults it does not have, a rate it ignores) shows here.
"""

from __future__ import annotations

import asyncio
import contextlib
import sys
import tempfile
import time
from collections.abc import AsyncIterator
from pathlib import Path
from typing import Any

import common
import scale

sys.path.insert(0, str(common.ROOT))

from gateway.link.telemetry_feed import STREAM_RATES_HZ

WINDOW_S = 30.0
SETTLE_S = 10.0
#: cache streams that come with another stream (or the HEARTBEAT) instead of a rate of their own
FOLLOWS = {
    "heading_deg": "attitude_euler",
    "attitude": "attitude_euler",
    "velocity_ned": "position",
    "in_air": "landed_state",
    "armed": "HEARTBEAT (1 Hz, not asked for)",
    "flight_mode": "HEARTBEAT (1 Hz, not asked for)",
    "imu": "raw_imu on ArduPilot, imu on PX4",
    "rc_status": "SYS_STATUS and RC_CHANNELS (MAVSDK sets no rate for it)",
    "battery": "SYS_STATUS (health) on ArduPilot, BATTERY_STATUS on PX4",
}


class LinkCounter:
    """A TCP proxy between the sidecar and the autopilot that counts the MAVLink messages the autopilot
    sends, by message id (MAVLink 1 and 2 frames; bytes between frames are skipped)."""

    def __init__(self, url: str) -> None:
        host_port = url.split("://", 1)[1]
        self.host, _, port = host_port.rpartition(":")
        self.port = int(port)
        self.counts: dict[int, int] = {}
        self._server: asyncio.Server | None = None
        self._tasks: set[asyncio.Task[None]] = set()

    async def start(self) -> str:
        self._server = await asyncio.start_server(self._client, "127.0.0.1", 0)
        port = self._server.sockets[0].getsockname()[1]
        return f"tcpout://127.0.0.1:{port}"

    async def stop(self) -> None:
        if self._server is not None:
            self._server.close()
        for task in list(self._tasks):
            task.cancel()
        await asyncio.gather(*self._tasks, return_exceptions=True)

    async def _client(self, reader: asyncio.StreamReader, writer: asyncio.StreamWriter) -> None:
        up_reader, up_writer = await asyncio.open_connection(self.host, self.port)
        for coro in (self._pipe(reader, up_writer, False), self._pipe(up_reader, writer, True)):
            task = asyncio.create_task(coro)
            self._tasks.add(task)
            task.add_done_callback(self._tasks.discard)

    async def _pipe(self, reader: asyncio.StreamReader, writer: asyncio.StreamWriter, count: bool) -> None:
        buf = b""
        with contextlib.suppress(ConnectionError, asyncio.CancelledError):
            while data := await reader.read(65536):
                writer.write(data)
                if count:
                    buf = self._count(buf + data)
        writer.close()

    def _count(self, buf: bytes) -> bytes:
        i = 0
        while i < len(buf):
            magic = buf[i]
            if magic == 0xFD and i + 10 <= len(buf):  # MAVLink 2: 10-byte header, CRC, optional signature
                size = 10 + buf[i + 1] + 2 + (13 if buf[i + 2] & 1 else 0)
                msg_id = buf[i + 7] | buf[i + 8] << 8 | buf[i + 9] << 16
            elif magic == 0xFE and i + 6 <= len(buf):  # MAVLink 1: 6-byte header, CRC
                size = 6 + buf[i + 1] + 2
                msg_id = buf[i + 5]
            elif magic in (0xFD, 0xFE):
                break  # a header not all here yet
            else:
                i += 1
                continue
            if i + size > len(buf):
                break
            self.counts[msg_id] = self.counts.get(msg_id, 0) + 1
            i += size
        return buf[i:]


def message_name(msg_id: int) -> str:
    from pymavlink.dialects.v20 import ardupilotmega

    cls = ardupilotmega.mavlink_map.get(msg_id)
    return cls.msgname if cls is not None else f"id {msg_id}"


@contextlib.asynccontextmanager
async def counted(sim_: common.Sim, counter: LinkCounter) -> AsyncIterator[common.Sim]:
    """``sim_`` with its one drone reached through ``counter``."""
    url = await counter.start()
    try:
        yield common.Sim(sim_.proc, [url], sim_.sysids, sim_.udp_urls, sim_.control_url, sim_.log)
    finally:
        await counter.stop()


@contextlib.asynccontextmanager
async def one_drone(use_sim: bool, wd: Path, counter: list[LinkCounter]) -> AsyncIterator[common.Gateway]:
    if use_sim:
        async with common.sim(1, speedup=1.0, workdir=wd) as sim_:
            counter.append(LinkCounter(sim_.urls[0]))
            async with counted(sim_, counter[0]) as through, common.gateway(through, workdir=wd) as gw:
                yield gw
        return
    from tests.helpers.autopilots import arducopter, ardupilot_missing

    missing = ardupilot_missing()
    if missing:
        raise SystemExit(f'no ArduCopter SITL: {missing} (eval "$(../shared/sitl/install)", or --sim)')
    with arducopter(wd / "sitl", speedup=1.0, sysid=1, taken=set()) as ap:
        sim_ = common.Sim(
            proc=None, urls=[ap.url], sysids=[1], udp_urls=[None], control_url="", log=wd / "none"
        )  # type: ignore[arg-type]
        counter.append(LinkCounter(ap.url))
        async with counted(sim_, counter[0]) as through, common.gateway(through, workdir=wd) as gw:
            yield gw


async def measure(use_sim: bool) -> dict[str, Any]:
    with tempfile.TemporaryDirectory(prefix="stream-rates-") as tmp:
        wd = Path(tmp)
        (wd / "sitl").mkdir()
        counter: list[LinkCounter] = []
        async with one_drone(use_sim, wd, counter) as gw:
            waited, states = await common.wait_states(gw, "ready", 240.0)
            if states.get(gw.drone_ids[0]) != "ready":
                raise SystemExit(f"the drone was not ready after {waited:.0f} s: {states}\n{gw.log_tail()}")
            await asyncio.sleep(SETTLE_S)  # the rates requested at session start have taken effect
            sidecars = await gw.sidecar_pids()
            gw_cpu, sc_cpu = common.CpuMeter([gw.pid]), common.CpuMeter(sidecars)
            c0 = await scale.message_counts(gw)
            wire0 = dict(counter[0].counts)
            gw_cpu.start()
            sc_cpu.start()
            t0 = time.monotonic()
            await asyncio.sleep(WINDOW_S)
            c1 = await scale.message_counts(gw)
            wire1 = dict(counter[0].counts)
            elapsed = time.monotonic() - t0
            return {
                "source": "simulator" if use_sim else "ArduCopter SITL",
                "rates": {k: (v - c0.get(k, 0.0)) / elapsed for k, v in sorted(c1.items())},
                "gw_cpu": gw_cpu.percent(),
                "sc_cpu": sc_cpu.percent(),
                "wire": {
                    message_name(k): (v - wire0.get(k, 0)) / elapsed
                    for k, v in sorted(wire1.items())
                    if v > wire0.get(k, 0)
                },
            }


def render(r: dict[str, Any]) -> str:
    rows = []
    for name, got in r["rates"].items():
        if name in ("status_text", "mission_progress") and got == 0:
            continue
        asked = STREAM_RATES_HZ.get(name)
        source = FOLLOWS.get(name)
        if asked is None and source in STREAM_RATES_HZ:
            asked = STREAM_RATES_HZ[source]
        rows.append([name, "-" if asked is None else f"{asked:g}", f"{got:.2f}", source or name])
    return "\n".join(
        [
            f"{r['source']}, one drone at rest, {WINDOW_S:g} s window after {SETTLE_S:g} s settling; load "
            f"average {r['load']}. Gateway {r['gw_cpu']:.2f} % of a core (all of it, with its fixed "
            f"costs), sidecar {r['sc_cpu']:.2f} %.",
            "",
            common.table(["cache stream", "asked, Hz", "received per s", "set by"], rows),
            "",
            f"On the wire, what the sidecar parses: {sum(r['wire'].values()):.2f} MAVLink messages a second "
            "from the autopilot.",
            "",
            common.table(
                ["message", "per s"],
                sorted(([k, f"{v:.2f}"] for k, v in r["wire"].items()), key=lambda row: -float(row[1])),
            ),
        ]
    )


def main() -> int:
    p = common.parser(__doc__.splitlines()[0])
    p.add_argument("--sim", action="store_true", help="the project's simulator instead of ArduCopter SITL")
    args = p.parse_args()
    result = asyncio.run(measure(args.sim))
    result["load"] = Path("/proc/loadavg").read_text().split()[0]  # at the end of the window
    print(render(result))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
