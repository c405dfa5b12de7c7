"""The link monitor's wake-ups: once a second, and at the moment the heartbeat reaches the link-lost limit."""

from __future__ import annotations

import time
from typing import Any

from gateway.config import Settings
from gateway.link.link_monitor import MONITOR_LATE_S, MONITOR_PERIOD_S, monitor_wait_s
from gateway.link.session import Link
from gateway.registry.spec import VehicleSpec


def link(**settings: Any) -> Link:
    return Link(
        VehicleSpec(id="alpha", url="tcpout://127.0.0.1:5760"),
        Settings(_env_file=None, **settings),
        rules_for=lambda _autopilot: None,  # type: ignore[arg-type,return-value]
    )


def test_without_a_session_it_checks_once_a_period() -> None:
    assert monitor_wait_s(link()) == MONITOR_PERIOD_S


def test_it_wakes_when_the_heartbeat_reaches_the_limit() -> None:
    lk = link(link_lost_after_s=3.0)
    lk._system = object()
    now = time.monotonic()
    lk._session_started = now - 10.0
    lk.facts.last_heartbeat = now  # fresh: the limit is 3 s away, the period comes first
    assert monitor_wait_s(lk) == MONITOR_PERIOD_S
    lk.facts.last_heartbeat = now - 2.6  # the limit in 0.4 s: woken then, not at the next period
    assert 0.3 < monitor_wait_s(lk) <= 0.4 + MONITOR_LATE_S
    lk.facts.last_heartbeat = now - 5.0  # already lost: the period again
    assert monitor_wait_s(lk) == MONITOR_PERIOD_S


def test_before_the_first_heartbeat_the_session_start_counts() -> None:
    lk = link(link_lost_after_s=3.0)
    lk._system = object()
    lk._session_started = time.monotonic() - 2.8
    assert 0.1 < monitor_wait_s(lk) <= 0.2 + MONITOR_LATE_S
