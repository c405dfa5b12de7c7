"""Cluster figures: three gateway nodes, NATS and PostgreSQL on this machine, nine simulated drones.

- a cached read answered by each node from its own telemetry cache (MCP get_telemetry, never forwarded),
  on the drone's owner and on another node;
- a cached read that is a verb (MCP check_arrival: the owner's operation and telemetry) on the owner and
  forwarded by another node, and one hop of a forwarded call alone (NATS request/reply to the owner);
- a command (MCP hold_position, REST hold) on the owner and forwarded by another node to the owner;
- emergency stop from one node with drones of all three nodes in the air: the REST call returns after
  every owner answered that it sent the hold, so its duration bounds the time to the last command sent;
- NATS traffic per drone per second (the server's own counters, no call running);
- takeover: kill -9 of a node, until every one of its drones is owned by another node and ready there.

Run: .venv/bin/python bench/cluster.py [--full] [--write]
"""

from __future__ import annotations

import asyncio
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

import httpx

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
sys.path.insert(0, str(Path(__file__).resolve().parent))

import common

from tests.cluster.harness import Cluster, cluster, missing_engines, wait_spread
from tests.helpers.timing import eventually

DRONES, NODES = 9, 3


def by_owner(owners: dict[str, str]) -> dict[str, list[str]]:
    out: dict[str, list[str]] = {}
    for vid, node in sorted(owners.items()):
        out.setdefault(node, []).append(vid)
    return out


async def timed(samples: list[float], call: Any) -> Any:
    started = time.perf_counter()
    result = await call()
    samples.append(time.perf_counter() - started)
    return result


async def mcp_calls(
    c: Cluster, owners: dict[str, str], tool: str, n: int, args: dict[str, Any] | None = None
) -> dict[str, list[float]]:
    """The tool on a drone node A owns: called on node A (local) and on node B (forwarded, for verbs)."""
    drone = by_owner(owners)["node-a"][0]
    arguments = {"drone_id": drone, **(args or {})}
    out: dict[str, list[float]] = {"local": [], "remote": []}
    for label, node in (("local", c.node("node-a")), ("remote", c.node("node-b"))):
        async with node.client(name=f"bench-{tool}-{label}") as mcp:
            for _ in range(3):  # warm up
                await mcp.call_tool(tool, arguments)
            for _ in range(n):
                r = await timed(out[label], lambda mcp=mcp: mcp.call_tool(tool, arguments))
                assert not r.is_error, r.content[0].text if r.content else r
    return out


async def forward_hop(c: Cluster, owners: dict[str, str], n: int) -> list[float]:
    """One NATS request/reply to the owner (the arrival verb), from a client of our own."""
    from gateway.cluster.bus import Bus

    bus = Bus([c.nats.url], "bench")
    await bus.connect()
    drone = by_owner(owners)["node-a"][0]
    caller = {"via": "rest", "principal": "bench"}
    samples: list[float] = []
    try:
        for _ in range(3):
            await bus.call(drone, "arrival", {"drone_id": drone}, caller, 10.0)
        for _ in range(n):
            await timed(samples, lambda: bus.call(drone, "arrival", {"drone_id": drone}, caller, 10.0))
    finally:
        await bus.close()
    return samples


async def take_off(c: Cluster, drone: str, owner: str, alt_m: float = 10.0) -> None:
    async with c.node(owner).client(name="bench-takeoff") as mcp:
        r = await mcp.call_tool("takeoff", {"drone_id": drone, "alt_m": alt_m})
        assert not r.is_error, r.content[0].text if r.content else r


async def commands(c: Cluster, owners: dict[str, str], n: int) -> dict[str, list[float]]:
    drone = by_owner(owners)["node-a"][0]
    out: dict[str, list[float]] = {"local": [], "remote": []}
    async with httpx.AsyncClient(timeout=30) as http:
        for _ in range(n):
            for label, node in (("local", c.node("node-a")), ("remote", c.node("node-b"))):
                url = f"{node.base_url}/api/v1/vehicles/{drone}/hold"
                r = await timed(out[label], lambda url=url: http.post(url))
                assert r.status_code == 200, r.text
    return out


