"""Three gateway nodes on one PostgreSQL and one NATS (both started here from the installed packages),
nine simulated drones, real sidecars, real MCP clients over Streamable HTTP and real REST.

The tests share one cluster (module scope) and run in file order: ownership and the whole-fleet view,
then operator lock and emergency stop from node B, then the loss of node C (kill -9) with drones in the
air and the takeover. Every MCP and REST call made is counted, and the audit table must hold exactly
that many rows.
"""

from __future__ import annotations

import asyncio
import contextlib
import json
from collections.abc import AsyncIterator
from pathlib import Path
from typing import Any

import pytest
import pytest_asyncio
from mcp.types import CallToolResult

from gateway.fleet import geo
from tests.cluster.harness import SCOPED_TOKEN, Cluster, Node, cluster, missing_engines, wait_spread
from tests.helpers.timing import eventually, scaled
from tests.registry.procs import alive, mavsdk_servers_of

pytestmark = [
    pytest.mark.asyncio(loop_scope="module"),
    pytest.mark.skipif(missing_engines() is not None, reason=str(missing_engines())),
]


class Calls:
    """Counts every audited call the tests make (MCP tools/call and state-changing REST)."""

    def __init__(self) -> None:
        self.count = 0

    async def tool(self, client: Any, tool: str, args: dict[str, Any], **kw: Any) -> CallToolResult:
        self.count += 1
        return await client.call_tool(tool, args, **kw)

    async def post(self, node: Node, path: str, body: Any = None) -> Any:
        self.count += 1
        response = await node.post(path, body)
        assert response.status_code < 400, response.text
        return response.json()

    async def delete(self, node: Node, path: str) -> Any:
        self.count += 1
        response = await node.delete(path)
        assert response.status_code < 400, response.text
        return response.json()


@pytest_asyncio.fixture(scope="module", loop_scope="module")
async def cl(tmp_path_factory: pytest.TempPathFactory) -> AsyncIterator[Cluster]:
    workdir: Path = tmp_path_factory.mktemp("cluster")
    async with cluster(workdir, drones=9, nodes=3, speedup=5.0, vehicle_tags={"d4": ["north"]}) as c:
        c.calls = Calls()  # type: ignore[attr-defined]
        c.sidecars_seen = set()  # type: ignore[attr-defined]
        yield c
        seen = set(c.sidecars_seen)  # type: ignore[attr-defined]
    assert not [p for p in seen if alive(p)], "a mavsdk_server survived the cluster"


def ok(r: CallToolResult) -> dict[str, Any]:
    assert not r.is_error, r.content[0].text if r.content else r
    assert r.structured_content is not None
    return r.structured_content


def err(r: CallToolResult) -> str:
    assert r.is_error, r.structured_content
    return r.content[0].text


def parent_pid(pid: int) -> int:
    return int(Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[1])


def by_owner(owners: dict[str, str]) -> dict[str, list[str]]:
    out: dict[str, list[str]] = {}
    for vid, node in sorted(owners.items()):
        out.setdefault(node, []).append(vid)
    return out


async def take_off(c: Cluster, node: Node, drone_ids: list[str], alt_m: float = 10.0) -> None:
    """Every drone up, each takeoff succeeded. The module's drones fly test after test: each gets a full
    battery first (a run slowed by load drained one to 25 %, below the takeoff minimum), and a takeoff
    refused because its owner has not heard the new battery yet (nothing was sent) is asked again."""
    calls: Calls = c.calls  # type: ignore[attr-defined]
    for d in drone_ids:
        await c.sim.control.set_battery(c.drone_ids.index(d), 100.0)
    async with node.client(name=f"takeoff-{node.name}") as mcp:

        async def takeoff(drone_id: str) -> CallToolResult:
            async def attempt() -> CallToolResult | None:
                r = await calls.tool(mcp, "takeoff", {"drone_id": drone_id, "alt_m": alt_m})
                text = r.content[0].text if r.is_error and r.content else ""  # type: ignore[union-attr]
                return None if "min_battery_takeoff" in text else r

            return await eventually(attempt, f"{drone_id}: a takeoff past the battery check", within_s=20)

        results = await asyncio.gather(*(takeoff(d) for d in drone_ids))
    for r in results:
        assert ok(r)["status"] == "succeeded", r


