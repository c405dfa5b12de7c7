"""Real autopilots for tests: ArduCopter SITL and PX4 SIH (``tests/helpers/autopilots.py``), started from
the binaries that ``eval "$(../shared/sitl/install)"`` points at. Without them every test here skips and
says so. A test starts its own autopilots on instance numbers whose ports are free, in a temporary
folder, and stops them afterwards, also when it fails; or it flies the one its module keeps
(``kept_px4``, ``kept_arducopter``: booting is the expensive part), which every test of that module leaves
on the ground and disarmed, and which is started afresh after a test that failed."""

from __future__ import annotations

import contextlib
from collections.abc import AsyncIterator, Callable, Iterator
from pathlib import Path
from typing import Any

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


def px4_speed_factor(request: pytest.FixtureRequest) -> float:
    """The PX4 SIH speed factor of the requesting test module: its ``PX4_SPEED_FACTOR`` when it sets one
    (a module whose checks cannot hold faster than real time says why there), else the test equipment's
    ``autopilots.PX4_SPEED_FACTOR``."""
    return float(getattr(request.module, "PX4_SPEED_FACTOR", autopilots.PX4_SPEED_FACTOR))


@pytest.fixture
def px4(tmp_path: Path, request: pytest.FixtureRequest) -> Iterator[Autopilot]:
    """PX4 SIH (physics inside the autopilot, lockstep at the module's speed factor), MAVLink UDP 14540 +
    instance."""
    try:
        with autopilots.px4(tmp_path, speed_factor=px4_speed_factor(request)) as ap:
            yield ap
    except autopilots.Unavailable as exc:
        pytest.skip(str(exc))


class KeptAutopilot:
    """One autopilot for the tests of a module, started on first use and stopped with the module, or by
    ``stop`` (after a test that failed, which may have left it flying)."""

    def __init__(self, start: Callable[[], contextlib.AbstractContextManager[Autopilot]]) -> None:
        self._start = start
        self._stack = contextlib.ExitStack()
        self._autopilot: Autopilot | None = None

    def get(self) -> Autopilot:
        if self._autopilot is None:
            self._autopilot = self._stack.enter_context(self._start())
        return self._autopilot

    def on_stop(self, callback: Callable[..., Any], *args: Any) -> None:
        """Call ``callback(*args)`` when the autopilot stops, before its process does."""
        self._stack.callback(callback, *args)

    def stop(self) -> None:
        self._autopilot = None
        stack, self._stack = self._stack, contextlib.ExitStack()
        stack.close()


def _kept(kept: KeptAutopilot, request: pytest.FixtureRequest) -> Iterator[Autopilot]:
    failed = request.session.testsfailed  # counted when the test's call is reported, before teardown
    try:
        autopilot = kept.get()
    except autopilots.Unavailable as exc:
        pytest.skip(str(exc))
    yield autopilot
    if request.session.testsfailed > failed:
        kept.stop()


@pytest.fixture(scope="module")
def kept_px4(
    tmp_path_factory: pytest.TempPathFactory, request: pytest.FixtureRequest
) -> Iterator[KeptAutopilot]:
    factor = px4_speed_factor(request)
    kept = KeptAutopilot(lambda: autopilots.px4(tmp_path_factory.mktemp("px4"), speed_factor=factor))
    try:
        yield kept
    finally:
        kept.stop()


@pytest.fixture
def px4_of_module(kept_px4: KeptAutopilot, request: pytest.FixtureRequest) -> Iterator[Autopilot]:
    """The module's PX4 SIH (``kept_px4``), as the previous test of the module left it: on the ground and
    disarmed, wherever it landed (PX4 sets home where it arms)."""
    yield from _kept(kept_px4, request)


@pytest.fixture(scope="module")
def kept_arducopter(tmp_path_factory: pytest.TempPathFactory) -> Iterator[KeptAutopilot]:
    kept = KeptAutopilot(lambda: autopilots.arducopter(tmp_path_factory.mktemp("arducopter"), speedup=5))
    try:
        yield kept
    finally:
        kept.stop()


@pytest.fixture
def arducopter_of_module(
    kept_arducopter: KeptAutopilot, request: pytest.FixtureRequest
) -> Iterator[Autopilot]:
    """The module's ArduCopter SITL (``kept_arducopter``, speed-up 5), on the ground and disarmed as the
    previous test of the module left it."""
    yield from _kept(kept_arducopter, request)


@pytest.fixture
def launch(tmp_path: Path, request: pytest.FixtureRequest) -> Iterator[Callable[[str, int], list[Autopilot]]]:
    """``launch(kind, n)``: n autopilots of one kind ("ardupilot" at speed-up 5, each with its instance
    number as system id, or "px4") started together, each on its own instance number; all stopped at
    the end of the test, also when it fails. PX4 runs at the module's speed factor."""
    taken: set[int] = set()
    factor = px4_speed_factor(request)
    with contextlib.ExitStack() as stack:

        def start(kind: str, n: int) -> list[Autopilot]:
            def one() -> contextlib.AbstractContextManager[Autopilot]:
                if kind == "px4":
                    return autopilots.px4(tmp_path, taken=taken, speed_factor=factor)
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
