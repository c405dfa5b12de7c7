"""Shared fixtures. Integration tests start real processes: every one is cleaned up, even on failure."""

from __future__ import annotations

import os
import signal
import subprocess
from collections.abc import AsyncIterator, Iterator
from pathlib import Path

import pytest
from hypothesis import settings as hypothesis_settings

from gateway.registry.store import Store
from tests.helpers.file_order import longest_files_first, seconds_per_file
from tests.helpers.sqlite_at_head import at_head
from tests.helpers.suite_tail import SuiteTail, from_environment
from tests.helpers.timing import TIME_SCALE, scaled

# no per-example time limit: Hypothesis's default 200 ms deadline is a wall-clock threshold, which fails a
# correct property on a busy machine (tests judge behaviour, bench/ measures speed)
hypothesis_settings.register_profile("fleet", deadline=None)
hypothesis_settings.load_profile("fleet")


def pytest_report_header(config: pytest.Config) -> str:
    fixed = os.environ.get("FLEET_TEST_TIME_SCALE")
    source = "FLEET_TEST_TIME_SCALE" if fixed else "load average at start; more where it grows"
    return f"test deadlines x{TIME_SCALE:g} ({source})"


@pytest.hookimpl(trylast=True)
def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    """Longest test files first (tests/helpers/file_order.py), so the workers of ``make test`` finish
    together; the order is all it changes."""
    order = longest_files_first(items, seconds_per_file())
    items[:] = [items[i] for i in order]


_tail: SuiteTail | None = None


def _controlling(config: pytest.Config) -> bool:
    """The process that sees every test's report: pytest itself, or xdist's controller (not a worker)."""
    return not hasattr(config, "workerinput")


def pytest_sessionstart(session: pytest.Session) -> None:
    """CI's signal that the suite is near its end (tests/helpers/suite_tail.py), when asked for."""
    global _tail
    workers = session.config.getoption("numprocesses", None)
    count = workers if isinstance(workers, int) and workers > 0 else 1
    tail = from_environment(count, seconds_per_file())  # read everywhere: it leaves the environment
    _tail = tail if _controlling(session.config) else None


@pytest.hookimpl(optionalhook=True)
def pytest_xdist_node_collection_finished(node: object, ids: list[str]) -> None:
    if _tail is not None:
        _tail.collected(ids)


def pytest_collection_finish(session: pytest.Session) -> None:
    if _tail is not None and _controlling(session.config):
        _tail.collected(item.nodeid for item in session.items)


def pytest_runtest_logreport(report: pytest.TestReport) -> None:
    if _tail is not None and report.when == "teardown":
        _tail.finished(report.nodeid)


@pytest.hookimpl(trylast=True)
def pytest_configure(config: pytest.Config) -> None:
    """FLEET_TEST_TIME_SCALE stretches pytest-timeout's per-test bound like every other deadline (last:
    pytest-timeout's own pytest_configure sets the bound this stretches)."""
    timeout = getattr(config, "_env_timeout", None)
    if timeout and TIME_SCALE != 1.0:
        config._env_timeout = timeout * TIME_SCALE  # type: ignore[attr-defined]


@pytest.fixture
def process_reaper() -> Iterator[list[subprocess.Popen]]:
    """Append every Popen a test starts; they are terminated (then killed) when the test ends."""
    procs: list[subprocess.Popen] = []
    yield procs
    for proc in procs:
        if proc.poll() is None:
            try:
                os.killpg(proc.pid, signal.SIGTERM) if _own_group(proc) else proc.terminate()
            except ProcessLookupError:
                pass
    for proc in procs:
        try:
            proc.wait(timeout=scaled(5))
        except subprocess.TimeoutExpired:
            try:
                os.killpg(proc.pid, signal.SIGKILL) if _own_group(proc) else proc.kill()
            except ProcessLookupError:
                pass
            proc.wait(timeout=scaled(5))


def _own_group(proc: subprocess.Popen) -> bool:
    try:
        return os.getpgid(proc.pid) == proc.pid
    except ProcessLookupError:
        return False


@pytest.fixture
def db_url(tmp_path: Path) -> str:
    """A fresh SQLite file per test (tests/persist overrides it to run on PostgreSQL too)."""
    return f"sqlite+aiosqlite:///{tmp_path / 'gateway.db'}"


@pytest.fixture
async def store(db_url: str) -> AsyncIterator[Store]:
    """A Store opened on ``db_url`` (a fresh SQLite file is copied at the schema's head first:
    tests/helpers/sqlite_at_head.py), closed after the test."""
    opened = await Store.open(await at_head(db_url))
    try:
        yield opened
    finally:
        await opened.close()