async def landed(c: Cluster, drone_ids: list[str]) -> bool:
    states = [await c.true_state(d) for d in drone_ids]
    return all(not s["armed"] and s["rel_alt_m"] < 0.5 for s in states)


async def test_each_drone_has_one_owner_and_every_node_sees_the_whole_fleet(cl: Cluster) -> None:
    owners = await wait_spread(cl)
    groups = by_owner(owners)
    assert sorted(groups) == ["node-a", "node-b", "node-c"] and sum(map(len, groups.values())) == 9
    sidecar_pids: set[int] = set()
    for node in cl.nodes:
        view = await node.get("/cluster")
        assert view["node_id"] == node.name and view["held"] == groups[node.name]
        for v in (await node.get("/vehicles"))["items"]:
            status = v["status"]
            if owners[v["id"]] == node.name:  # the owner runs the one sidecar, as its own child
                pid = status["sidecar"]["pid"]
                assert pid and parent_pid(pid) == node.proc.pid
                sidecar_pids.add(pid)
            else:  # everyone else holds a view fed by the owner's snapshots
                assert status["owner_node"] == owners[v["id"]] and status["sidecar"]["state"] == "remote"
                assert v["state"] == "ready" and status["snapshot_age_s"] < 3.0, status
    assert len(sidecar_pids) == 9
    assert sorted(sidecar_pids) == sorted(p for n in cl.nodes for p in mavsdk_servers_of(n.proc.pid))
    cl.sidecars_seen |= sidecar_pids  # type: ignore[attr-defined]
    # any node's MCP surface lists the whole fleet, with positions, from the telemetry cache
    async with cl.node("node-a").client(name="lister") as mcp:
        rows = ok(await cl.calls.tool(mcp, "list_drones", {}))  # type: ignore[attr-defined]
        status = ok(await cl.calls.tool(mcp, "fleet_status", {}))  # type: ignore[attr-defined]
    assert rows["count"] == 9
    for row in rows["drones"]:
        truth = await cl.true_state(row["drone_id"])
        assert row["state"] == "ready" and row["stale"] is False, row
        assert geo.horizontal_distance_m(row["lat_deg"], row["lon_deg"], truth["lat"], truth["lon"]) < 3.0
    assert status["count"] == 9 and status["ready"] == 9 and len(status["table"].splitlines()) == 10