async def emergency_stops(c: Cluster, flyers: list[str], n: int) -> list[float]:
    samples: list[float] = []
    async with httpx.AsyncClient(base_url=c.node("node-b").base_url, timeout=60) as http:
        for _ in range(n):
            r = await timed(samples, lambda: http.post("/api/v1/fleet/stop", json={"action": "hold"}))
            body = r.json()
            sent = [x for x in body["results"] if x["outcome"] == "sent"]
            assert sorted(x["vehicle_id"] for x in sent) == sorted(flyers), body
            await http.delete("/api/v1/fleet/lock")
    return samples


async def nats_traffic(c: Cluster, seconds: float) -> dict[str, float]:
    async with httpx.AsyncClient(timeout=10) as http:
        a = (await http.get(f"{c.nats.monitor_url}/varz")).json()
        t0 = time.monotonic()
        await asyncio.sleep(seconds)
        b = (await http.get(f"{c.nats.monitor_url}/varz")).json()
        dt = time.monotonic() - t0
    per = DRONES * dt
    return {
        "in_msgs": (b["in_msgs"] - a["in_msgs"]) / per,
        "in_bytes": (b["in_bytes"] - a["in_bytes"]) / per,
        "out_msgs": (b["out_msgs"] - a["out_msgs"]) / per,
        "out_bytes": (b["out_bytes"] - a["out_bytes"]) / per,
    }


async def takeover(c: Cluster, owners: dict[str, str]) -> dict[str, float]:
    lost = c.node("node-c")
    victims = by_owner(owners)["node-c"]
    survivor = c.node("node-a")
    started = time.perf_counter()
    lost.kill9()
    owned_at: float | None = None
    while True:
        now_owners = await c.owners(survivor)
        if owned_at is None and all(now_owners.get(d) in ("node-a", "node-b") for d in victims):
            owned_at = time.perf_counter() - started
        if owned_at is not None:
            states = await c.states(survivor)
            if all(states[d] == "ready" for d in victims):
                return {"owned_s": owned_at, "ready_s": time.perf_counter() - started}
        if time.perf_counter() - started > 120:
            raise TimeoutError("takeover did not finish within 120 s")
        await asyncio.sleep(0.05)


def snapshot_costs(n: int = 2000) -> tuple[int, float, float]:
    """Bytes of one snapshot of a flying drone, and the CPU time to encode it (owner) and to decode and
    apply it (every other node), in microseconds."""
    from types import SimpleNamespace

    from gateway.cluster import snapshot
    from gateway.link import telemetry as t

    cache = t.TelemetryCache()
    for name, value in {
        "position": t.PositionValue(47.1, 8.2, 500.0, 10.0),
        "home": t.PositionValue(47.1, 8.2, 490.0, 0.0),
        "attitude": t.AttitudeValue(1.0, 2.0, 3.0),
        "velocity_ned": t.VelocityNedValue(1.0, 2.0, 0.1),
        "heading_deg": 90.0,
        "battery": t.BatteryValue(80.0, 12.1),
        "gps_info": t.GpsInfoValue(10, "FIX_3D"),
        "flight_mode": "GUIDED",
        "armed": True,
        "in_air": True,
        "landed_state": "IN_AIR",
        "health": t.HealthValue(*[True] * 7),
        "rc_status": t.RcStatusValue(True, True, None),
        "imu": t.ImuValue((1.0, 2.0, 3.0), (0.1, 0.2, 0.3), 30.0),
        "mission_progress": t.MissionProgressValue(1, 5),
    }.items():
        cache.put(name, value)
    for i in range(10):
        cache.add_status_text("info", f"status text number {i} of a flight")
    status = {"id": "d1", "state": "ready", "sysid": 1, "autopilot": "ArduPilot", "is_simulator": True,
              "sidecar": {"state": "serving", "pid": 1, "grpc_port": 1, "restarts": 0}}  # fmt: skip
    vehicle = SimpleNamespace(id="d1", telemetry=cache, status=lambda: status)
    payload = snapshot.encode(vehicle, "n", 1, 1, None)
    started = time.process_time()
    for _ in range(n):
        snapshot.encode(vehicle, "n", 1, 1, None)
    encode_us = (time.process_time() - started) / n * 1e6
    into = t.TelemetryCache()
    started = time.process_time()
    for _ in range(n):
        snapshot.apply(into, snapshot.decode(payload))
    return len(payload), encode_us, (time.process_time() - started) / n * 1e6


