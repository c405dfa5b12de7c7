"""Starting many links a few at a time: slots per event loop, each held until its start is done or for a
bounded time.

A gateway restoring hundreds of vehicles would otherwise start hundreds of mavsdk_server processes in
the same second and then open hundreds of gRPC sessions at once: each sidecar loads its binary and
discovers its vehicle, each session subscribes its streams and asks for its rates, all on a machine
whose cores they share, so a session's connection times out, its sidecar is restarted and starts again
(measured at 300 drones: 600 restarts in 3 minutes, 10 drones ready). Paced, each start gets the CPU it
needs and the first vehicles are ready while the last start.
"""

from __future__ import annotations

import asyncio
import weakref


class Slot:
    """One slot, held by one start; ``release`` may be called any number of times."""

    def __init__(self, slots: asyncio.Semaphore, hold_at_most_s: float) -> None:
        self._slots: asyncio.Semaphore | None = slots
        self._timer = asyncio.get_running_loop().call_later(hold_at_most_s, self.release)

    def release(self) -> None:
        slots, self._slots = self._slots, None
        if slots is not None:
            self._timer.cancel()
            slots.release()


class Pace:
    """At most ``slots`` starts at once in each event loop (``slots`` and ``hold_at_most_s`` are read
    when a loop's first slot is taken and at each take, so a test may change them)."""

    def __init__(self, slots: int, hold_at_most_s: float) -> None:
        self.slots = slots
        self.hold_at_most_s = hold_at_most_s
        self._by_loop: weakref.WeakKeyDictionary[asyncio.AbstractEventLoop, asyncio.Semaphore] = (
            weakref.WeakKeyDictionary()
        )

    async def take(self) -> Slot:
        """Wait for a free slot; the caller releases it (or it frees itself after ``hold_at_most_s``)."""
        loop = asyncio.get_running_loop()
        slots = self._by_loop.get(loop)
        if slots is None:
            slots = self._by_loop[loop] = asyncio.Semaphore(self.slots)
        await slots.acquire()
        return Slot(slots, self.hold_at_most_s)