async def test_an_agent_on_node_a_flies_a_drone_owned_by_node_c(cl: Cluster) -> None:
    """Every command goes to the drone's owner and comes back as a local one would: the result, the
    owner's progress as MCP progress notifications, a refusal in the owner's own words, a wait
    forwarded to the owner; the audit row of a call left running is finished when the owner ends it."""
    calls: Calls = cl.calls  # type: ignore[attr-defined]
    owners = await wait_spread(cl)
    drone = by_owner(owners)["node-c"][0]
    progress: list[tuple[float, str | None]] = []

    async def on_progress(done: float, total: float | None, message: str | None) -> None:
        progress.append((done, message))

    async with cl.node("node-a").client(name="forwarded") as mcp:
        up = ok(
            await calls.tool(mcp, "takeoff", {"drone_id": drone, "alt_m": 10}, progress_callback=on_progress)
        )
        assert up["status"] == "succeeded" and up["drone_id"] == drone, up
        assert progress and any(0.0 < done < 1.0 for done, _ in progress), progress  # the owner's climb
        assert abs((await cl.true_state(drone))["rel_alt_m"] - 10.0) < 1.5
        # a goto, waited for on the owner
        truth = await cl.true_state(drone)
        lat, lon = geo.offset_position(truth["lat"], truth["lon"], 25.0, 0.0)
        goto = {"drone_id": drone, "lat_deg": lat, "lon_deg": lon, "alt_m": 12}
        there = ok(await calls.tool(mcp, "go_to_location", goto))
        assert there["status"] == "succeeded", there
        truth = await cl.true_state(drone)
        assert geo.horizontal_distance_m(truth["lat"], truth["lon"], lat, lon) < 3.0
        # a refusal: the same class (a refusal) and the same words as on the node that owns the drone
        too_high = {**goto, "alt_m": 5000}
        refused_here = err(await calls.tool(mcp, "go_to_location", too_high))
        async with cl.node("node-c").client(name="owner") as owner:
            refused_there = err(await calls.tool(owner, "go_to_location", too_high))
        assert refused_here.startswith("Refused: ") and refused_here == refused_there, (
            refused_here,
            refused_there,
        )
        # wait:false, then the wait forwarded to the owner (monitor_flight on node A)
        back = {**goto, "lat_deg": truth["lat"] - 0.0002, "wait": False}
        leg = ok(await calls.tool(mcp, "go_to_location", back))
        assert leg["status"] == "running", leg
        monitored = ok(await calls.tool(mcp, "monitor_flight", {"drone_id": drone}))
        assert monitored["operation_id"] == leg["operation_id"] and monitored["status"] == "succeeded", (
            monitored
        )

        seen: list[Any] = []

        async def row_finished() -> bool:
            rows = await cl.rows("SELECT action, outcome, error FROM audit WHERE operation_id = :i",
                                 i=leg["operation_id"])  # fmt: skip
            seen[:] = [tuple(r) for r in rows]
            return len(rows) == 1 and rows[0].outcome == "ok"

        try:
            await eventually(row_finished, "the audit row of the wait:false call finished by the owner",
                             within_s=10)  # fmt: skip
        except AssertionError as exc:
            raise AssertionError(f"{exc}; its rows: {seen}") from None
        down = ok(await calls.tool(mcp, "land", {"drone_id": drone}))
        assert down["status"] in ("succeeded", "running"), down
    await eventually(lambda: landed(cl, [drone]), "the drone owned by node C landed", within_s=60)
    # every operation is recorded under the id node A was given
    ops = await cl.rows("SELECT id FROM operations WHERE vehicle_id = :v", v=drone)
    assert {leg["operation_id"], up["operation_id"], there["operation_id"]} <= {r.id for r in ops}


async def test_a_formation_spanning_every_node(cl: Cluster) -> None:
    """Fleet verbs run on the node that received them; each drone's steps run on its owner."""
    calls: Calls = cl.calls  # type: ignore[attr-defined]
    owners = await wait_spread(cl)
    groups = by_owner(owners)
    team = [groups[name][-1] for name in ("node-a", "node-b", "node-c")]
    async with cl.node("node-b").client(name="formation") as mcp:
        up = ok(await calls.tool(mcp, "fleet_takeoff", {"drone_ids": team, "alt_m": 10}))
        assert up["status"] == "succeeded", up
        truths = [await cl.true_state(d) for d in team]
        lat = sum(t["lat"] for t in truths) / 3
        lon = sum(t["lon"] for t in truths) / 3
        c_lat, c_lon = geo.offset_position(lat, lon, 30.0, 0.0)
        args = {"drone_ids": team, "formation": "line", "center_lat_deg": c_lat, "center_lon_deg": c_lon,
                "alt_m": 15, "spacing_m": 12}  # fmt: skip
        formed = ok(await calls.tool(mcp, "formation_goto", args))
        assert formed["status"] == "succeeded", formed
        for member in formed["drones"]:
            truth = await cl.true_state(member["drone_id"])
            target = (member["target_lat_deg"], member["target_lon_deg"])
            assert geo.horizontal_distance_m(truth["lat"], truth["lon"], *target) < 3.0, member
            assert abs(truth["rel_alt_m"] - member["target_alt_m"]) < 1.5, member
        # each drone's legs are operations of its owner (kind formation), not of node B
        for d in team:
            kinds = [r.kind for r in await cl.rows("SELECT kind FROM operations WHERE vehicle_id = :v", v=d)]
            assert "formation" in kinds, (d, kinds)
        down = ok(await calls.tool(mcp, "fleet_land", {"drone_ids": team}))
        assert down["status"] in ("succeeded", "running"), down
    await eventually(lambda: landed(cl, team), "the formation landed", within_s=90)


