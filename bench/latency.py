"""Tool-call latency through MCP over HTTP, next to the same operation done directly with mavsdk_grpc.

One simulated drone, one gateway process (``fleet-gateway serve``: REST + /mcp, SQLite audit) and, on
the same vehicle, a second mavsdk_server that this script drives directly with ``mavsdk_grpc`` (the sim
sends the vehicle's MAVLink on a second link, UDP, as SITL's ``--out`` does). Each iteration times the
MCP call and then the direct call, so both see the same machine load. The MCP client is the SDK's
Streamable HTTP client in its default (2026-07-28, stateless) mode, over loopback.

Operations:
- cached telemetry read: MCP ``get_position`` / ``get_telemetry`` (answered from the gateway's cache)
  against the direct way a naive server reads a value (first item of ``telemetry.position()``, i.e. the
  next stream sample), and against a bare gRPC round trip to a sidecar (``info.get_version()``,
  answered by mavsdk_server from its own cache), the floor of anything that goes through MAVSDK, and
  against a plain HTTP GET of the gateway's ``/healthz`` (the floor of anything that goes through HTTP)
  and an MCP ``prompts/list`` (the floor of anything that goes through the MCP SDK, without tool or audit);
- command dispatch, until the autopilot's COMMAND_ACK: MCP ``set_max_speed`` against
  ``action.set_current_speed``, and MCP ``go_to_location(wait=false)`` against ``action.goto_location``.
"""

from __future__ import annotations

import asyncio
import contextlib
import math
import time
from collections.abc import AsyncIterator, Awaitable, Callable
from pathlib import Path
from typing import Any

import common

SPEEDUP = 1.0  # real time: stream periods are wall-clock periods, as with a real vehicle
ALT_M = 15.0
OP_TIMEOUT_S = 30.0  # a hung call ends the run with an error instead of hanging it


@contextlib.asynccontextmanager
async def direct_system(url: str, workdir: Path) -> AsyncIterator[Any]:
    """A mavsdk_grpc System through its own (loopback-confined) mavsdk_server on ``url``."""
    from mavsdk_grpc import System

    from gateway.link.confine import sidecar_binary
    from gateway.util.ports import free_tcp_port

    binary = sidecar_binary("loopback", None, None)
    port = free_tcp_port()
    log = workdir / "direct-mavsdk.log"
    fd = common._log_fd(log)
    try:
        proc = await asyncio.create_subprocess_exec(
            str(binary), "-p", str(port), "--sysid", "246", "--compid", "190", url,
            stdout=fd, stderr=fd, stdin=asyncio.subprocess.DEVNULL, start_new_session=True,
        )  # fmt: skip
    finally:
        import os

        os.close(fd)
    try:
        system = System(mavsdk_server_address="127.0.0.1", port=port)
        await asyncio.wait_for(system.connect(), 90)
        async for state in system.core.connection_state():
            if state.is_connected:
                break
        yield system
    finally:
        await common.stop_group(proc)


async def first(stream: Any) -> Any:
    async for item in stream:
        return item
    return None


async def series(
    n: int, pairs: dict[str, Callable[[int], Awaitable[Any]]], warmup: int = 5
) -> dict[str, list[float]]:
    """Run each named operation n times, interleaved; return the durations (s) per name."""
    out: dict[str, list[float]] = {k: [] for k in pairs}
    for i in range(warmup + n):
        for name, op in pairs.items():
            t0 = time.perf_counter()
            await asyncio.wait_for(op(i), OP_TIMEOUT_S)
            if i >= warmup:
                out[name].append(time.perf_counter() - t0)
    return out


