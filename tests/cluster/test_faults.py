"""The cluster under its own engines' faults, with real PostgreSQL, NATS, sidecars and simulated drones:

- PostgreSQL stopped for 20 s under three drones in the air: every node fences itself (no sidecar left
  behind, whatever its flight log could not write); an emergency stop then still reaches every drone,
  sent by each fenced node over the drone's own link: a hold from one node, then a land from the other
  puts every drone into LAND; when PostgreSQL is back, each drone is ready
  again under exactly one sidecar, without restarting a node, the stop is in the audit with the time it
  was made, and its fleet lock is stored. SIGTERM ends every node.
- one node cut off from NATS (a TCP proxy the test controls, between the node and NATS): a command
  forwarded to it, and one it forwards, answer "not run" within the accept time; when the link heals, the
  owners drop both (they arrive after their deadline) and the drones stay on the ground. Cut off, the
  node still ends on SIGTERM.
"""

from __future__ import annotations

import asyncio
import contextlib
import json
import os
import re
import signal
import subprocess
from collections.abc import Iterator
from datetime import UTC, datetime
from pathlib import Path
from typing import Any
from urllib.parse import urlparse

import pytest
from mcp.types import CallToolResult
from sqlalchemy import text

from gateway.registry.store import Store
from tests.cluster.harness import (
    Node,
    cluster,
    missing_engines,
    start_node,
    stop_node,
    wait_node_ready,
    wait_spread,
)
from tests.helpers.tcpproxy import TcpProxy
from tests.helpers.timing import eventually, scaled
from tests.persist.pg import create_database, find_pg_bin, restartable_postgres
from tests.registry.procs import alive, mavsdk_servers_of

pytestmark = [
    pytest.mark.skipif(missing_engines() is not None, reason=str(missing_engines())),
    pytest.mark.skipif(
        not (find_pg_bin("initdb") and find_pg_bin("postgres")),
        reason="these tests stop and start their own PostgreSQL server: its binaries are not installed",
    ),
]


OUTAGE_S = 20.0


def ok(r: CallToolResult) -> dict[str, Any]:
    assert not r.is_error, r.content[0].text if r.content else r
    assert r.structured_content is not None
    return r.structured_content


def err(r: CallToolResult) -> str:
    assert r.is_error, r.structured_content
    return r.content[0].text


def sidecars(nodes: list[Node]) -> dict[str, list[int]]:
    return {n.name: mavsdk_servers_of(n.proc.pid) for n in nodes}


def log_has(node: Node, text: str) -> bool:
    return text in node.log.read_text(errors="replace")


async def take_off(node: Node, drone_ids: list[str], alt_m: float = 10.0) -> None:
    async with node.client(name="takeoff") as mcp:
        results = await asyncio.gather(
            *(mcp.call_tool("takeoff", {"drone_id": d, "alt_m": alt_m}) for d in drone_ids)
        )
    for r in results:
        assert ok(r)["status"] == "succeeded", r