async def test_a_scoped_agent_sees_and_commands_only_its_vehicles_on_every_node(cl: Cluster) -> None:
    calls: Calls = cl.calls  # type: ignore[attr-defined]
    for node in cl.nodes:
        async with node.client(name=f"scoped-{node.name}", token=SCOPED_TOKEN) as mcp:
            rows = ok(await calls.tool(mcp, "list_drones", {}))
            assert sorted(r["drone_id"] for r in rows["drones"]) == ["d1", "d4"], rows
            assert ok(await calls.tool(mcp, "fleet_status", {}))["count"] == 2
            assert ok(await calls.tool(mcp, "get_telemetry", {"drone_id": "d4"}))
            for tool, args in (("get_telemetry", {"drone_id": "d2"}), ("land", {"drone_id": "d9"})):
                text = err(await calls.tool(mcp, tool, args))
                assert "unknown drone id" in text and "known ids: d1, d4" in text, text
            # d5 is unknown to this agent; d1 is landed with it when still armed, refused when already
            # down: either way the answer names d5 as unknown
            landing = await calls.tool(mcp, "fleet_land", {"drone_ids": ["d1", "d5"]})
            text = err(landing) if landing.is_error else json.dumps(ok(landing)["not_sent"])
            assert "d5" in text and "unknown drone id" in text, text
        async with node.client(name=f"full-{node.name}") as mcp:
            assert ok(await calls.tool(mcp, "list_drones", {}))["count"] == 9


