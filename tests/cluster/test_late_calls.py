"""Calls routed to a drone's owner over a real NATS server: the owner accepts a call before running it,
and refuses one that reaches it after its deadline or for a lease epoch it does not hold; a caller that
heard no acceptance in time says "not run", and a caller cut off from the bus says so without sending."""

from __future__ import annotations

import asyncio
import json
from collections.abc import AsyncIterator
from pathlib import Path
from typing import Any

import pytest
import pytest_asyncio

from gateway.cluster.bus import Bus, call_subject
from gateway.errors import NotRun
from tests.cluster.harness import find_nats_server, nats_server, server_has_all_sent

pytestmark = pytest.mark.skipif(find_nats_server() is None, reason="nats-server is not installed")


@pytest_asyncio.fixture
async def buses(tmp_path: Path) -> AsyncIterator[tuple[Bus, Bus, list[str]]]:
    """An owner's bus answering calls for d1 (epoch 7) and a caller's bus; the calls the owner ran."""
    with nats_server(tmp_path) as server:
        owner, caller = Bus([server.url], "owner"), Bus([server.url], "caller")
        await owner.connect()
        await caller.connect()
        ran: list[str] = []

        async def handler(name: str, args: dict[str, Any], who: dict[str, Any], progress: Any) -> Any:
            ran.append(name)
            return {"done": name}

        def check(epoch: int | None) -> None:
            if epoch is not None and epoch != 7:
                raise NotRun(f"stale epoch {epoch}")

        await owner.serve_calls("d1", handler, check)
        await server_has_all_sent(owner.client)  # the server knows the subscription before anyone calls
        try:
            yield owner, caller, ran
        finally:
            await caller.close()
            await owner.close()


async def test_a_call_in_time_for_the_current_epoch_runs(buses: tuple[Bus, Bus, list[str]]) -> None:
    _, caller, ran = buses
    assert await caller.call("d1", "land", {}, {}, 10.0, epoch=7) == {"done": "land"}
    assert ran == ["land"]


async def test_a_stale_epoch_is_refused_and_not_run(buses: tuple[Bus, Bus, list[str]]) -> None:
    _, caller, ran = buses
    with pytest.raises(NotRun, match="stale epoch 6"):
        await caller.call("d1", "land", {}, {}, 10.0, epoch=6)
    assert ran == []


async def test_a_call_reaching_the_owner_after_its_deadline_is_dropped(
    buses: tuple[Bus, Bus, list[str]],
) -> None:
    """As after a partition heals: the message was held in the bus past the time its caller gave up."""
    _, caller, ran = buses
    nc = caller.client
    inbox = nc.new_inbox()
    answers: asyncio.Queue[Any] = asyncio.Queue()

    async def collect(msg: Any) -> None:
        await answers.put(msg)

    await nc.subscribe(inbox, cb=collect)
    await server_has_all_sent(nc)
    body = {"call": "goto", "args": {}, "caller": {"node": "node-x"}, "accept_by": 0.0, "epoch": 7}
    await nc.publish(call_subject("d1"), json.dumps(body).encode(), reply=inbox)
    msg = await asyncio.wait_for(answers.get(), 10.0)
    assert msg.data, f"an empty message (headers {msg.headers}): the owner never heard the call"
    reply = json.loads(msg.data)
    assert (msg.headers or {}).get("Fleet-Kind") == "result" and reply["error"]["code"] == "not_run", reply
    assert "after its deadline" in reply["error"]["message"]
    assert ran == []


async def test_no_acceptance_in_time_is_not_run(buses: tuple[Bus, Bus, list[str]]) -> None:
    """An owner that hears the call but never accepts it (a stalled node): the caller's answer is 'not run'
    after the accept time, not after the whole forwarding timeout."""
    _, caller, ran = buses

    async def deaf(msg: Any) -> None:
        return None

    await caller.client.subscribe(call_subject("d2"), cb=deaf, queue="owner")
    await server_has_all_sent(caller.client)
    loop = asyncio.get_running_loop()
    started = loop.time()
    with pytest.raises(NotRun, match=r"did not accept takeoff within 0.5 s.*not run"):
        await caller.call("d2", "takeoff", {}, {}, 60.0, accept_s=0.5)
    assert loop.time() - started < 30.0  # far below the 60 s the call could have waited
    assert ran == []


async def test_a_caller_cut_off_from_the_bus_sends_nothing(buses: tuple[Bus, Bus, list[str]]) -> None:
    _, caller, ran = buses
    await caller.client.close()
    with pytest.raises(NotRun, match=r"cut off from the cluster's bus.*not sent and did not run"):
        await caller.call("d1", "land", {}, {}, 10.0)
    assert ran == []


async def test_a_message_that_is_not_a_call_is_answered_and_not_run(
    buses: tuple[Bus, Bus, list[str]],
) -> None:
    """The owner validates a call's body (`CallRequest`): arguments that are not a JSON object, or no verb,
    are answered invalid_argument, naming what is wrong; nothing runs."""
    _, caller, ran = buses
    nc = caller.client
    for body, wrong in (({"call": "land", "args": [1, 2]}, "args"), ({"args": {}}, "call")):
        msg = await nc.request(call_subject("d1"), json.dumps(body).encode(), timeout=10.0)
        reply = json.loads(msg.data)
        assert (msg.headers or {}).get("Fleet-Kind") == "result", msg.headers
        assert reply["error"]["code"] == "invalid_argument" and wrong in reply["error"]["message"], reply
    assert ran == []
