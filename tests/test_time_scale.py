"""The per-test timeout (pytest-timeout) is stretched by the same scale as every deadline the tests wait
on (tests/helpers/timing.py): on a busy machine a test gets the time its own waits are given."""

from __future__ import annotations

import os

import pytest

from tests.helpers import timing
from tests.helpers.timing import TIME_SCALE


def test_the_per_test_timeout_is_stretched_like_every_deadline(pytestconfig: pytest.Config) -> None:
    given = (
        pytestconfig.getoption("timeout")
        or os.environ.get("PYTEST_TIMEOUT")
        or pytestconfig.getini("timeout")
    )
    assert given, "pytest-timeout has no per-test bound configured"
    assert pytestconfig._env_timeout == pytest.approx(float(given) * TIME_SCALE)  # type: ignore[attr-defined]


def test_a_deadline_stretches_with_the_load_now_when_the_machine_got_busier(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    monkeypatch.setattr(timing, "FIXED_SCALE", None)
    monkeypatch.setattr(timing, "TIME_SCALE", 1.0)
    monkeypatch.setattr(os, "cpu_count", lambda: 2)
    monkeypatch.setattr(os, "getloadavg", lambda: (6.0, 1.0, 1.0))
    assert timing.scaled(10) == pytest.approx(30)
    monkeypatch.setattr(os, "getloadavg", lambda: (40.0, 1.0, 1.0))
    assert timing.scaled(10) == pytest.approx(10 * timing.MAX_AUTO_SCALE)
    # quieter than at the start: never below the start's scale
    monkeypatch.setattr(timing, "TIME_SCALE", 2.0)
    monkeypatch.setattr(os, "getloadavg", lambda: (0.5, 1.0, 1.0))
    assert timing.scaled(10) == pytest.approx(20)


def test_a_fixed_scale_is_not_moved_by_the_load(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(timing, "FIXED_SCALE", 1.5)
    monkeypatch.setattr(os, "getloadavg", lambda: (40.0, 1.0, 1.0))
    assert timing.scaled(10) == pytest.approx(15)