async def test_lock_and_emergency_stop_from_node_b_reach_every_node_and_drone(cl: Cluster) -> None:
    calls: Calls = cl.calls  # type: ignore[attr-defined]
    owners = await wait_spread(cl)
    groups = by_owner(owners)
    flyers = {name: groups[name][0] for name in ("node-a", "node-b", "node-c")}
    await asyncio.gather(*(take_off(cl, cl.node(n), [d]) for n, d in flyers.items()))
    # each owner sends its drone on a long leg (wait=false: the operation runs on)
    targets: dict[str, tuple[float, float]] = {}
    legs: dict[str, str] = {}

    async def leg(name: str, drone: str) -> None:
        truth = await cl.true_state(drone)
        targets[drone] = lat, lon = geo.offset_position(truth["lat"], truth["lon"], 800.0, 0.0)
        async with cl.node(name).client(name=f"leg-{name}") as mcp:
            goto = {"drone_id": drone, "lat_deg": lat, "lon_deg": lon, "alt_m": 10}
            started = ok(await calls.tool(mcp, "go_to_location", {**goto, "wait": False}))
            assert started["status"] == "running", started
            legs[drone] = started["operation_id"]

    await asyncio.gather(*(leg(n, d) for n, d in flyers.items()))

    # node A's reads show each drone's current action, wherever it is owned (its owner publishes it)
    async def actions_on_node_a() -> tuple[Any, ...] | None:
        async with cl.node("node-a").client(name="reader") as mcp:
            rows = {r["drone_id"]: r for r in ok(await calls.tool(mcp, "list_drones", {}))["drones"]}
            table = ok(await calls.tool(mcp, "fleet_status", {}))["table"].splitlines()
            seen = {d: ok(await calls.tool(mcp, "get_telemetry", {"drone_id": d})) for d in flyers.values()}
        if all(rows[d]["operation"] == "goto running" for d in flyers.values()):
            return rows, table, seen
        return None

    _rows, table, seen = await eventually(actions_on_node_a, "every leg listed on node A", within_s=10)
    for drone in flyers.values():
        assert any(line.split()[0] == drone and line.split()[-2] == "goto" for line in table), table
        operation = seen[drone]["operation"]
        assert operation["operation_id"] == legs[drone] and operation["status"] == "running", operation
        assert operation["kind"] == "goto" and operation["params"]["alt_m"] == 10, operation

    stop = await calls.post(cl.node("node-b"), "/fleet/stop", {"action": "hold"})
    assert stop["fleet_lock"]["scope"] == "*"
    sent = {r["vehicle_id"]: r for r in stop["results"]}
    for drone in flyers.values():
        assert sent[drone]["outcome"] == "sent", sent[drone]
        assert sent[drone]["superseded_operation"], sent[drone]  # the owner superseded the running leg
    for vid in set(owners) - set(flyers.values()):
        assert sent[vid]["outcome"] == "skipped" and sent[vid]["message"] == "on the ground", sent[vid]

    # the drones stop short of their targets, wherever their owner is
    async def holding() -> bool:
        before = {d: await cl.true_state(d) for d in flyers.values()}
        await asyncio.sleep(1.0)
        after = {d: await cl.true_state(d) for d in flyers.values()}
        return all(
            geo.horizontal_distance_m(before[d]["lat"], before[d]["lon"], after[d]["lat"], after[d]["lon"])
            < 0.5
            for d in flyers.values()
        )

    await eventually(holding, "every flying drone holds after the stop from node B", within_s=30)
    for drone, (lat, lon) in targets.items():
        truth = await cl.true_state(drone)
        assert geo.horizontal_distance_m(truth["lat"], truth["lon"], lat, lon) > 50.0, drone

    # the fleet lock reached every node: each refuses its own agents
    for name, drone in flyers.items():
        async with cl.node(name).client(name=f"locked-{name}") as mcp:
            truth = await cl.true_state(drone)
            lat, lon = geo.offset_position(truth["lat"], truth["lon"], 10.0, 0.0)
            goto = {"drone_id": drone, "lat_deg": lat, "lon_deg": lon, "alt_m": 10}
            text = err(await calls.tool(mcp, "go_to_location", goto))
            assert "operator_lock" in text, text
    # a vehicle lock set on node C reaches node A's agents too; removing it on node A clears it on C
    drone_a = flyers["node-a"]
    await calls.delete(cl.node("node-c"), "/fleet/lock")
    await calls.post(cl.node("node-c"), f"/vehicles/{drone_a}/lock", {"reason": "inspection"})

    async def locked_on_a() -> bool:
        return any(lk["scope"] == drone_a for lk in (await cl.node("node-a").get("/locks"))["items"])

    await eventually(locked_on_a, "node C's vehicle lock seen on node A", within_s=10)
    async with cl.node("node-a").client(name="vehicle-lock") as mcp:
        text = err(await calls.tool(mcp, "land", {"drone_id": drone_a}))
        assert "inspection" in text, text
    await calls.delete(cl.node("node-a"), f"/vehicles/{drone_a}/lock")

    async def unlocked_on_c() -> bool:
        return not (await cl.node("node-c").get("/locks"))["items"]

    await eventually(unlocked_on_c, "the unlock on node A seen on node C", within_s=10)
    # an operator on node B lands every drone, wherever it is owned
    for drone in flyers.values():
        assert (await calls.post(cl.node("node-b"), f"/vehicles/{drone}/land"))["outcome"] == "sent"
    await eventually(lambda: landed(cl, list(flyers.values())), "the drones landed", within_s=90)


