"""Pacing of link starts: slots per event loop, released by their holder or after their time."""

from __future__ import annotations

import asyncio

from gateway.link.pacing import Pace
from tests.helpers.timing import scaled


async def test_a_start_waits_for_a_free_slot_and_gets_it_on_release() -> None:
    pace = Pace(slots=2, hold_at_most_s=600.0)
    first, second = await pace.take(), await pace.take()
    third = asyncio.create_task(pace.take())
    await asyncio.sleep(0.05)
    assert not third.done()  # both slots held
    first.release()
    first.release()  # releasing twice frees one slot only
    slot = await asyncio.wait_for(third, scaled(5.0))
    fourth = asyncio.create_task(pace.take())
    await asyncio.sleep(0.05)
    assert not fourth.done()
    second.release()
    slot.release()
    (await asyncio.wait_for(fourth, scaled(5.0))).release()


async def test_a_slot_frees_itself_after_its_time() -> None:
    pace = Pace(slots=1, hold_at_most_s=0.2)
    await pace.take()  # never released by its holder
    slot = await asyncio.wait_for(pace.take(), scaled(5.0))
    slot.release()
