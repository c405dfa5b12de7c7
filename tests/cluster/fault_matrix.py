"""The emergency stop under each fault of the cluster's engines and nodes: one case per fault and node the
stop is sent through (every node that survives the fault), shared by tests/cluster/test_fault_matrix.py
(which asserts) and bench/cluster_matrix.py (which prints the figures).

Two nodes, four simulated drones in the air (two owned by each), every node's NATS and PostgreSQL
connections through proxies the case controls (cut, or delayed: a slow database), which run in a process
of their own (`tests.cluster.proxies`). Each case:

1. the fault (:data:`MATRIX`);
2. an agent's move through the stopping node for a drone the other node owns: it must be answered in
   time (run, or refused as not run), and never run later;
3. the emergency stop (land) through the case's node (each node that survives the fault has a case of
   its own): every drone in LAND as the simulator has it within
   3 s (a deadline on the wait, from the moment the stop is sent), and every drone's outcome ``sent``;
   a drone whose node is frozen while it holds the drone's link cannot be reached by anyone: it answers
   ``sent`` or ``taking_over`` (saying what is being done) and lands once that node runs again; the
   stop of a node cut from NATS reaches the other node's drones through PostgreSQL (both logs say so,
   and the other node stores a land operation for each);
4. recovery, then within 90 s every drone ready under exactly one sidecar, and the audit holding the stop
   and the move.

The cases run one after another on one cluster (:meth:`Rig.prepare` between them: a killed node started
again, batteries full, the fleet lock and any takeover lock released, the drones on the ground, two owned
by each node).
"""

from __future__ import annotations

import asyncio
import contextlib
import os
import signal
import time
from collections.abc import AsyncIterator
from dataclasses import dataclass
from datetime import UTC, datetime, timedelta
from pathlib import Path
from typing import Any
from urllib.parse import urlparse

import httpx

from tests.cluster.harness import (
    Cluster,
    Node,
    cluster,
    freeze,
    kill_nats,
    restart_nats,
    start_node,
    stop_node,
    thaw,
    wait_node_ready,
    wait_spread,
)
from tests.cluster.proxies import RemoteProxy, proxy_process
from tests.helpers.timing import eventually, scaled
from tests.persist.pg import PostgresServer, restartable_postgres
from tests.registry.procs import mavsdk_servers_of

BOTH = ("node-a", "node-b")
#: fault -> the nodes the stop is sent through, one case each: every node that survives the fault (a
#: frozen or killed node answers nobody)
MATRIX: dict[str, tuple[str, ...]] = {
    "nats-killed": BOTH,
    "nats-frozen": BOTH,
    "postgresql-killed": BOTH,
    "postgresql-frozen": BOTH,
    "slow-database": BOTH,
    "node-a-frozen": ("node-b",),
    "node-a-cut-from-nats": BOTH,
    "node-a-cut-from-postgresql": BOTH,
    "node-a-killed": ("node-b",),
}
#: every case: (fault, the node the stop is sent through)
CASES = [(fault, via) for fault, nodes in MATRIX.items() for via in nodes]
#: a slow database: every chunk each way through its proxy held this long
SLOW_DATABASE_S = 1.0
#: the stop's deadline: every drone in LAND within this of the stop being sent
STOP_DEADLINE_S = 3.0
#: a forwarded move is refused within this, or runs: the accept time (3 s), the clock margin the caller
#: waits past it (0.5 s) and the MCP round trip
MOVE_ANSWER_S = 5.0
#: a move its owner accepted is answered within this: done (30 m at the simulator's 5x), or cut short
#: when its owner fences itself (the 3 s lease's fence, 80% of it after the last renewal)
MOVE_RUN_ANSWER_S = 15.0
#: the answer of a move its owner accepted and then gave the drone up (`gateway.errors.OwnerFenced`)
CUT_SHORT = "not finished: node"


