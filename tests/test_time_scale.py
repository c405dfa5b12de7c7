"""The per-test timeout (pytest-timeout) is stretched by the same scale as every deadline the tests wait
on (tests/helpers/timing.py): on a busy machine a test gets the time its own waits are given."""

from __future__ import annotations

import os

import pytest

from tests.helpers.timing import TIME_SCALE


def test_the_per_test_timeout_is_stretched_like_every_deadline(pytestconfig: pytest.Config) -> None:
    given = (
        pytestconfig.getoption("timeout")
        or os.environ.get("PYTEST_TIMEOUT")
        or pytestconfig.getini("timeout")
    )
    assert given, "pytest-timeout has no per-test bound configured"
    assert pytestconfig._env_timeout == pytest.approx(float(given) * TIME_SCALE)  # type: ignore[attr-defined]