async def test_postgresql_down_under_drones_in_the_air(tmp_path: Path) -> None:
    with restartable_postgres() as pg:
        async with cluster(
            tmp_path, drones=3, nodes=2, speedup=5.0, database_server=pg.url,
            extra_env={"GATEWAY_CLUSTER_LEASE_TTL_S": "6"},
        ) as c:  # fmt: skip
            await wait_spread(c)
            pids = {n.name: n.proc.pid for n in c.nodes}
            await take_off(c.node("node-a"), c.drone_ids)

            pg.stop()
            stopped_at = datetime.now(UTC)

            # no database: each node fences itself, and no sidecar is left behind
            def fenced() -> bool:
                return all(log_has(n, "could not renew its leases in time") for n in c.nodes)

            async def fenced_and_stopped() -> dict[str, list[int]] | None:
                found = sidecars(c.nodes)
                return found if fenced() and not any(found.values()) else None

            with contextlib.suppress(AssertionError):
                await eventually(fenced_and_stopped, "every node fenced, its sidecars stopped", within_s=30)
            assert fenced(), "\n".join(n.log_tail(20) for n in c.nodes)
            assert not any(sidecars(c.nodes).values()), sidecars(c.nodes)
            assert all(n.alive for n in c.nodes)
            modes = {d: (await c.true_state(d))["mode"] for d in c.drone_ids}
            assert "LAND" not in modes.values(), modes  # still flying their last command

            # a stop now that no node holds a link: each fenced node sends it over the drone's own link;
            # from either node, hold (a reposition to where the drone is) and then land
            response = await c.node("node-a").post("/fleet/stop", {"action": "hold"})
            assert response.status_code == 200, response.text
            held = {r["vehicle_id"]: r["outcome"] for r in response.json()["results"]}
            assert held == {d: "sent" for d in c.drone_ids}, response.json()

            async def accepted_by_every_autopilot() -> bool | None:  # the other node's send logs later
                logs = "".join(n.log.read_text(errors="replace") for n in c.nodes)
                said = (rf"{d}: hold sent over its own link by .*ACCEPTED" for d in c.drone_ids)
                took = (re.search(pattern, logs) for pattern in said)
                return all(took) or None

            await eventually(accepted_by_every_autopilot, "every autopilot accepting the hold", within_s=10)
            response = await c.node("node-b").post("/fleet/stop", {"action": "land"})
            assert response.status_code == 200, response.text
            stop = response.json()
            outcomes = {r["vehicle_id"]: r for r in stop["results"]}
            assert all(outcomes[d]["outcome"] == "sent" for d in c.drone_ids), outcomes
            assert stop["fleet_lock"]["scope"] == "*" and stop["fleet_lock"]["stored"] is False, stop

            async def all_landing() -> bool:
                modes = [(await c.true_state(d))["mode"] for d in c.drone_ids]
                return modes == ["LAND"] * len(c.drone_ids)

            await eventually(all_landing, "every drone in LAND after the stop", within_s=3)
            assert all(log_has(n, "sent over its own link by fenced node") for n in c.nodes), outcomes
            assert not any(sidecars(c.nodes).values()), sidecars(c.nodes)  # the links were only borrowed
            # the outage lasts as long as the one this is about (its leases expire in the meantime)
            await asyncio.sleep(max(0.0, OUTAGE_S - (datetime.now(UTC) - stopped_at).total_seconds()))

            pg.start()
            back_at = datetime.now(UTC)

            async def one_sidecar_each() -> dict[str, Any] | None:
                """Each drone held by one node, which runs one sidecar per drone it holds (the counts
                taken together: a handover for balance may be under way), and every drone ready."""
                held = {n.name: (await n.get("/cluster"))["held"] for n in c.nodes}
                found = sidecars(c.nodes)
                states = await c.states(c.node("node-a"))
                every = sorted(d for drones in held.values() for d in drones)
                if (
                    every == sorted(c.drone_ids)
                    and all(len(found[name]) == len(drones) for name, drones in held.items())
                    and all(states.get(d) == "ready" for d in c.drone_ids)
                ):
                    return {"held": held, "sidecars": found}
                return None

            await eventually(one_sidecar_each, "every drone ready under one sidecar", within_s=90)
            assert {n.name: n.proc.pid for n in c.nodes if n.alive} == pids  # no node was restarted

            async def stops_audited() -> list[Any] | None:
                rows = await c.rows("SELECT t FROM audit WHERE action = 'rest.fleet_stop' ORDER BY t")
                return rows if len(rows) >= 2 else None

            rows = await eventually(
                stops_audited, "both stops' audit rows after the database is back", within_s=30
            )
            assert len(rows) == 2, rows  # the hold and the land
            for (t,) in rows:  # the time each was made
                t = t if t.tzinfo else t.replace(tzinfo=UTC)
                assert stopped_at.timestamp() - 1 < t.timestamp() < back_at.timestamp(), (t, stopped_at)
            assert [r[0] for r in await c.rows("SELECT scope FROM locks")] == ["*"]

            # SIGTERM ends every node, sidecars and all
            running = [p for pids_of in sidecars(c.nodes).values() for p in pids_of]
            for node in c.nodes:
                os.kill(node.proc.pid, signal.SIGTERM)
            for node in c.nodes:
                try:
                    node.proc.wait(timeout=scaled(30))
                except subprocess.TimeoutExpired:
                    raise AssertionError(f"{node.name} did not end on SIGTERM:\n{node.log_tail()}") from None
            assert not [p for p in running if alive(p)]


@contextlib.contextmanager
def proxies() -> Iterator[dict[str, TcpProxy]]:
    made: dict[str, TcpProxy] = {}
    try:
        yield made
    finally:
        for proxy in made.values():
            proxy.close()


