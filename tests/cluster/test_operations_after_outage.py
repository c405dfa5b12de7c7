"""Operations under a PostgreSQL outage, with real PostgreSQL, NATS, gateway nodes, sidecars and simulated
drones: no operation stays ``running`` in the database once its flight is over.

Two nodes, four drones in the air (two owned by each), a long move of each: one of each node sent before
PostgreSQL is killed (its row stored as running), the other just after (its row kept in its node's
spool). Which node takes which drone once PostgreSQL is back is a race: a drone taken again by the node
that had it, and one taken by the other node before the first node's spool wrote its move, are each a
way an operation used to stay running; four drones make at least one of them likely in every run. Both nodes
fence themselves; the emergency stop lands the drones over the fenced nodes' own links; PostgreSQL comes
back, the drones are taken over again (by the node that had them, or by the other one) and are on the
ground. Then every operation of the case has ended in the database, each move as what happened to it (the
drone landed before arriving: not ``succeeded``), and the next takeoff is not refused by a move that is
long over.
"""

from __future__ import annotations

import asyncio
import contextlib
import os
import signal
from pathlib import Path
from typing import Any

import pytest
from mcp.types import CallToolResult

from tests.cluster.fault_matrix import one_sidecar_each, take_off, wait_gone
from tests.cluster.harness import Node, cluster, missing_engines, wait_spread
from tests.helpers.timing import eventually, scaled
from tests.persist.pg import find_pg_bin, restartable_postgres

pytestmark = [
    pytest.mark.timeout(scaled(420)),
    pytest.mark.skipif(missing_engines() is not None, reason=str(missing_engines())),
    pytest.mark.skipif(
        not (find_pg_bin("initdb") and find_pg_bin("postgres")),
        reason="this test kills and starts its own PostgreSQL server: its binaries are not installed",
    ),
]

#: far enough that no move arrives before the stop lands the drones (5x speed-up)
MOVE_NORTH_M = 600
FENCED = "could not renew its leases in time"


def ok(r: CallToolResult) -> dict[str, Any]:
    assert not r.is_error, r.content[0].text if r.content else r
    assert r.structured_content is not None
    return r.structured_content


def log_from(node: Node, since: int) -> str:
    with node.log.open("rb") as fh:
        fh.seek(since)
        return fh.read().decode(errors="replace")


async def test_no_operation_stays_running_after_postgresql_was_killed(tmp_path: Path) -> None:
    with restartable_postgres() as pg:
        async with cluster(tmp_path, drones=4, nodes=2, speedup=5.0, database_server=pg.url) as c:
            owners = await wait_spread(c)
            mine = {name: sorted(d for d, n in owners.items() if n == name) for name in ("node-a", "node-b")}
            assert [len(drones) for drones in mine.values()] == [2, 2], owners
            # one move of each node stored before the kill, the other kept in its node's spool
            before = [mine["node-a"][0], mine["node-b"][0]]
            after = [mine["node-a"][1], mine["node-b"][1]]
            await take_off(c.node("node-a"), c.drone_ids)
            since = {n.name: n.log.stat().st_size for n in c.nodes}
            move = {"north_m": MOVE_NORTH_M, "east_m": 0, "wait": False}
            async with c.node("node-a").client(name="mover") as mcp:
                for drone in before:
                    ok(await mcp.call_tool("move_to_relative", {"drone_id": drone, **move}))

                async def stored() -> bool:
                    rows = await c.rows(
                        "SELECT status FROM operations WHERE kind = 'move_to_relative' AND status = 'running'"
                    )
                    return len(rows) == len(before)

                await eventually(stored, f"the moves of {before} stored as running", within_s=10)
                assert pg.proc is not None
                os.killpg(pg.proc.pid, signal.SIGKILL)
                pg.proc.wait(timeout=scaled(10))
                # a node may fence itself before its move is sent (the lease's 80 %): then it is not run
                answers = await asyncio.gather(
                    *(mcp.call_tool("move_to_relative", {"drone_id": d, **move}) for d in after)
                )
            moved = before + [d for d, r in zip(after, answers, strict=True) if not r.is_error]

            async def fenced() -> bool:
                return all(FENCED in log_from(n, since[n.name]) for n in c.nodes)

            await eventually(fenced, "both nodes fenced themselves", within_s=30)
            response = await c.node("node-a").post("/fleet/stop", {"action": "land"})
            assert response.status_code == 200, response.text

            async def grounded() -> bool:
                truths = [await c.true_state(d) for d in c.drone_ids]
                return all(not t["armed"] and t["rel_alt_m"] < 0.5 for t in truths)

            await eventually(grounded, "every drone landed and disarmed", within_s=90)
            wait_gone(pg)
            pg.proc = None
            pg.start()
            await eventually(lambda: one_sidecar_each(c), "every drone ready under one sidecar", within_s=90)

            # every operation's flight is over (the drones are on the ground): none stays running
            rows: list[Any] = []

            async def none_running() -> bool:
                rows[:] = await c.rows(
                    "SELECT id, vehicle_id, kind, status, message FROM operations ORDER BY created_at"
                )
                return not [r for r in rows if r[3] == "running"]

            try:
                await eventually(none_running, "no operation running in the database", within_s=60)
            except AssertionError as exc:
                logs = "\n".join(f"--- {n.name}\n{log_from(n, since[n.name])[-6000:]}" for n in c.nodes)
                raise AssertionError(f"{exc}; operations {rows}\n{logs}") from None
            moves = {r[1]: (r[3], r[4]) for r in rows if r[2] == "move_to_relative"}
            assert sorted(moves) == sorted(moved), rows
            for drone, (status, message) in moves.items():
                # the drone was landed by the stop before it arrived
                assert status in ("failed", "interrupted", "superseded"), (drone, status, message)
            for node in c.nodes:
                running = await node.get("/operations", status="running")
                assert running["items"] == [], (node.name, running)

            # nothing that is long over holds a drone back: the next takeoff of each succeeds
            await wait_spread(c)
            for drone in c.drone_ids:
                with contextlib.suppress(Exception):
                    await c.node("node-b").delete(f"/vehicles/{drone}/takeover")
            await c.node("node-b").delete("/fleet/lock")
            await take_off(c.node("node-b"), c.drone_ids)
            async with c.node("node-b").client(name="lander") as mcp:
                landed = await asyncio.gather(*(mcp.call_tool("land", {"drone_id": d}) for d in c.drone_ids))
            for r in landed:
                assert ok(r)["status"] == "succeeded", r
