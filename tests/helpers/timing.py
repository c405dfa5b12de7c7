"""Test deadlines, stretched on slow or busy machines by one knob.

``FLEET_TEST_TIME_SCALE=3 make test`` multiplies every deadline the tests wait on (and pytest's per-test
timeout) by 3. Without it the scale follows the machine's load: a 2-core machine with a load average of
6 waits up to 3 times longer (at most ``MAX_AUTO_SCALE``), so a run on a busy machine gets the time an
idle one would not need. The load when the run starts sets the per-test timeout and the least scale;
each deadline is stretched further when the machine got busier since (read when the deadline is set:
work that starts beside a run half an hour in is the run's busy machine too). Deadlines bound a wait;
they never assert how long something took.
"""

from __future__ import annotations

import asyncio
import os
from collections.abc import Awaitable, Callable
from typing import TypeVar

T = TypeVar("T")


MAX_AUTO_SCALE = 4.0


def _load_scale() -> float:
    """Load average per core now, between 1 and MAX_AUTO_SCALE (1 where the OS has no load average)."""
    try:
        load = os.getloadavg()[0]
    except OSError:
        return 1.0
    return min(MAX_AUTO_SCALE, max(1.0, round(load / (os.cpu_count() or 1), 1)))


def _fixed_scale() -> float | None:
    """FLEET_TEST_TIME_SCALE as a number, None when unset."""
    raw = os.environ.get("FLEET_TEST_TIME_SCALE", "").strip()
    if not raw:
        return None
    try:
        value = float(raw)
    except ValueError:
        raise SystemExit(f"FLEET_TEST_TIME_SCALE must be a number >= 1, e.g. 2; got {raw!r}") from None
    if not value >= 1.0:
        raise SystemExit(f"FLEET_TEST_TIME_SCALE must be a number >= 1, e.g. 2; got {raw!r}")
    return value


FIXED_SCALE = _fixed_scale()
#: the scale when the run starts: pytest's per-test timeout, and the least any deadline is stretched by
TIME_SCALE = FIXED_SCALE if FIXED_SCALE is not None else _load_scale()


def scaled(seconds: float) -> float:
    """A deadline of ``seconds`` on an idle machine, stretched by FLEET_TEST_TIME_SCALE, else by the
    machine's load now or at the start, whichever is higher."""
    if FIXED_SCALE is not None:
        return seconds * FIXED_SCALE
    return seconds * max(TIME_SCALE, _load_scale())


async def settled(
    read: Callable[[], Awaitable[T]],
    still: Callable[[T, T], bool],
    what: str,
    *,
    window_s: float = 1.5,
    within_s: float = 60.0,
) -> T:
    """Read until two readings ``window_s`` apart are ``still`` (e.g. a drone stopped moving); the
    last reading. Raises AssertionError naming ``what`` after ``within_s`` (scaled) without that."""
    loop = asyncio.get_running_loop()
    deadline = loop.time() + scaled(within_s)
    before = await read()
    while True:
        await asyncio.sleep(window_s)
        now = await read()
        if still(before, now):
            return now
        if loop.time() > deadline:
            raise AssertionError(f"{what}: not settled within {scaled(within_s):g} s; last {before} -> {now}")
        before = now


async def eventually(
    check: Callable[[], Awaitable[T]],
    what: str,
    *,
    within_s: float = 60.0,
    explain: Callable[[], object] | None = None,
) -> T:
    """Await ``check()`` until it returns something truthy; that value. AssertionError after the
    (scaled) deadline, naming ``what``, the last value seen and, given ``explain``, what it returns
    (the state that a bare False hides)."""
    loop = asyncio.get_running_loop()
    deadline = loop.time() + scaled(within_s)
    while not (result := await check()):
        if loop.time() > deadline:
            seen = f"; {explain()!r}" if explain is not None else ""
            raise AssertionError(f"{what}: not reached within {scaled(within_s):g} s; last {result!r}{seen}")
        await asyncio.sleep(0.2)
    return result
