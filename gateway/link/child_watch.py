"""Sidecar processes waited for on the event loop (a pidfd each) instead of by a thread each.

Python 3.11's asyncio waits for every child process in a thread of its own (``ThreadedChildWatcher``):
one thread per sidecar in the gateway, 300 at 300 drones, each with its stack and its wake-ups. Its
``PidfdChildWatcher`` is tied to one loop attached beforehand, and the gateway's tests run many loops.
``LoopPidfdWatcher`` is that watcher as Python 3.12 made it: the loop that spawns the child is the one
that waits on its pidfd. Python 3.12 and later use theirs by themselves (and deprecate setting one); a
kernel without ``pidfd_open`` (before Linux 5.3, or a sandbox that refuses it) keeps the threads.
"""

from __future__ import annotations

import asyncio
import functools
import logging
import os
import sys
from collections.abc import Callable
from typing import TypeVarTuple, Unpack

Args = TypeVarTuple("Args")

log = logging.getLogger("gateway.sidecar")


class LoopPidfdWatcher(asyncio.AbstractChildWatcher):
    """A child watcher that needs no attached loop: each child's pidfd is read by the running loop."""

    def add_child_handler(
        self, pid: int, callback: Callable[[int, int, Unpack[Args]], object], *args: *Args
    ) -> None:
        loop = asyncio.get_running_loop()
        pidfd = os.pidfd_open(pid)
        loop.add_reader(pidfd, self._reap, loop, pid, pidfd, callback, args)

    @staticmethod
    def _reap(
        loop: asyncio.AbstractEventLoop,
        pid: int,
        pidfd: int,
        callback: Callable[..., object],
        args: tuple[object, ...],
    ) -> None:
        loop.remove_reader(pidfd)
        try:
            _, status = os.waitpid(pid, 0)
        except ChildProcessError:  # reaped by someone else: its status is lost, as asyncio says too
            returncode = 255
            log.warning("child process pid %d was reaped elsewhere; its exit status is unknown", pid)
        else:
            returncode = os.waitstatus_to_exitcode(status)
        os.close(pidfd)
        callback(pid, returncode, *args)

    def remove_child_handler(self, pid: int) -> bool:
        return True  # the pidfd's reader goes with the process's end

    def attach_loop(self, loop: asyncio.AbstractEventLoop | None) -> None:
        pass  # no loop of its own: the spawning loop waits

    def close(self) -> None:
        pass

    def is_active(self) -> bool:
        return True

    def __enter__(self) -> LoopPidfdWatcher:
        return self

    def __exit__(self, *exc: object) -> None:
        pass


@functools.cache
def wait_for_children_on_the_loop() -> None:
    """From now on this process's asyncio waits for its children on the loop (once; see the module)."""
    if sys.version_info >= (3, 12) or not hasattr(os, "pidfd_open"):
        return
    try:
        os.close(os.pidfd_open(os.getpid()))
    except OSError:
        return
    asyncio.set_child_watcher(LoopPidfdWatcher())
