"""Where one sidecar's CPU at rest goes: a bare mavsdk_server measured in steps, one window each.

One simulated drone at real time and one mavsdk_server started here (as the gateway starts it, without
the gateway), then, each over ``--window`` seconds, the sidecar's thread wake-ups (voluntary and
involuntary context switches) and CPU from /proc, and the gRPC stream items it sent:

1. ``no drone``: a second mavsdk_server listening where nothing sends (its gRPC server opens only once
   a system is discovered);
2. ``drone, no client``: the drone connected (it sends its HEARTBEAT only: no rate asked), no gRPC client;
3. ``subscriptions, no rates``: the gateway's telemetry feed (``TelemetryFeed.start``: the streams it
   holds open at rest on ArduPilot) and its HEARTBEAT and EKF_STATUS_REPORT loops through mavlink_direct;
4. ``subscriptions and rest rates``: the rest rates asked (``STREAM_RATES_HZ``, each as the gateway asks
   it: MAV_CMD_SET_MESSAGE_INTERVAL in a COMMAND_LONG);
5. ``rest rates, no rc_status``: the same without the RC status stream (one item a SYS_STATUS);
6. ``rest rates, no subscription``: the rates kept, every stream closed, the gRPC channel open.

The differences split the sidecar's cost into a fixed part per process, a part per MAVLink message
received and a part per gRPC stream item sent. The client's own process (this one: the feed's Python
code, gRPC's asyncio client, no relay) is measured beside it. ``--rounds`` repeats steps 2-6 (a
shared machine's noise).
"""

from __future__ import annotations

import asyncio
import contextlib
import json
import os
import socket
import sys
import time
from collections.abc import AsyncIterator, Callable
from pathlib import Path
from typing import Any

import common
from wakeups import ThreadSample, delta, threads

from gateway.link.mavsdk_system import MavlinkMessage, System
from gateway.link.sidecar import mavsdk_server_binary
from gateway.link.telemetry import TelemetryCache
from gateway.link.telemetry_feed import MESSAGE_IDS, STREAM_RATES_HZ, TelemetryFeed

WINDOW_S = 20.0
SETTLE_S = 5.0
MAV_CMD_SET_MESSAGE_INTERVAL = 511
GCS_SYSID = 246


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port: int = s.getsockname()[1]
        return port


@contextlib.asynccontextmanager
async def mavsdk_server(url: str, log: Path) -> AsyncIterator[tuple[int, int]]:
    """A mavsdk_server on ``url`` with a free gRPC port, as the gateway's sidecar runs: (pid, port)."""
    from gateway.config import Settings

    port = _free_port()
    binary = mavsdk_server_binary(Settings(sidecar_confinement="loopback"))
    with log.open("wb") as out:
        proc = await asyncio.create_subprocess_exec(
            binary, "-p", str(port), "--sysid", str(GCS_SYSID), "--compid", "190", url,
            stdout=out, stderr=asyncio.subprocess.STDOUT, stdin=asyncio.subprocess.DEVNULL,
        )  # fmt: skip
    try:
        yield proc.pid, port
    finally:
        proc.terminate()
        with contextlib.suppress(TimeoutError):
            await asyncio.wait_for(proc.wait(), 10.0)
        if proc.returncode is None:
            proc.kill()
            await proc.wait()


class Counter:
    """gRPC stream items received by the client, all streams together."""

    def __init__(self) -> None:
        self.items = 0

    def wrap(self, handle: Callable[[Any], None]) -> Callable[[Any], None]:
        def counted(item: Any) -> None:
            self.items += 1
            handle(item)

        return counted


class CountingFeed(TelemetryFeed):
    """The gateway's feed, counting the stream items it handles."""

    counter = Counter()

    def _subscribe(
        self, name: str, subscribe: Callable[[], AsyncIterator[Any]], handle: Callable[[Any], None]
    ) -> None:
        super()._subscribe(name, subscribe, self.counter.wrap(handle))


async def measure(title: str, pids: list[int], counter: Counter | None, window_s: float) -> list[str]:
    """One window: per process, wake-ups and CPU a second; the items the client got a second."""
    before = {p: threads(p) for p in pids}
    items0 = counter.items if counter is not None else 0
    t0 = time.monotonic()
    load0 = os.getloadavg()[0]
    await asyncio.sleep(window_s)
    seconds = time.monotonic() - t0
    after: dict[int, dict[int, ThreadSample]] = {p: threads(p) for p in pids}
    items = (counter.items - items0) / seconds if counter is not None else 0.0
    rows = []
    for p in pids:
        who = "client" if p == os.getpid() else "sidecar"
        d = delta(before[p], after[p])
        wakes = sum(v[1] + v[2] for v in d.values()) / seconds
        cpu = 100 * sum(v[3] for v in d.values()) / seconds
        count = sum(v[0] for v in d.values())
        rows.append(f"| {title} | {who} | {count} | {wakes:.1f} | {cpu:.3f} | {items:.2f} | {load0:.2f} |")
    return rows


