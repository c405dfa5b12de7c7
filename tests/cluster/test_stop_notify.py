"""The PostgreSQL stop relay's rules, without a database: only stops cross, late ones are dropped, a node's
own notification is not run again, and the store's URL becomes a DSN asyncpg takes."""

from __future__ import annotations

import asyncio
import json
import time
from typing import Any

import pytest

from gateway.cluster.stop_notify import STOP_CHANNEL, StopRelay, asyncpg_dsn
from gateway.errors import NotRun


def relay(ran: list[dict[str, Any]]) -> StopRelay:
    async def handler(stop: dict[str, Any]) -> Any:
        ran.append(stop)
        return None  # not this node's drone: nothing to answer

    return StopRelay("postgresql+asyncpg://u:p@127.0.0.1:5/db", "node-b", handler)


async def deliver(r: StopRelay, **body: Any) -> None:
    r._on_notify(None, 1, STOP_CHANNEL, json.dumps(body))
    await asyncio.gather(*list(r._tasks))


async def test_only_stops_in_time_from_other_nodes_are_run() -> None:
    ran: list[dict[str, Any]] = []
    r = relay(ran)
    soon = time.time() + 5
    await deliver(r, id="1", vehicle="d1", command="takeoff", node="node-a", accept_by=soon)
    await deliver(r, id="2", vehicle="d1", command="land", node="node-a", accept_by=time.time() - 1)
    await deliver(r, id="3", vehicle="d1", command="land", node="node-b", accept_by=soon)
    assert ran == []
    await deliver(r, id="4", vehicle="d1", command="land", node="node-a", accept_by=soon)
    assert [s["id"] for s in ran] == ["4"]


async def test_a_non_stop_is_not_sent() -> None:
    with pytest.raises(NotRun, match="goto was not sent"):
        await relay([]).send("d1", "goto", {}, 3, {}, 1.0)


def test_dsn() -> None:
    assert asyncpg_dsn("postgresql+asyncpg://u:p@h:5432/db") == "postgresql://u:p@h:5432/db"


async def test_a_stop_sent_again_runs_once_and_gets_the_first_answer_again() -> None:
    ran: list[dict[str, Any]] = []
    acks: list[dict[str, Any]] = []
    release = asyncio.Event()

    async def handler(stop: dict[str, Any]) -> Any:
        ran.append(stop)
        await release.wait()
        return {"drone_id": stop["vehicle"], "status": "running"}

    r = StopRelay("postgresql+asyncpg://u:p@127.0.0.1:5/db", "node-b", handler)

    async def notify(channel: str, body: dict[str, Any], within_s: float = 5.0) -> None:
        acks.append(body)

    r._notify = notify  # type: ignore[method-assign]  # the unit under test is the relay's bookkeeping
    stop = {"id": "7", "vehicle": "d1", "command": "land", "node": "node-a", "accept_by": time.time() + 5}
    r._on_notify(None, 1, STOP_CHANNEL, json.dumps(stop))
    r._on_notify(None, 1, STOP_CHANNEL, json.dumps(stop))  # sent again while it runs: not run twice
    release.set()
    await asyncio.gather(*list(r._tasks))
    r._on_notify(None, 1, STOP_CHANNEL, json.dumps(stop))  # sent again after: the first answer again
    await asyncio.gather(*list(r._tasks))
    assert [s["id"] for s in ran] == ["7"]
    assert len(acks) == 2 and acks[0] == acks[1] and acks[0]["ok"] is True, acks


async def test_stops_relayed_at_once_each_get_their_answer(pg_base_url: str) -> None:
    """Four stops relayed at the same moment through a real PostgreSQL (a fleet stop relays each drone's):
    none shares a connection with another, and the owner answers each."""
    from tests.persist.pg import create_database

    url = await create_database(pg_base_url)

    async def owner(stop: dict[str, Any]) -> Any:
        await asyncio.sleep(0.2)  # its land takes a moment: the stops overlap
        return {"drone_id": stop["vehicle"], "ran_on": "node-b"}

    async def nobody(stop: dict[str, Any]) -> Any:
        return None

    a, b = StopRelay(url, "node-a", nobody), StopRelay(url, "node-b", owner)
    await a.start()
    await b.start()
    try:
        drones = ["d1", "d2", "d3", "d4"]
        answers = await asyncio.gather(
            *(a.send(d, "land", {}, None, {"via": "rest", "principal": "op"}, 10.0) for d in drones)
        )
        assert [x["drone_id"] for x in answers] == drones, answers
    finally:
        await a.close()
        await b.close()
