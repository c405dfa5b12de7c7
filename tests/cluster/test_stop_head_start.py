"""An operator's stop for a drone another node owns: the bus has a short head start, then PostgreSQL
carries the stop beside it (`gateway.cluster.owner_calls`), without waiting for the bus's accept time
and its clock margin; a stop the owner accepts over the bus within the head start is not relayed."""

from __future__ import annotations

import asyncio
from types import SimpleNamespace
from typing import Any

from gateway.cluster.owner_calls import OwnerCalls
from gateway.cluster.stop_takeover import StopTakeover
from gateway.errors import NotRun
from gateway.fleet.policy.caller import Caller

OPERATOR = Caller(via="rest", principal="operator")


class Bus:
    """A bus whose owner answers after ``accept_after_s`` (None: never; the call is not run then)."""

    def __init__(self, accept_after_s: float | None) -> None:
        self.accept_after_s = accept_after_s
        self.ended = asyncio.Event()

    async def call(self, *_args: Any, accept_s: float, accepted_event: asyncio.Event | None = None,
                   **_kw: Any) -> Any:  # fmt: skip
        try:
            if self.accept_after_s is None:
                await asyncio.sleep(accept_s + 0.5)  # the accept time and the clock margin
                raise NotRun("not accepted", bus="no answer")
            await asyncio.sleep(self.accept_after_s)
            if accepted_event is not None:
                accepted_event.set()
            return {"drone_id": "d1", "via": "bus"}
        finally:
            self.ended.set()


class Relay:
    listening = True

    def __init__(self, bus: Bus) -> None:
        self.bus = bus
        self.sent: list[tuple[str, bool]] = []  # (drone, whether the bus call had ended by then)

    async def send(self, drone_id: str, *_args: Any) -> Any:
        self.sent.append((drone_id, self.bus.ended.is_set()))
        return {"drone_id": drone_id, "via": "postgresql"}


def node(bus: Bus, relay: Relay) -> Any:
    settings = SimpleNamespace(cluster_accept_timeout_s=3.0)
    n = SimpleNamespace(node_id="node-b", started=True, fenced={}, registry=None, held={}, bus=bus,
                        relay=relay, settings=settings)  # fmt: skip
    n.takeover = StopTakeover(n)  # type: ignore[arg-type]
    return n


async def test_a_stop_the_bus_does_not_carry_goes_through_postgresql_while_the_bus_still_waits() -> None:
    bus = Bus(accept_after_s=None)
    relay = Relay(bus)
    calls = OwnerCalls(node(bus, relay))
    answer = await calls.forward_stop("d1", "land", OPERATOR)
    assert answer == {"drone_id": "d1", "via": "postgresql"}
    # relayed before the bus gave up (its accept time and clock margin), not after
    assert relay.sent == [("d1", False)], relay.sent


async def test_a_stop_the_owner_accepts_over_the_bus_in_time_is_not_relayed() -> None:
    bus = Bus(accept_after_s=0.0)
    relay = Relay(bus)
    calls = OwnerCalls(node(bus, relay))
    answer = await calls.forward_stop("d1", "land", OPERATOR)
    assert answer == {"drone_id": "d1", "via": "bus"}
    assert relay.sent == []