async def test_a_node_cut_off_from_nats_runs_no_late_command(tmp_path: Path) -> None:
    with proxies() as made:

        def via(name: str, url: str) -> str:
            if name != "node-b":
                return url
            target = urlparse(url)
            made[name] = proxy = TcpProxy(target.hostname or "127.0.0.1", target.port or 4222)
            return f"nats://127.0.0.1:{proxy.port}"

        async with cluster(tmp_path, drones=2, nodes=2, speedup=5.0, nats_via=via) as c:
            owners = await wait_spread(c)
            on_a = next(d for d, n in owners.items() if n == "node-a")
            on_b = next(d for d, n in owners.items() if n == "node-b")
            node_a, node_b = c.node("node-a"), c.node("node-b")

            made["node-b"].cut()
            async with (
                node_a.client(name="to-the-cut-off-owner") as mcp_a,
                node_b.client(name="cut-off") as mcp_b,
            ):
                to_b, from_b = await asyncio.gather(
                    mcp_a.call_tool("takeoff", {"drone_id": on_b, "alt_m": 10}),
                    mcp_b.call_tool("takeoff", {"drone_id": on_a, "alt_m": 10}),
                )
            for text in (err(to_b), err(from_b)):
                assert "did not accept takeoff" in text and "it was not run" in text, text
            made["node-b"].heal()

            # both calls reach their owners once the link heals, late: each owner drops its call
            async def both_dropped() -> bool:
                return log_has(node_b, "dropped takeoff from node-a") and log_has(
                    node_a, "dropped takeoff from node-b"
                )

            await eventually(both_dropped, "each owner dropped the late takeoff", within_s=60)
            for drone in (on_a, on_b):
                truth = await c.true_state(drone)
                assert not truth["armed"] and truth["rel_alt_m"] < 0.5, (drone, truth)
            # the cluster works again across the healed link
            await wait_spread(c)
            async with node_a.client(name="after") as mcp:
                assert ok(await mcp.call_tool("get_parameter", {"drone_id": on_b, "name": "WPNAV_SPEED"}))
            # cut off again, SIGTERM still ends the node (its bus connection cannot hold it)
            made["node-b"].cut()
            its_sidecars = mavsdk_servers_of(node_b.proc.pid)
            assert its_sidecars
            os.kill(node_b.proc.pid, signal.SIGTERM)
            try:
                node_b.proc.wait(timeout=scaled(30))
            except subprocess.TimeoutExpired:
                raise AssertionError(f"node-b did not end on SIGTERM:\n{node_b.log_tail()}") from None
            assert not [p for p in its_sidecars if alive(p)]


async def test_writes_kept_during_an_outage_survive_a_kill_9(tmp_path: Path) -> None:
    """A gateway killed (-9) while the database is down keeps what it could not write in its spool file;
    started again once the database is back, it writes those rows first, in order, with their times."""
    spool = tmp_path / "gw" / "spool.jsonl"
    with restartable_postgres() as pg:
        store = await Store.open(await create_database(pg.url))  # the schema, made once
        url = store.url
        await store.close()
        env = {"GATEWAY_SPOOL_PATH": str(spool)}
        node = start_node("gw", url, "", tmp_path, env)
        try:
            await wait_node_ready(node, 60)
            pg.stop()
            outage = datetime.now(UTC)
            for action in ("hold", "land", "hold"):
                response = await node.post("/fleet/stop", {"action": action})
                assert response.status_code == 200, response.text
                assert response.json()["fleet_lock"]["stored"] is False

            async def kept() -> list[dict[str, Any]] | None:
                lines = [json.loads(x) for x in spool.read_text().splitlines()] if spool.exists() else []
                audit = [x for x in lines if x.get("kind", "").startswith("audit")]
                return lines if len(audit) >= 1 and any(x.get("kind") == "lock" for x in lines) else None

            lines = await eventually(kept, "the stops' audit rows and lock in the spool file", within_s=30)
            node.kill9()
            assert spool.exists() and not any("done" in x for x in lines), lines
            killed = datetime.now(UTC)

            pg.start()
            node = start_node("gw", url, "", tmp_path, env)
            await wait_node_ready(node, 60)
            rows = await _rows(
                url, "SELECT action, t FROM audit WHERE action = 'rest.fleet_stop' ORDER BY id"
            )
            assert len(rows) == 3, rows
            for _action, t in rows:  # the time each stop was made, not when it was written
                t = t if t.tzinfo else t.replace(tzinfo=UTC)
                assert outage.timestamp() - 1 < t.timestamp() < killed.timestamp(), (t, outage, killed)
            assert [r[0] for r in await _rows(url, "SELECT scope FROM locks")] == ["*"]
            assert not spool.exists()  # all written: nothing waits
            assert log_has(node, "writes kept by this node's previous run")
        finally:
            stop_node(node)


async def _rows(url: str, sql: str) -> list[Any]:
    store = await Store.open(url, upgrade=False)
    try:
        async with store.engine.connect() as conn:
            return list((await conn.execute(text(sql))).all())
    finally:
        await store.close()
