"""The shared ticks (gateway/util/ticks.py): every check of a period from one timer per event loop, in
the order they came; a cancelled check is not called again, a failing one keeps its place, and the
timer stops with the last check."""

from __future__ import annotations

import asyncio

from gateway.util import ticks


def _timers(loop: asyncio.AbstractEventLoop) -> int:
    return sum(1 for handle in loop._scheduled if not handle.cancelled())  # type: ignore[attr-defined]


async def _until(condition: object, within_s: float = 5.0) -> None:
    loop = asyncio.get_running_loop()
    deadline = loop.time() + within_s
    while not condition():  # type: ignore[operator]
        assert loop.time() < deadline, "not reached in time"
        await asyncio.sleep(0.005)


async def test_checks_of_one_period_share_one_timer_and_run_in_order() -> None:
    loop = asyncio.get_running_loop()
    before = _timers(loop)
    calls: list[str] = []
    places = [ticks.every(0.02, lambda name=name: calls.append(name)) for name in ("a", "b", "c")]
    assert _timers(loop) == before + 1  # three checks, one timer
    await _until(lambda: len(calls) >= 6)
    assert calls[:6] == ["a", "b", "c", "a", "b", "c"]
    for place in places:
        place.cancel()
    assert _timers(loop) == before  # no check left: no timer


async def test_a_cancelled_check_is_not_called_and_a_failing_one_keeps_its_place() -> None:
    calls: list[str] = []

    def failing() -> None:
        calls.append("failing")
        raise RuntimeError("boom")

    bad = ticks.every(0.02, failing)
    gone = ticks.every(0.02, lambda: calls.append("gone"))
    good = ticks.every(0.02, lambda: calls.append("good"))
    gone.cancel()
    gone.cancel()  # twice is harmless
    await _until(lambda: calls.count("good") >= 2)
    assert "gone" not in calls
    assert calls.count("failing") >= 2  # called again after it raised
    bad.cancel()
    good.cancel()


async def test_a_check_may_cancel_another_before_its_turn() -> None:
    calls: list[str] = []
    later: list[ticks.Tick] = []

    def first() -> None:
        calls.append("first")
        later[0].cancel()

    one = ticks.every(0.02, first)
    later.append(ticks.every(0.02, lambda: calls.append("second")))
    await _until(lambda: calls.count("first") >= 2)
    assert "second" not in calls
    one.cancel()