@dataclass
class Rig:
    c: Cluster
    pg: PostgresServer
    nats_proxies: dict[str, RemoteProxy]
    db_proxies: dict[str, RemoteProxy]

    def inject(self, fault: str) -> None:
        c, pg = self.c, self.pg
        if fault == "nats-killed":
            kill_nats(c.nats)
        elif fault == "nats-frozen":
            freeze(c.nats.proc)
        elif fault == "postgresql-killed":
            assert pg.proc is not None
            os.killpg(pg.proc.pid, signal.SIGKILL)
            pg.proc.wait(timeout=scaled(10))
        elif fault == "postgresql-frozen":
            assert pg.proc is not None
            freeze(pg.proc)
        elif fault == "slow-database":
            for proxy in self.db_proxies.values():
                proxy.delay_s = SLOW_DATABASE_S
        elif fault == "node-a-frozen":
            freeze(c.node("node-a").proc)
        elif fault == "node-a-killed":
            c.node("node-a").kill9()
        elif fault == "node-a-cut-from-nats":
            self.nats_proxies["node-a"].cut()
        elif fault == "node-a-cut-from-postgresql":
            self.db_proxies["node-a"].cut()
        else:
            raise ValueError(f"fault: one of {', '.join(MATRIX)}; got {fault!r}")

    async def prepare(self) -> dict[str, str]:
        """Ready for the next case: both nodes running (a killed one started again), the fleet unlocked,
        every drone on the ground and disarmed, two owned by each node and ready; the owners."""
        c = self.c
        for index, node in enumerate(c.nodes):
            if not node.alive:
                stop_node(node)
                env = node.env
                c.nodes[index] = again = start_node(
                    node.name, env["GATEWAY_DATABASE_URL"], env["GATEWAY_CLUSTER_NATS_URL"], c.workdir, c.env
                )
                await wait_node_ready(again, 90.0)
        for index in range(len(c.drone_ids)):  # a fresh battery: the cases fly one after another
            await c.sim.control.set_battery(index, 100.0)
        truths = [await c.true_state(d) for d in c.drone_ids]
        if any(t["armed"] for t in truths):  # a case that failed left some in the air
            await c.nodes[0].post("/fleet/stop", {"action": "land"})

        async def grounded() -> bool:
            truths = [await c.true_state(d) for d in c.drone_ids]
            return all(not t["armed"] and t["rel_alt_m"] < 0.5 for t in truths)

        await eventually(grounded, "every drone on the ground and disarmed", within_s=60)

        async def unlocked() -> bool:  # a lock a node kept while the database was down is written late
            # (a lock broadcast while NATS was down, delivered after this unlock, is dropped by every node:
            # gateway.cluster.lock_versions)
            response = await c.nodes[0].delete("/fleet/lock")
            assert response.status_code == 200, response.text
            # a land sent over a drone's own link by another node is a mode its owner did not command: a
            # takeover lock there, which the operator releases
            for d in c.drone_ids:
                response = await c.nodes[0].delete(f"/vehicles/{d}/takeover")
                assert response.status_code == 200, response.text
            views = [await n.get(p) for n in c.nodes for p in ("/locks", "/takeovers")]
            return not any(v["items"] for v in views) and not await c.rows("SELECT scope FROM locks")

        await eventually(unlocked, "the fleet unlocked on every node and in the database", within_s=40)

        async def even() -> dict[str, str] | None:
            # each node reads its fair share from the nodes it sees alive, so a node just started again can
            # be missing from it for a moment (the other then holds three): the cases need two each, which
            # the holder hands over once the restarted node counts
            owners = await wait_spread(c)
            held = sorted(owners.values())
            each = len(c.drone_ids) // len(c.nodes)
            return owners if held == sorted(n.name for n in c.nodes for _ in range(each)) else None

        owners = await eventually(even, "two drones owned by each node", within_s=90)

        still_running: list[Any] = []

        async def settled() -> bool:
            # a case's stop can still be travelling (a land a thawed node's drones get once their new owner
            # picks the stop's operations up): it would supersede the next case's takeoff
            still_running[:] = await c.rows(
                "SELECT id, vehicle_id, kind, message, updated_at FROM operations WHERE status = 'running'"
            )
            return not still_running

        await eventually(
            settled,
            "no operation of an earlier case still running",
            within_s=60,
            explain=lambda: [tuple(map(str, row)) for row in still_running],
        )
        return owners

    def recover(self, fault: str) -> None:
        c, pg = self.c, self.pg
        if fault == "nats-killed":
            restart_nats(c.nats, c.workdir)
        elif fault == "nats-frozen":
            thaw(c.nats.proc)
        elif fault == "postgresql-killed":
            pg.proc = None
            wait_gone(pg)
            pg.start()
        elif fault == "postgresql-frozen":
            assert pg.proc is not None
            thaw(pg.proc)
        elif fault == "slow-database":
            for proxy in self.db_proxies.values():
                proxy.delay_s = 0.0
        elif fault == "node-a-frozen":
            thaw(c.node("node-a").proc)
        elif fault == "node-a-cut-from-nats":
            self.nats_proxies["node-a"].heal()
        elif fault == "node-a-cut-from-postgresql":
            self.db_proxies["node-a"].heal()


