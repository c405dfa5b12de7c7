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
