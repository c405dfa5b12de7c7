"""Cluster fault figures: what the engines' faults cost, on this machine (real PostgreSQL, NATS, sidecars,
simulated drones; two nodes, three drones, 10 s lease, the default):

- PostgreSQL stopped for 20 s under three drones in the air: how long until both nodes fenced
  themselves (no sidecar left); then how long the emergency stop (land, from the node that owns fewer of
  them, each fenced node sending it over the drone's own link) takes to answer, and until every drone is
  in LAND (the simulator's own mode); once PostgreSQL is started again, how long until every drone is
  ready under exactly one sidecar; how many writes the nodes kept and wrote late;
- one node cut off from NATS (a TCP proxy cut): how long a command forwarded to it, and one it forwards,
  take to answer "not run".

Run: .venv/bin/python bench/cluster_faults.py [--write]
"""

from __future__ import annotations

import asyncio
import re
import sys
import tempfile
import time
from pathlib import Path
from typing import Any
from urllib.parse import urlparse

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
sys.path.insert(0, str(Path(__file__).resolve().parent))

import common

from tests.cluster.harness import Node, cluster, missing_engines, wait_spread
from tests.helpers.tcpproxy import TcpProxy
from tests.helpers.timing import eventually
from tests.persist.pg import find_pg_bin, restartable_postgres
from tests.registry.procs import mavsdk_servers_of

OUTAGE_S = 20.0


async def until(check: Any, what: str, within_s: float, started: float) -> float:
    await eventually(check, what, within_s=within_s)
    return time.perf_counter() - started


def log_has(node: Node, text: str) -> bool:
    return text in node.log.read_text(errors="replace")


def kept_written(nodes: list[Node]) -> int:
    total = 0
    for node in nodes:
        found = re.findall(
            r"the writes kept on this node are written \((\d+)\)", node.log.read_text(errors="replace")
        )
        total += sum(int(n) for n in found)
    return total


async def postgres_outage() -> dict[str, float]:
    with restartable_postgres() as pg:
        workdir = Path(tempfile.mkdtemp(prefix="bench-faults-"))
        async with cluster(
            workdir, drones=3, nodes=2, speedup=5.0, database_server=pg.url,
            extra_env={"GATEWAY_CLUSTER_LEASE_TTL_S": "10"},
        ) as c:  # fmt: skip
            owners = await wait_spread(c)
            async with c.node("node-a").client(name="bench-takeoff") as mcp:
                await asyncio.gather(
                    *(mcp.call_tool("takeoff", {"drone_id": d, "alt_m": 10}) for d in c.drone_ids)
                )
            fewer = min(("node-a", "node-b"), key=lambda n: sum(1 for o in owners.values() if o == n))
            pg.stop()
            stopped = time.perf_counter()

            async def fenced() -> bool:
                gone = not any(mavsdk_servers_of(n.proc.pid) for n in c.nodes)
                return gone and all(log_has(n, "could not renew its leases in time") for n in c.nodes)

            fence = await until(fenced, "both nodes fenced", 60, stopped)
            started = time.perf_counter()
            response = await c.node(fewer).post("/fleet/stop", {"action": "land"})
            answered = time.perf_counter() - started
            outcomes = [r["outcome"] for r in response.json()["results"]]
            assert outcomes == ["sent"] * 3, response.text

            async def landing() -> bool:
                return [(await c.true_state(d))["mode"] for d in c.drone_ids] == ["LAND"] * 3

            in_land = await until(landing, "every drone in LAND", 30, started)
            await asyncio.sleep(max(0.0, OUTAGE_S - (time.perf_counter() - stopped)))
            pg.start()
            back = time.perf_counter()

            async def ready() -> bool:
                held = {n.name: (await n.get("/cluster"))["held"] for n in c.nodes}
                states = await c.states(c.node("node-a"))
                every = sorted(d for drones in held.values() for d in drones)
                return (
                    every == sorted(c.drone_ids)
                    and all(len(mavsdk_servers_of(n.proc.pid)) == len(held[n.name]) for n in c.nodes)
                    and all(states.get(d) == "ready" for d in c.drone_ids)
                )

            ready_s = await until(ready, "every drone ready under one sidecar", 120, back)

            async def written() -> bool:
                return all(log_has(n, "are written") for n in c.nodes if log_has(n, "kept on this node"))

            await eventually(written, "the kept writes written", within_s=60)
            return {
                "stop_answer_s": answered,
                "in_land_s": in_land,
                "fenced_s": fence,
                "ready_after_return_s": ready_s,
                "kept_written": float(kept_written(c.nodes)),
            }


async def nats_cut() -> dict[str, float]:
    made: dict[str, TcpProxy] = {}

    def via(name: str, url: str) -> str:
        if name != "node-b":
            return url
        target = urlparse(url)
        made[name] = proxy = TcpProxy(target.hostname or "127.0.0.1", target.port or 4222)
        return f"nats://127.0.0.1:{proxy.port}"

    workdir = Path(tempfile.mkdtemp(prefix="bench-faults-"))
    try:
        async with cluster(workdir, drones=2, nodes=2, speedup=5.0, nats_via=via) as c:
            owners = await wait_spread(c)
            on_a = next(d for d, n in owners.items() if n == "node-a")
            on_b = next(d for d, n in owners.items() if n == "node-b")
            made["node-b"].cut()
            out: dict[str, float] = {}
            async with c.node("node-a").client(name="a") as mcp_a, c.node("node-b").client(name="b") as mcp_b:
                for label, mcp, drone in (("to_cut_off_s", mcp_a, on_b), ("from_cut_off_s", mcp_b, on_a)):
                    started = time.perf_counter()
                    r = await mcp.call_tool("takeoff", {"drone_id": drone, "alt_m": 10})
                    out[label] = time.perf_counter() - started
                    assert r.is_error and "it was not run" in r.content[0].text, r
            made["node-b"].heal()
            return out
    finally:
        for proxy in made.values():
            proxy.close()


def main() -> int:
    args = common.parser(__doc__.splitlines()[0]).parse_args()
    why = missing_engines() or (
        None if find_pg_bin("postgres") else "PostgreSQL server binaries are not installed"
    )
    if why:
        print(f"skipped: {why}")
        return 0
    info = common.machine()
    print(common.machine_line(info))
    pg = asyncio.run(postgres_outage())
    cut = asyncio.run(nats_cut())
    body = common.table(
        ["fault", "figure", "value"],
        [
            [
                "PostgreSQL stopped (20 s), 3 drones in the air",
                "both nodes fenced, no sidecar left (10 s lease)",
                f"{pg['fenced_s']:.1f} s",
            ],
            ["", "then emergency stop (land) answered", f"{pg['stop_answer_s'] * 1000:.0f} ms"],
            ["", "every drone in LAND after the stop", f"{pg['in_land_s']:.2f} s"],
            [
                "",
                "PostgreSQL back: every drone ready under one sidecar",
                f"{pg['ready_after_return_s']:.1f} s",
            ],
            ["", "writes kept on the nodes and written late", f"{pg['kept_written']:.0f}"],
            [
                "node B cut off from NATS",
                "command forwarded to it: 'not run'",
                f"{cut['to_cut_off_s']:.2f} s",
            ],
            ["", "command it forwards: 'not run'", f"{cut['from_cut_off_s']:.2f} s"],
        ],
    )
    print(body)
    if args.write:
        common.write_section("cluster-faults", "Cluster under engine faults", body, info)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
