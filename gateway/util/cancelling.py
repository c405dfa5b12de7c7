"""Whose cancellation a CancelledError is."""

from __future__ import annotations

import asyncio


def cancelled_here() -> bool:
    """Whether the running task itself is being cancelled; False when a CancelledError came from
    something it awaited ending cancelled (a library cancelling what it waited on)."""
    task = asyncio.current_task()
    return task is None or task.cancelling() > 0