async def run(n_reads: int, n_cmds: int, speedup: float) -> dict[str, Any]:
    from gateway.fleet import geo
    from gateway.util.ports import free_udp_port

    with common.workdir("latency") as wd:
        udp = free_udp_port()
        async with (
            common.sim(1, speedup=speedup, udp_base_port=udp, workdir=wd) as sim_,
            common.gateway(sim_, workdir=wd) as gw,
        ):
            waited, states = await common.wait_states(gw, "ready", 120)
            if any(s != "ready" for s in states.values()):
                raise RuntimeError(f"drone not ready after {waited:.0f} s: {states}\n{gw.log_tail()}")
            async with (
                common.mcp_client(gw.mcp_url) as mcp,
                direct_system(f"udpin://127.0.0.1:{udp}", wd) as drone,
            ):
                await drone.telemetry.set_rate_position(5.0)
                takeoff = common.structured(
                    await mcp.call_tool("takeoff", {"drone_id": "d1", "alt_m": ALT_M})
                )
                if takeoff.get("status") != "succeeded":
                    raise RuntimeError(f"takeoff did not finish: {takeoff}")
                home = common.structured(await mcp.call_tool("get_home_position", {"drone_id": "d1"}))
                pos = common.structured(await mcp.call_tool("get_position", {"drone_id": "d1"}))
                points = [geo.offset_position(pos["lat_deg"], pos["lon_deg"], n, 0.0) for n in (0.0, 6.0)]
                amsl = home["alt_amsl_m"] + ALT_M

                def mcp_call(tool: str, args: Callable[[int], dict[str, Any]]) -> Any:
                    async def op(i: int) -> None:
                        common.structured(await mcp.call_tool(tool, {"drone_id": "d1", **args(i)}))

                    return op

                async def direct_position(_i: int) -> None:
                    await first(drone.telemetry.position())

                async def direct_version(_i: int) -> None:
                    await drone.info.get_version()

                async def mcp_floor(_i: int) -> None:
                    await mcp.list_prompts()

                async def http_floor(_i: int) -> None:
                    (await gw.http.get("/healthz")).raise_for_status()

                async def direct_speed(i: int) -> None:
                    await drone.action.set_current_speed(5.0 + i % 2)

                async def direct_goto(i: int) -> None:
                    lat, lon = points[i % 2]
                    await drone.action.goto_location(lat, lon, amsl, math.nan)

                def goto_args(i: int) -> dict[str, Any]:
                    lat, lon = points[(i + 1) % 2]
                    return {"lat_deg": lat, "lon_deg": lon, "alt_m": ALT_M, "wait": False}

                reads = await series(
                    n_reads,
                    {
                        "mcp get_position": mcp_call("get_position", lambda i: {}),
                        "mcp get_telemetry": mcp_call("get_telemetry", lambda i: {}),
                        "direct telemetry.position() next sample": direct_position,
                        "direct info.get_version() (gRPC floor)": direct_version,
                        "http GET /healthz (HTTP floor)": http_floor,
                        "mcp prompts/list (MCP floor, no tool)": mcp_floor,
                    },
                )
                cmds = await series(
                    n_cmds,
                    {
                        "mcp set_max_speed": mcp_call("set_max_speed", lambda i: {"speed_mps": 5.0 + i % 2}),
                        "direct action.set_current_speed": direct_speed,
                        "mcp go_to_location wait=false": mcp_call("go_to_location", goto_args),
                        "direct action.goto_location": direct_goto,
                    },
                )
                with contextlib.suppress(Exception):
                    await mcp.call_tool("land", {"drone_id": "d1", "wait": False})
    return {"reads": reads, "cmds": cmds, "speedup": speedup}


def render(r: dict[str, Any]) -> str:
    allv = {**r["reads"], **r["cmds"]}
    p = {k: common.pcts(v) for k, v in allv.items()}
    rows = [
        [f"`{k}`", len(v), common.ms(p[k]["p50"]), common.ms(p[k]["p95"]), common.ms(p[k]["p99"])]
        for k, v in allv.items()
    ]

    def ratio(a: str, b: str) -> str:
        if a not in p or b not in p:
            return "n/a"
        return " / ".join(f"{p[a][q] / p[b][q]:.1f}x" for q in ("p50", "p95", "p99"))

    lines = [
        f"One simulated drone (speed-up {r['speedup']:g}x, flying at {ALT_M:g} m), one gateway process, "
        "a second mavsdk_server on the same vehicle for the direct calls; MCP over Streamable HTTP "
        "on loopback (SDK client, 2026-07-28 mode); operations interleaved. Times in ms.",
        "",
        common.table(["operation", "n", "p50", "p95", "p99"], rows),
        "",
        "Ratios (p50 / p95 / p99):",
        "",
        f"- `get_position` via MCP vs the next stream sample read directly: "
        f"{ratio('mcp get_position', 'direct telemetry.position() next sample')}",
        f"- `get_position` via MCP vs a bare gRPC round trip to the sidecar: "
        f"{ratio('mcp get_position', 'direct info.get_version() (gRPC floor)')}",
        f"- `get_position` via MCP vs a plain HTTP request to the same server (`/healthz`): "
        f"{ratio('mcp get_position', 'http GET /healthz (HTTP floor)')}",
        f"- MCP `prompts/list` (transport + SDK, no tool, no audit row) vs `/healthz`: "
        f"{ratio('mcp prompts/list (MCP floor, no tool)', 'http GET /healthz (HTTP floor)')}",
        f"- `set_max_speed` via MCP vs direct: "
        f"{ratio('mcp set_max_speed', 'direct action.set_current_speed')}",
        f"- goto via MCP (`wait=false`) vs direct: "
        f"{ratio('mcp go_to_location wait=false', 'direct action.goto_location')}",
        "",
        "A cached read through MCP costs the HTTP + JSON-RPC + audit-row overhead only; a direct read of "
        "the next stream sample waits up to one stream period (5 Hz in simulated time). Command dispatch "
        "includes the round trip to the autopilot's COMMAND_ACK in both columns; the MCP side adds the "
        "safety checks, the operation record and the audit row.",
    ]
    return "\n".join(lines)


def main() -> int:
    p = common.parser(__doc__.splitlines()[0])
    p.add_argument("--speedup", type=float, default=SPEEDUP, help="simulator speed-up (default real time)")
    args = p.parse_args()
    info = common.machine()
    n_reads, n_cmds = (1000, 300) if args.full else (100, 40)
    r = asyncio.run(run(n_reads, n_cmds, args.speedup))
    text = render(r)
    print(text)
    if args.write:
        common.write_section("latency", "Tool-call latency: MCP over HTTP vs direct mavsdk_grpc", text, info)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
