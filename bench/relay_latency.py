"""What the relay (gateway/link/relay.py) adds to a PARAM_VALUE's way from the drone to its sidecar, and
whether a burst of them arrives whole: a drone on a loopback TCP port (as ArduPilot SITL) sends
PARAM_VALUE frames, a reader plays the sidecar, once connected to the drone directly and once through
the relay (the sidecar's side as the gateway starts mavsdk_server on it).

    .venv/bin/python -m bench.relay_latency [--frames 1000] [--gap-ms 2] [--burst 1300]

Prints the latency (send to receive, ms: median, 95th percentile, max) of frames sent one by one every
``--gap-ms``, direct and relayed, the difference of the medians, then how many frames of a burst of
``--burst`` (a parameter list) the reader got, direct and relayed. Everything runs in one event loop,
so a busy machine shows in both columns alike.
"""

from __future__ import annotations

import argparse
import asyncio
import statistics
import time
from collections.abc import Awaitable, Callable

from pymavlink.dialects.v20 import ardupilotmega as mavlink

from gateway.link.mavlink_frames import FrameSplitter
from gateway.link.relay import Relay

Reader = tuple[asyncio.StreamReader, asyncio.StreamWriter]


def _param(mav: mavlink.MAVLink, index: int, count: int) -> bytes:
    message = mavlink.MAVLink_param_value_message(f"P{index:05d}".encode(), 0.0, 9, count, index)
    return bytes(message.pack(mav))


async def _run(
    connect: Callable[[int], Awaitable[Reader]], frames: int, gap_s: float, burst: int
) -> tuple[list[float], int]:
    """(latencies in ms of ``frames`` paced frames, frames of a ``burst`` received)."""
    mav = mavlink.MAVLink(None, srcSystem=1, srcComponent=1)
    sent: dict[int, float] = {}
    connected = asyncio.Event()

    async def drone(reader: asyncio.StreamReader, writer: asyncio.StreamWriter) -> None:
        connected.set()
        await asyncio.sleep(0.5)  # the reader is connected through the relay by then
        for i in range(frames):
            sent[i] = time.perf_counter()
            writer.write(_param(mav, i, frames))
            await asyncio.sleep(gap_s)
        writer.write(b"".join(_param(mav, frames + i, frames + burst) for i in range(burst)))
        await writer.drain()
        await reader.read()

    server = await asyncio.start_server(drone, "127.0.0.1", 0)
    port = server.sockets[0].getsockname()[1]
    reader, writer = await connect(port)
    latencies: list[float] = []
    burst_got = 0
    splitter = FrameSplitter()
    try:
        while burst_got < burst:
            data = await asyncio.wait_for(reader.read(65536), 5.0)
            if not data:
                break
            now = time.perf_counter()
            for frame in splitter.feed(data):
                msg = mavlink.MAVLink(None).decode(bytearray(frame.data))
                index = int(msg.param_index)
                if index < frames:
                    latencies.append((now - sent[index]) * 1000)
                else:
                    burst_got += 1
    except TimeoutError:
        pass
    finally:
        writer.close()
        server.close()
    return latencies, burst_got


def _figures(label: str, latencies: list[float]) -> str:
    ordered = sorted(latencies)
    p95 = ordered[int(len(ordered) * 0.95) - 1]
    return (
        f"{label}: {len(ordered)} frames, median {statistics.median(ordered):.3f} ms, "
        f"p95 {p95:.3f} ms, max {ordered[-1]:.3f} ms"
    )


async def main_async(frames: int, gap_s: float, burst: int) -> None:
    async def direct(port: int) -> Reader:
        return await asyncio.open_connection("127.0.0.1", port)

    relays: list[Relay] = []

    async def relayed(port: int) -> Reader:
        relay = Relay("bench", f"tcpout://127.0.0.1:{port}", [])
        await relay.start()
        relays.append(relay)
        host_port = relay.sidecar_url.partition("://")[2]
        host, _, sidecar_port = host_port.rpartition(":")
        return await asyncio.open_connection(host, int(sidecar_port))

    plain, plain_burst = await _run(direct, frames, gap_s, burst)
    through, through_burst = await _run(relayed, frames, gap_s, burst)
    for relay in relays:
        await relay.close()
    print(_figures("direct ", plain))
    print(_figures("relayed", through))
    added = statistics.median(through) - statistics.median(plain)
    print(f"relay adds {added:.3f} ms (median) to a PARAM_VALUE")
    print(f"burst of {burst} PARAM_VALUE: direct {plain_burst} received, relayed {through_burst} received")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--frames", type=int, default=1000)
    parser.add_argument("--gap-ms", type=float, default=2.0)
    parser.add_argument("--burst", type=int, default=1300)
    args = parser.parse_args()
    asyncio.run(main_async(args.frames, args.gap_ms / 1000, args.burst))


if __name__ == "__main__":
    main()