def wait_gone(pg: PostgresServer) -> None:
    """Until the killed postmaster named in its pid file is gone (a start before that is refused)."""
    pid_file = pg.data / "postmaster.pid"
    deadline = time.monotonic() + scaled(20)
    while time.monotonic() < deadline:
        try:
            pid = int(pid_file.read_text().split()[0])
            os.kill(pid, 0)
        except (OSError, ValueError, IndexError):
            return
        time.sleep(0.1)


@contextlib.asynccontextmanager
async def rig(workdir: Path) -> AsyncIterator[Rig]:
    """The cluster of a case: PostgreSQL the case can kill and freeze, and every node's connections to
    NATS and PostgreSQL through proxies of its own."""
    with restartable_postgres() as pg, proxy_process() as proxies:
        nats_proxies: dict[str, RemoteProxy] = {}
        db_proxies: dict[str, RemoteProxy] = {}

        def nats_via(name: str, url: str) -> str:
            proxy = nats_proxies[name] = proxies.open("127.0.0.1", urlparse(url).port or 4222)
            return f"nats://127.0.0.1:{proxy.port}"

        def database_via(name: str, url: str) -> str:
            port = urlparse(url.replace("postgresql+asyncpg", "postgresql")).port or 5432
            proxy = db_proxies[name] = proxies.open("127.0.0.1", port)
            return url.replace(f":{port}/", f":{proxy.port}/")

        async with cluster(
            workdir, drones=4, nodes=2, speedup=5.0, database_server=pg.url, nats_via=nats_via,
            database_via=database_via,
        ) as c:  # fmt: skip
            yield Rig(c, pg, nats_proxies, db_proxies)


def _log_has(node: Node, text: str, since: int = 0) -> bool:
    return text in _log_since(node, since, keep_chars=None)


def _log_since(node: Node, since: int, keep_chars: int | None = 6000) -> str:
    """The node's log from byte ``since`` on; its last ``keep_chars`` (a failure's message names what
    the node said, its traceback first of all)."""
    with node.log.open("rb") as fh:
        fh.seek(since)
        text = fh.read().decode(errors="replace")
    return text if keep_chars is None else text[-keep_chars:]


async def one_sidecar_each(c: Cluster) -> dict[str, Any] | None:
    """Each drone held by one live node, which runs one sidecar per drone it holds, and every drone
    ready as every live node sees it."""
    held = {n.name: (await n.get("/cluster"))["held"] for n in c.live_nodes}
    found = {n.name: mavsdk_servers_of(n.proc.pid) for n in c.live_nodes}
    every = sorted(d for drones in held.values() for d in drones)
    states = [await c.states(n) for n in c.live_nodes]
    if (
        every == sorted(c.drone_ids)
        and all(len(found[name]) == len(drones) for name, drones in held.items())
        and all(s.get(d) == "ready" for s in states for d in c.drone_ids)
    ):
        return {"held": held, "sidecars": found}
    return None


async def take_off(node: Node, drone_ids: list[str], alt_m: float = 10.0, attempts: int = 3) -> None:
    """Every drone up, each takeoff succeeded. A takeoff superseded by a landing is sent again (at most
    ``attempts`` times in all): under load, a stop an earlier case sent to a node then frozen reached the
    drone after this case's preparation (seen once in a full run beside a model server, load 3.5); the
    case's own checks start after this."""
    pending = list(drone_ids)
    async with node.client(name="takeoff") as mcp:
        for _ in range(attempts):
            results = await asyncio.gather(
                *(mcp.call_tool("takeoff", {"drone_id": d, "alt_m": alt_m}) for d in pending)
            )
            for r in results:
                assert not r.is_error and r.structured_content is not None, r
                assert r.structured_content["status"] in ("succeeded", "superseded"), r
            statuses = [(r.structured_content or {}).get("status") for r in results]
            pending = [d for d, status in zip(pending, statuses, strict=True) if status != "succeeded"]
            if not pending:
                return
    raise AssertionError(f"takeoff of {pending} superseded {attempts} times: {results}")


