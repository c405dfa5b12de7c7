"""Waiting on a real vehicle's state with a deadline, failing with what it said."""

from __future__ import annotations

import asyncio
from collections.abc import Callable

from gateway.fleet.vehicle import Vehicle
from tests.helpers.timing import scaled


async def until(what: str, check: Callable[[], object], within_s: float, v: Vehicle) -> None:
    loop = asyncio.get_running_loop()
    deadline = loop.time() + scaled(within_s)
    while not check():
        if loop.time() > deadline:
            texts = [f"{t.severity}: {t.text}" for t in list(v.telemetry.status_texts)[-8:]]
            raise AssertionError(
                f"{v.id}: {what} not reached within {scaled(within_s):g} s; {v.status()}; {texts}"
            )
        await asyncio.sleep(0.2)
