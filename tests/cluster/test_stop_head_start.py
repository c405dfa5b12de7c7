"""An operator's stop for a drone another node owns: the bus has a short head start, then PostgreSQL
carries the stop beside it (`gateway.cluster.owner_calls`), without waiting for the bus's accept time
and its clock margin; a stop the owner accepts over the bus within the head start is not relayed."""

from __future__ import annotations

import asyncio
from types import SimpleNamespace
from typing import Any

import pytest

from gateway.cluster.owner_calls import OwnerCalls
from gateway.cluster.stop_takeover import StopTakeover
from gateway.errors import NotRun, OwnerFenced
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


class CancelledBus(Bus):
    """A bus whose call ends cancelled under the stop (a library cancelled what the call awaited)."""

    async def call(self, *_args: Any, **_kw: Any) -> Any:
        self.ended.set()
        raise asyncio.CancelledError


class CancelledRelay(Relay):
    """A relay whose send ends cancelled under the stop (its connection lost mid-statement)."""

    async def send(self, drone_id: str, *_args: Any) -> Any:
        self.sent.append((drone_id, True))
        raise asyncio.CancelledError


async def test_a_bus_call_that_ends_cancelled_under_the_stop_leaves_the_stop_to_postgresql() -> None:
    bus = CancelledBus(accept_after_s=None)
    relay = Relay(bus)
    answer = await OwnerCalls(node(bus, relay)).forward_stop("d1", "land", OPERATOR)
    assert answer == {"drone_id": "d1", "via": "postgresql"}
    assert relay.sent == [("d1", True)]


async def test_a_path_that_ends_cancelled_is_one_failed_path_the_others_still_carry_the_stop() -> None:
    bus = Bus(accept_after_s=None)
    n = node(bus, CancelledRelay(bus))

    async def late_answer() -> Any:
        await asyncio.sleep(0.2)
        return {"drone_id": "d1", "via": "fenced node"}

    async def cancelled() -> Any:
        raise asyncio.CancelledError

    loop = asyncio.get_running_loop()
    answer = await n.takeover.reach(
        "d1", "land", OPERATOR, None, None, [cancelled(), late_answer()], [], loop.time() + 5, take_over=False
    )
    assert answer == {"drone_id": "d1", "via": "fenced node"}


async def test_every_path_ending_cancelled_is_not_run_not_a_cancelled_stop() -> None:
    bus = Bus(accept_after_s=None)
    n = node(bus, Relay(bus))

    async def cancelled() -> Any:
        raise asyncio.CancelledError

    loop = asyncio.get_running_loop()
    with pytest.raises(NotRun, match="no owner acknowledged land for d1"):
        await n.takeover.reach("d1", "land", OPERATOR, None, None, [cancelled()], [], loop.time() + 1,
                               take_over=False)  # fmt: skip


class FencingBus(Bus):
    """A bus whose owner accepts the stop and then fences itself while it runs it (it could not renew
    its leases): the call ends OwnerFenced; the fenced node's stop-only path answers."""

    def __init__(self) -> None:
        super().__init__(accept_after_s=0.0)
        self.subjects: list[str | None] = []

    async def call(self, *_args: Any, subject: str | None = None, **_kw: Any) -> Any:
        self.subjects.append(subject)
        if subject is None:
            raise OwnerFenced(
                "not finished: node node-a gave drone 'd1' up while it ran land", vehicle_id="d1"
            )
        return {"drone_id": "d1", "via": "fenced node"}


@pytest.mark.parametrize("relay_listening", [False, True], ids=["postgresql-down", "postgresql-up"])
async def test_an_owner_that_fences_itself_while_it_runs_the_stop_leaves_it_to_its_stop_only_path(
    relay_listening: bool,
) -> None:
    """The owner's OwnerFenced is no refusal of the stop: it let go of the drone, the stop may not have
    reached it; the stop goes on through the fenced node's stop-only path (and this node's link)."""
    bus = FencingBus()
    relay = Relay(bus)
    relay.listening = relay_listening
    answer = await OwnerCalls(node(bus, relay)).forward_stop("d1", "land", OPERATOR)
    assert answer == {"drone_id": "d1", "via": "fenced node"}
    assert bus.subjects[0] is None and bus.subjects[-1] is not None, bus.subjects