def row(name: str, samples: list[float]) -> list[str]:
    p = common.pcts(samples, (50, 99))
    return [name, str(len(samples)), common.ms(p["p50"]), common.ms(p["p99"])]


async def run(full: bool) -> str:
    n = 200 if full else 50
    workdir = Path(tempfile.mkdtemp(prefix="bench-cluster-"))
    async with cluster(workdir, drones=DRONES, nodes=NODES, speedup=5.0) as c:
        owners = await wait_spread(c)
        groups = by_owner(owners)
        traffic = await nats_traffic(c, 20.0 if full else 10.0)
        reads = await mcp_calls(c, owners, "get_telemetry", n)
        arrivals = await mcp_calls(c, owners, "check_arrival", n)
        hop = await forward_hop(c, owners, n)
        flyers = [groups[name][0] for name in ("node-a", "node-b", "node-c")]
        await asyncio.gather(*(take_off(c, d, owners[d]) for d in flyers))
        holds = await mcp_calls(c, owners, "hold_position", n // 2)
        cmds = await commands(c, owners, n // 2)
        stops = await emergency_stops(c, flyers, 10 if full else 5)
        async with httpx.AsyncClient(timeout=30) as http:
            for d in flyers:
                await http.post(f"{c.node('node-a').base_url}/api/v1/vehicles/{d}/land")

        async def landed() -> bool:
            states = [await c.true_state(d) for d in flyers]
            return all(not s["armed"] for s in states)

        await eventually(landed, "the bench drones landed", within_s=120)
        to = await takeover(c, owners)
        ttl = float(c.nodes[0].env["GATEWAY_CLUSTER_LEASE_TTL_S"])
        hz = float(c.nodes[0].env["GATEWAY_CLUSTER_TELEMETRY_HZ"])
    size, encode_us, decode_us = snapshot_costs()
    headers = ["what", "n", "p50 ms", "p99 ms"]
    table = common.table(
        headers,
        [
            row("cached read (MCP get_telemetry) on the owner", reads["local"]),
            row("cached read (MCP get_telemetry) on another node, from its cache", reads["remote"]),
            row("cached read verb (MCP check_arrival) on the owner", arrivals["local"]),
            row("cached read verb (MCP check_arrival) forwarded to the owner", arrivals["remote"]),
            row("forwarded call alone (NATS request/reply to the owner)", hop),
            row("command (MCP hold_position) on the owner", holds["local"]),
            row("command (MCP hold_position) forwarded to the owner", holds["remote"]),
            row("command (REST hold) on the owner", cmds["local"]),
            row("command (REST hold) forwarded to the owner", cmds["remote"]),
            row(f"emergency stop from node B, {len(flyers)} drones on 3 nodes", stops),
        ],
    )
    lines = [
        f"{NODES} nodes, {DRONES} simulated drones (speed-up 5), lease {ttl:g} s, "
        f"snapshots {hz:g} Hz per drone.",
        "",
        table,
        "",
        f"NATS traffic per drone per second (no calls): {traffic['in_msgs']:.2f} messages "
        f"({traffic['in_bytes'] / 1024:.2f} KiB) published, {traffic['out_msgs']:.2f} messages "
        f"({traffic['out_bytes'] / 1024:.2f} KiB) delivered (every node receives every snapshot).",
        f"One snapshot of a flying drone: {size} bytes; CPU {encode_us:.0f} µs to encode (owner), "
        f"{decode_us:.0f} µs to decode and apply (every other node).",
        "",
        f"Takeover after kill -9 of a node with {len(groups['node-c'])} drones: leases taken by the "
        "other nodes "
        f"after {to['owned_s']:.2f} s, every drone ready on its new owner after {to['ready_s']:.2f} s.",
    ]
    return "\n".join(lines)


def main() -> int:
    args = common.parser(__doc__.splitlines()[0]).parse_args()
    missing = missing_engines()
    if missing:
        print(f"skipped: {missing}")
        return 0
    info = common.machine()
    body = asyncio.run(run(args.full))
    print(common.machine_line(info))
    print(body)
    if args.write:
        common.write_section(
            "cluster", "Cluster: forwarding, emergency stop, takeover, NATS traffic", body, info
        )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