async def _relayed_through_postgresql(
    c: Cluster, foreign: list[str], outcomes: dict[str, Any], log_from: dict[str, int]
) -> None:
    """The stop of node-a cut from NATS reached node-b's drones through PostgreSQL notifications: both
    logs say so, and node-b ran and stored a land operation for each (the ids in the stop's outcomes)."""
    assert _log_has(c.node("node-a"), "relayed through PostgreSQL to node node-b", log_from["node-a"])
    for d in foreign:
        said = f"{d}: land relayed through PostgreSQL from node node-a"
        assert _log_has(c.node("node-b"), said, log_from["node-b"]), d
    ops = {d: outcomes[d]["operation_id"] for d in foreign}
    assert all(ops.values()), outcomes

    async def stored() -> list[Any] | None:
        rows = await c.rows(
            "SELECT vehicle_id FROM operations WHERE kind = 'land' AND id = ANY(:ids)", ids=list(ops.values())
        )
        return rows if len(rows) == len(ops) else None

    rows = await eventually(stored, "node-b's land operations of the relayed stop", within_s=30)
    assert sorted(r[0] for r in rows) == foreign, rows


async def _is(value: bool) -> bool:
    return value


async def run_case(r: Rig, fault: str, via: str) -> dict[str, Any]:
    """One case of the matrix on the rig (cases run one after another on one rig): ``fault``, the stop
    sent through node ``via``; its checks asserted; what it measured (seconds, and the outcomes)."""
    if via not in MATRIX[fault]:
        raise ValueError(f"via: for {fault}, one of {', '.join(MATRIX[fault])}; got {via!r}")
    clock = asyncio.get_running_loop().time
    figures: dict[str, Any] = {"via": via}
    c = r.c
    owners = await r.prepare()
    case_began = datetime.now(UTC)  # the audit from here on: this case's calls
    assert sorted(owners.values()) == ["node-a", "node-a", "node-b", "node-b"], owners
    await take_off(c.node("node-a"), c.drone_ids)
    stopper = c.node(via)
    other = "node-b" if via == "node-a" else "node-a"
    foreign = sorted(d for d, n in owners.items() if n == other)
    on_a = sorted(d for d, n in owners.items() if n == "node-a")
    held_by_frozen = on_a if fault == "node-a-frozen" else []

    log_from = {name: c.node(name).log.stat().st_size for name in ("node-a", "node-b")}
    r.inject(fault)
    if fault == "node-a-cut-from-postgresql":  # the stop after it fenced itself (else: as no fault)
        fenced = "could not renew its leases in time"
        await eventually(
            lambda: _is(_log_has(c.node("node-a"), fenced, log_from["node-a"])), "node-a fenced", within_s=30
        )
    pending: list[str] = []
    try:
        async with stopper.client(name="mover") as mcp:
            began, move_sent = clock(), datetime.now(UTC)
            moving = asyncio.ensure_future(
                mcp.call_tool("move_to_relative", {"drone_id": foreign[0], "north_m": 30, "east_m": 0})
            )
            try:  # a refusal comes within the accept time (plus the MCP round trip), or not at all
                move = await asyncio.wait_for(asyncio.shield(moving), scaled(MOVE_ANSWER_S))
            except TimeoutError:  # past it only a move that runs may answer (its owner accepted it): done,
                # or cut short when its owner fenced itself, as soon as it did
                move = await asyncio.wait_for(moving, scaled(MOVE_RUN_ANSWER_S - MOVE_ANSWER_S))
            text = str(move.content[0].text if move.content else move)
            kind = ("cut short" if CUT_SHORT in text else "refused") if move.is_error else "run"
            if clock() - began > scaled(MOVE_ANSWER_S):
                assert kind != "refused", f"{fault} via {via}: the move was refused late: {text}"
            figures["move_answer_s"] = round(clock() - began, 2)
            figures["move"] = kind
            figures["move_answer"] = text[:200]
        # the stop's HTTP client made before the clock starts: making one (its TLS context) is work of the
        # test's process, not of the stop
        async with httpx.AsyncClient(base_url=stopper.base_url, timeout=scaled(60)) as stop_http:
            sent_at, began = datetime.now(UTC), clock()
            stop = asyncio.create_task(stop_http.post("/api/v1/fleet/stop", json={"action": "land"}))
            landing = [d for d in c.drone_ids if d not in held_by_frozen]
            seen: dict[str, str] = {}

            async def all_landing() -> dict[str, str] | None:
                # every drone read at once: one round trip to the simulator per reading, not one per drone
                # (four round trips to a starved simulator, one after another, counted in the figure)
                truths = await asyncio.gather(*(c.true_state(d) for d in landing))
                seen.update({d: t["mode"] for d, t in zip(landing, truths, strict=True)})
                if set(seen.values()) != {"LAND"}:
                    return None
                figures.setdefault("stop_to_land_s", round(clock() - began, 2))
                return seen

            try:
                await eventually(
                    all_landing, f"{fault} via {via}: every drone in LAND", within_s=STOP_DEADLINE_S
                )
            except AssertionError as exc:
                answer = (await stop).text
                raise AssertionError(
                    f"{exc}; modes {seen}; the stop's answer {answer}; {via}'s log since the fault:\n"
                    + _log_since(stopper, log_from[via])
                ) from None
            finally:
                response = await stop
                figures["stop_answer_s"] = round(clock() - began, 2)
        assert response.status_code == 200, response.text
        outcomes = {x["vehicle_id"]: x for x in response.json()["results"]}
        figures["outcomes"] = {d: x["outcome"] for d, x in sorted(outcomes.items())}
        # sent; or taking over, saying how (a drone another node has just taken over, its link coming
        # up, or one whose link the frozen node holds): in LAND all the same, but for the frozen node's
        for d in c.drone_ids:
            assert outcomes[d]["outcome"] in ("sent", "taking_over"), outcomes
            if outcomes[d]["outcome"] == "taking_over":
                assert "keeps trying" in (outcomes[d]["message"] or ""), outcomes
        if fault == "node-a-cut-from-nats" and via == "node-a":
            await _relayed_through_postgresql(c, foreign, outcomes, log_from)
        pending += held_by_frozen  # checked in LAND once node-a runs again
    finally:
        r.recover(fault)
    recovered = clock()
    if pending:  # node-a runs again, finds its leases gone and lets go of the links: node-b lands them

        async def landing_late() -> dict[str, str] | None:
            modes = {d: (await c.true_state(d))["mode"] for d in pending}
            return modes if set(modes.values()) == {"LAND"} else None

        await eventually(landing_late, f"{fault} via {via}: {pending} in LAND once node-a runs", within_s=60)
        figures["frozen_node_drones_land_after_thaw_s"] = round(clock() - recovered, 2)

    what = f"{fault} via {via}"
    ready = await eventually(lambda: one_sidecar_each(c), f"{what}: every drone ready under one sidecar",
                             within_s=90)  # fmt: skip
    figures["ready_after_recovery_s"] = round(clock() - recovered, 2)
    figures["held"] = ready["held"]

    # every call of the case has its row, once (the autopilot's takeover rows aside): four takeoffs, the
    # move (refused or run) and the stop
    made = sorted(["takeoff"] * len(c.drone_ids) + ["move_to_relative", "rest.fleet_stop"])
    rows: list[Any] = []

    async def audited() -> list[Any] | None:
        rows[:] = await c.rows(
            "SELECT action, outcome FROM audit WHERE t >= :t AND principal IS DISTINCT FROM 'autopilot' "
            "ORDER BY t", t=case_began,
        )  # fmt: skip
        every = sorted(x[0] for x in rows) == made
        return rows if every and "running" not in {x[1] for x in rows} else None

    try:  # each call once, and each one's end recorded (none left running after recovery)
        await eventually(audited, f"{what}: every call of the case in the audit, ended", within_s=30)
    except AssertionError as exc:
        raise AssertionError(f"{exc}; rows {rows}") from None
    # when the stop reached its node, by the node's clock (its audit row: written at the end of the
    # request, with the request's duration): the part of stop -> LAND spent before the node had the stop
    timing = await c.rows(
        "SELECT t, duration_ms FROM audit WHERE action = 'rest.fleet_stop' AND t >= :t", t=case_began
    )
    if len(timing) == 1 and timing[0][1] is not None:
        written = timing[0][0] if timing[0][0].tzinfo else timing[0][0].replace(tzinfo=UTC)
        reached = written - timedelta(milliseconds=timing[0][1])
        figures["stop_reached_node_s"] = round((reached - sent_at).total_seconds(), 2)
    outcome = {action: result for action, result in rows if action != "takeoff"}
    assert outcome["rest.fleet_stop"] == "ok", rows
    assert [result for action, result in rows if action == "takeoff"] == ["ok"] * len(c.drone_ids), rows
    # refused, or cut short when its owner fenced itself: an error; run: ok
    assert outcome["move_to_relative"] == ("error" if move.is_error else "ok"), rows
    # the move never ran late: refused, no operation of it after it was sent; run (or cut short), none
    # after the stop
    late = await c.rows(
        "SELECT kind, created_at FROM operations WHERE vehicle_id = :d AND created_at > :t "
        "AND kind NOT IN ('land', 'return_to_launch')",
        d=foreign[0], t=move_sent if kind == "refused" else sent_at,
    )  # fmt: skip
    assert not late, late
    return figures