async def test_node_loss_with_drones_in_the_air_and_the_takeover(cl: Cluster) -> None:
    calls: Calls = cl.calls  # type: ignore[attr-defined]
    owners = await wait_spread(cl)
    lost = cl.node("node-c")
    victims = by_owner(owners)["node-c"]
    await take_off(cl, lost, victims)
    flights_before = {d: await cl.count_rows("flights", "vehicle_id = :v", v=d) for d in victims}
    mover = victims[0]
    truth = await cl.true_state(mover)
    # a leg long enough to be still flying when the node dies right after it started
    lat, lon = geo.offset_position(truth["lat"], truth["lon"], 0.0, 200.0)
    async with lost.client(name="before-loss") as mcp:
        goto = {"drone_id": mover, "lat_deg": lat, "lon_deg": lon, "alt_m": 10, "wait": False}
        leg = ok(await calls.tool(mcp, "go_to_location", goto))
    assert leg["status"] == "running"
    # an agent on node A waits on the leg (the wait runs on node C): it must follow the leg across the loss
    progressed = asyncio.Event()

    async def on_progress(progress: float, total: float | None, message: str | None) -> None:
        progressed.set()

    async def wait_from_a() -> dict[str, Any]:
        async with cl.node("node-a").client(name="waiting-across-loss") as mcp:
            args = {"drone_id": mover}
            return ok(await calls.tool(mcp, "monitor_flight", args, progress_callback=on_progress))

    waiting = asyncio.create_task(wait_from_a())
    await asyncio.wait_for(progressed.wait(), scaled(30))  # node C reports the leg's progress

    lost.kill9()  # node loss: the gateway and its sidecars die at once
    survivors = [cl.node("node-a"), cl.node("node-b")]

    async def taken_over() -> dict[str, str] | None:
        owners_now = await cl.owners(survivors[0])
        if not all(owners_now.get(d) in ("node-a", "node-b") for d in victims):
            return None
        for node in survivors:
            states = await cl.states(node)
            if not all(states[d] == "ready" for d in victims):
                return None
        return owners_now

    new_owners = await eventually(taken_over, "node C's drones taken over and ready on A and B", within_s=60)
    # new sidecars run on the new owners (telemetry requested again: positions are live and current)
    for d in victims:
        node = cl.node(new_owners[d])
        v = await node.get(f"/vehicles/{d}")
        assert v["status"]["sidecar"]["pid"] in mavsdk_servers_of(node.proc.pid)
        cl.sidecars_seen.add(v["status"]["sidecar"]["pid"])  # type: ignore[attr-defined]
        assert v["telemetry"]["position"]["stale"] is False
    # the leg that was flying is followed again by its new owner, under the same operation id, and says so
    async with cl.node(new_owners[mover]).client(name="after-loss") as mcp:
        answer = await calls.tool(mcp, "monitor_flight", {"drone_id": mover})
    monitored, monitored_text = ok(answer), answer.content[0].text
    assert monitored["operation_id"] == leg["operation_id"], monitored
    assert monitored["status"] == "succeeded", monitored
    # the client is told what happened, in the result and in the text it reads
    honest = f"node node-c was lost while this goto ran; node {new_owners[mover]} took {mover} over"
    assert honest in monitored["message"], monitored
    assert honest in monitored_text, monitored_text
    truth = await cl.true_state(mover)
    assert geo.horizontal_distance_m(truth["lat"], truth["lon"], lat, lon) < 3.0
    # node A's wait followed the leg to its new owner and ended with it (not at the forwarding timeout
    # with the database's 'running')
    followed = await asyncio.wait_for(waiting, scaled(60))
    assert followed["operation_id"] == leg["operation_id"] and followed["status"] == "succeeded", followed
    rows = await cl.rows("SELECT status, message FROM operations WHERE id = :i", i=leg["operation_id"])
    assert rows[0].status == "succeeded" and honest in rows[0].message, rows
    ops = (await survivors[0].get("/operations", vehicle_id=mover))["items"]
    assert not [o for o in ops if o["status"] == "running"], ops
    # no flight lost: the flight node C left open is closed, and the rest of it is a new flight
    for d in victims:
        open_old = await cl.rows(
            "SELECT id FROM flights WHERE vehicle_id = :v AND ended_at IS NULL ORDER BY id", v=d
        )
        assert await cl.count_rows("flights", "vehicle_id = :v", v=d) >= flights_before[d]
        assert len(open_old) <= 1
    # land them through node B, wherever they are now owned
    for d in victims:
        assert (await calls.post(survivors[1], f"/vehicles/{d}/land"))["outcome"] == "sent"
    await eventually(lambda: landed(cl, victims), "node C's drones landed by their new owners", within_s=90)


async def test_the_audit_holds_every_call_made(cl: Cluster) -> None:
    calls: Calls = cl.calls  # type: ignore[attr-defined]

    async def counted() -> bool:
        return await cl.count_rows("audit") == calls.count

    with contextlib.suppress(AssertionError):
        await eventually(counted, "audit rows", within_s=scaled(10))
    assert await cl.count_rows("audit") == calls.count