async def direct_loop(system: System, name: str, counter: Counter) -> None:
    """The session's mavlink_direct loops at rest (HEARTBEAT, EKF_STATUS_REPORT): each item decoded."""
    handle = counter.wrap(lambda msg: json.loads(msg.fields_json))
    async for msg in system.mavlink_direct.message(name):
        handle(msg)


async def ask_rate(system: System, sysid: int, message_id: int, hz: float) -> None:
    """MAV_CMD_SET_MESSAGE_INTERVAL as a COMMAND_LONG through mavlink_direct (no answer awaited)."""
    fields = {
        "target_system": sysid, "target_component": 1, "command": MAV_CMD_SET_MESSAGE_INTERVAL,
        "confirmation": 0, "param1": message_id, "param2": 1e6 / hz,
        "param3": 0, "param4": 0, "param5": 0, "param6": 0, "param7": 0,
    }  # fmt: skip
    await system.mavlink_direct.send_message(
        MavlinkMessage("COMMAND_LONG", GCS_SYSID, 190, sysid, 1, json.dumps(fields))
    )


async def run(window_s: float, rounds: int) -> None:
    rows: list[str] = []
    with common.workdir("sidecar_split") as wd:
        async with common.sim(1, speedup=1.0, workdir=wd) as sim_, contextlib.AsyncExitStack() as stack:
            idle_pid, _ = await stack.enter_async_context(
                mavsdk_server(f"udpin://127.0.0.1:{_free_port()}", wd / "idle.log")
            )
            pid, port = await stack.enter_async_context(mavsdk_server(sim_.urls[0], wd / "sidecar.log"))
            system = System("127.0.0.1", port)
            both = [pid, os.getpid()]
            await asyncio.sleep(SETTLE_S)
            rows += await measure("no drone", [idle_pid], None, window_s)
            for _ in range(rounds):
                rows += await measure("drone, no client", [pid, os.getpid()], None, window_s)
                await system.connect()
                counter = Counter()
                feed = CountingFeed("d1", system, TelemetryCache(), use_mavsdk_flight_mode=lambda: False)
                feed.counter = counter
                feed.start()
                loops = [
                    asyncio.create_task(direct_loop(system, "HEARTBEAT", counter)),
                    asyncio.create_task(direct_loop(system, "EKF_STATUS_REPORT", counter)),
                ]
                await asyncio.sleep(SETTLE_S)
                rows += await measure("subscriptions, no rates", both, counter, window_s)
                sysid = sim_.sysids[0]
                for name, hz in STREAM_RATES_HZ.items():
                    await ask_rate(system, sysid, MESSAGE_IDS[name], hz)
                await asyncio.sleep(SETTLE_S)
                rows += await measure("subscriptions and rest rates", both, counter, window_s)
                for task in feed._tasks:
                    if task.get_name().endswith("-rc_status"):
                        task.cancel()
                await asyncio.sleep(SETTLE_S)
                rows += await measure("rest rates, no rc_status", both, counter, window_s)
                await feed.stop()
                for task in loops:
                    task.cancel()
                await asyncio.gather(*loops, return_exceptions=True)
                await asyncio.sleep(SETTLE_S)
                rows += await measure("rest rates, no subscription", both, counter, window_s)
                for name in STREAM_RATES_HZ:  # back to nothing asked for the next round
                    await ask_rate(system, sysid, MESSAGE_IDS[name], 1e-6)
                await system.close()
                system = System("127.0.0.1", port)
                await asyncio.sleep(SETTLE_S)
    print("| step | process | threads | wake-ups/s | CPU % of a core | items/s | load (1 min) |")
    print("|---|---|---|---|---|---|---|")
    print("\n".join(rows))


def main() -> int:
    p = common.parser(__doc__ or "")
    p.add_argument("--window", type=float, default=WINDOW_S)
    p.add_argument("--rounds", type=int, default=1)
    args = p.parse_args()
    print(common.machine_line(common.machine()))
    asyncio.run(run(args.window, args.rounds))
    return 0


if __name__ == "__main__":
    sys.exit(main())
