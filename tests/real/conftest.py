"""Real autopilots for tests: ArduCopter SITL and PX4 SIH (``tests/helpers/autopilots.py``), started from
the binaries that ``eval "$(../shared/sitl/install)"`` points at. Without them every test here skips and
says so. Each test starts its own autopilots on instance numbers whose ports are free, in a temporary
folder, and stops them afterwards, also when it fails."""

from __future__ import annotations

import contextlib
from collections.abc import AsyncIterator, Callable, Iterator
from pathlib import Path

import pytest

from gateway.fleet.vehicles.registry import Registry
from tests.helpers import autopilots
from tests.helpers.autopilots import Autopilot
from tests.registry.conftest import fast_settings

pytestmark = pytest.mark.real


@pytest.fixture
def arducopter(tmp_path: Path) -> Iterator[Autopilot]:
    """ArduCopter SITL at speed-up 5 (about 9 s from start to flyable), TCP 5760 + 10 * instance."""
    try:
        with autopilots.arducopter(tmp_path, speedup=5) as ap:
            yield ap
    except autopilots.Unavailable as exc:
        pytest.skip(str(exc))


@pytest.fixture
def px4(tmp_path: Path) -> Iterator[Autopilot]:
    """PX4 SIH (physics inside the autopilot; real time only), MAVLink UDP 14540 + instance."""
    try:
        with autopilots.px4(tmp_path) as ap:
            yield ap
    except autopilots.Unavailable as exc:
        pytest.skip(str(exc))


@pytest.fixture
def launch(tmp_path: Path) -> Iterator[Callable[[str, int], list[Autopilot]]]:
    """``launch(kind, n)``: n autopilots of one kind ("ardupilot" at speed-up 5, each with its instance
    number as system id, or "px4") started together, each on its own instance number; all stopped at
    the end of the test, also when it fails."""
    taken: set[int] = set()
    with contextlib.ExitStack() as stack:

        def start(kind: str, n: int) -> list[Autopilot]:
            def one() -> contextlib.AbstractContextManager[Autopilot]:
                if kind == "px4":
                    return autopilots.px4(tmp_path, taken=taken)
                return autopilots.arducopter(tmp_path, speedup=5, sysid=None, taken=taken)

            try:
                return [stack.enter_context(one()) for _ in range(n)]
            except autopilots.Unavailable as exc:
                pytest.skip(str(exc))

        yield start


@pytest.fixture
async def registry(store) -> AsyncIterator[Registry]:  # type: ignore[no-untyped-def]
    reg = Registry(fast_settings(link_lost_after_s=3.0), store)
    await reg.start()
    try:
        yield reg
    finally:
        await reg.stop()
