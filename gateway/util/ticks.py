"""One timer per event loop for what every drone checks each second.

A loop per drone (``while True: check(); await asyncio.sleep(1.0)``) wakes the event loop once a second
for each drone, each at its own moment, with a timer, a future and a task step every time. Here a
period has one timer per event loop, and each tick calls every check registered for that period in
turn: one wake-up a second for the whole fleet. A check is a plain function (it must not block); one
that has something to wait for starts or wakes its own task. A check that raises is logged and keeps
its place.
"""

from __future__ import annotations

import asyncio
import logging
import weakref
from collections.abc import Callable

log = logging.getLogger("gateway.ticks")


class Tick:
    """A check's place in the ticks; ``cancel`` takes it out (any number of times)."""

    def __init__(self, ticker: _Ticker, check: Callable[[], None]) -> None:
        self._ticker: _Ticker | None = ticker
        self.check = check

    def cancel(self) -> None:
        ticker, self._ticker = self._ticker, None
        if ticker is not None:
            ticker.remove(self)


class _Ticker:
    """The checks of one period in one event loop, and the timer that calls them (only while there are
    checks)."""

    def __init__(self, period_s: float) -> None:
        self.period_s = period_s
        self.ticks: dict[Tick, None] = {}  # in the order they came
        self._timer: asyncio.TimerHandle | None = None

    def add(self, check: Callable[[], None]) -> Tick:
        tick = Tick(self, check)
        self.ticks[tick] = None
        if self._timer is None:
            self._timer = asyncio.get_running_loop().call_later(self.period_s, self._run)
        return tick

    def remove(self, tick: Tick) -> None:
        self.ticks.pop(tick, None)
        if not self.ticks and self._timer is not None:
            self._timer.cancel()
            self._timer = None

    def _run(self) -> None:
        self._timer = asyncio.get_running_loop().call_later(self.period_s, self._run)
        for tick in list(self.ticks):
            if tick not in self.ticks:
                continue  # cancelled by a check before it
            try:
                tick.check()
            except Exception:
                log.exception("a check called every %g s failed", self.period_s)


_TICKERS: weakref.WeakKeyDictionary[asyncio.AbstractEventLoop, dict[float, _Ticker]] = (
    weakref.WeakKeyDictionary()
)


def every(period_s: float, check: Callable[[], None]) -> Tick:
    """Call ``check`` every ``period_s`` seconds, from the next tick of the running event loop's timer of
    that period on, until the returned place is cancelled."""
    tickers = _TICKERS.setdefault(asyncio.get_running_loop(), {})
    ticker = tickers.get(period_s)
    if ticker is None:
        ticker = tickers[period_s] = _Ticker(period_s)
    return ticker.add(check)
