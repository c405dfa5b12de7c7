"""A stop for a drone whose link is being established (`gateway.fleet.commands.operator_verbs`): sent as
soon as the drone is heard (connected), not once it is ready to fly; tried again while the link comes and
goes; given up when the drone is unregistered or the link never comes."""

from __future__ import annotations

from collections.abc import Iterator

from gateway.errors import GatewayError, VehicleNotReady
from gateway.fleet.commands.operator_verbs import send_once_heard


def states(*seq: str | None) -> Iterator[str | None]:
    yield from seq
    while True:
        yield seq[-1]


async def test_the_stop_goes_once_the_drone_is_connected_not_ready() -> None:
    reading = states("connecting", "connecting", "connected")
    sent: list[str] = []

    async def stop() -> None:
        sent.append("land")

    assert await send_once_heard("d1", "land", lambda: next(reading), stop, within_s=5, every_s=0.01)
    assert sent == ["land"]


async def test_a_link_that_drops_between_reading_and_sending_is_tried_again() -> None:
    reading = states("connected")
    tries: list[int] = []

    async def stop() -> None:
        tries.append(1)
        if len(tries) < 3:
            raise VehicleNotReady("drone 'd1' is connecting", state="connecting")

    assert await send_once_heard("d1", "land", lambda: next(reading), stop, within_s=5, every_s=0.01)
    assert len(tries) == 3


async def test_an_autopilots_refusal_ends_the_wait() -> None:
    reading = states("ready")
    tries: list[int] = []

    async def stop() -> None:
        tries.append(1)
        raise GatewayError("the autopilot refused land: DENIED")

    assert not await send_once_heard("d1", "land", lambda: next(reading), stop, within_s=5, every_s=0.01)
    assert tries == [1]


async def test_nothing_is_sent_to_a_drone_never_heard_or_no_longer_registered() -> None:
    sent: list[str] = []

    async def stop() -> None:
        sent.append("land")

    never = states("connecting")
    assert not await send_once_heard("d1", "land", lambda: next(never), stop, within_s=0.1, every_s=0.01)
    gone = states("link_lost", None)
    assert not await send_once_heard("d1", "land", lambda: next(gone), stop, within_s=5, every_s=0.01)
    assert sent == []
