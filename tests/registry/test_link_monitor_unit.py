"""The link monitor's wake-ups: once a second, and at the moment the heartbeat reaches the link-lost limit."""

from __future__ import annotations

import time
from typing import Any

from gateway.config import Settings
from gateway.link.link_monitor import (
    MONITOR_LATE_S,
    MONITOR_PERIOD_S,
    ask_for_rates,
    monitor_wait_s,
    rates_wanted_again,
    silent_streams,
)
from gateway.link.session import Link, LinkHooks
from gateway.link.telemetry import HealthValue
from gateway.registry.spec import VehicleSpec


def link(rules: Any = None, **settings: Any) -> Link:
    """A link with no session, its autopilot's rules ``rules`` (a dialect)."""
    return Link(
        VehicleSpec(id="alpha", url="tcpout://127.0.0.1:5760"),
        Settings(_env_file=None, **settings),
        LinkHooks(rules_for=lambda _autopilot: rules),
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


def _connected(lk: Link) -> Link:
    lk._system = object()
    lk._session_started = time.monotonic() - 10.0
    lk.facts.last_heartbeat = time.monotonic()
    return lk


def _health(home_ok: bool) -> HealthValue:
    return HealthValue(True, True, True, True, True, home_ok, True)


def test_rates_are_asked_again_while_the_autopilot_has_a_home_the_gateway_never_received() -> None:
    lk = _connected(link(link_lost_after_s=3.0))
    lk.telemetry.put("position", object())
    lk.telemetry.put("health", _health(home_ok=False))
    assert rates_wanted_again(lk) is None  # no home on the autopilot either: nothing lost
    lk.telemetry.put("health", _health(home_ok=True))
    assert rates_wanted_again(lk) == "the autopilot has a home position the gateway has not received"
    lk.telemetry.put("home", object())
    assert rates_wanted_again(lk) is None
    lk.facts.last_heartbeat = time.monotonic() - 5.0  # link lost: nothing asked for
    lk.telemetry.home = None
    assert rates_wanted_again(lk) is None


def test_rates_are_asked_again_when_both_streams_fall_silent_under_fresh_heartbeats() -> None:
    lk = _connected(link(link_lost_after_s=3.0))
    assert rates_wanted_again(lk) == "telemetry streams silent while heartbeats continue (reboot?)"
    lk.telemetry.put("attitude", object())
    assert rates_wanted_again(lk) is None


def test_streams_without_an_answer_are_asked_for_alone_once_due() -> None:
    """The monitor asks again only for the streams whose rate request got no answer (the feed says when
    that is due), and asks for every rate when the streams fell silent."""
    lk = _connected(link(link_lost_after_s=3.0))
    lk.telemetry.put("position", object())
    lk.telemetry.put("health", _health(home_ok=False))
    asked: list[tuple[str, frozenset[str] | None]] = []
    due: frozenset[str] = frozenset()
    lk.schedule_rates = lambda why, force=False, only=None: asked.append((why, only))  # type: ignore[method-assign]
    lk.rates_to_ask_again = lambda: due  # type: ignore[method-assign]
    ask_for_rates(lk)
    assert asked == []  # everything answered
    due = frozenset({"health", "home"})
    ask_for_rates(lk)
    assert asked == [("no answer to the rate of health, home", due)]
    asked.clear()
    lk.telemetry.position = None  # silent streams: every rate, not only the unanswered ones
    ask_for_rates(lk)
    assert asked == [("telemetry streams silent while heartbeats continue (reboot?)", None)]


def test_an_ardupilot_drone_is_not_ready_before_its_first_ekf_report() -> None:
    """MAVSDK's health says "local position ok" once ArduPilot's EKF has an origin, seconds before the
    EKF uses GPS and the autopilot lets it arm: without an EKF_STATUS_REPORT yet, the drone is still
    initialising (unless the autopilot refused the stream; then the health decides)."""
    from types import SimpleNamespace

    from pymavlink.dialects.v20 import ardupilotmega as mav

    from gateway.fleet.dialects import ARDUPILOT

    lk = link(ARDUPILOT)
    session = SimpleNamespace(ekf_flags=None)
    lk._mavsdk = session  # type: ignore[assignment]
    lk._session_started = time.monotonic()
    lk._feed = SimpleNamespace(unsupported_rates={})  # type: ignore[assignment]
    lk.telemetry.put("home", object())
    lk.telemetry.put("battery", object())
    health = _health(home_ok=True)
    assert lk._waiting_for(health) == "waiting for the position estimate (no EKF status report yet)"
    session.ekf_flags = mav.EKF_ATTITUDE | mav.EKF_POS_VERT_ABS  # the EKF not using GPS yet
    assert lk._waiting_for(health) == "waiting for the position estimate (the EKF is not using GPS yet)"
    session.ekf_flags = mav.EKF_ATTITUDE | mav.EKF_POS_HORIZ_ABS
    assert lk._waiting_for(health) is None
    session.ekf_flags = None
    lk._feed.unsupported_rates = {"ekf_status": "refused"}  # the health's word stands
    assert lk._waiting_for(health) is None
    lk._feed.unsupported_rates = {}
    lk._session_started = time.monotonic() - 31.0  # no report after 30 s: the health decides too
    assert lk._waiting_for(health) is None


def test_an_armed_drone_keeps_its_home_while_mavsdk_forgets_it_after_a_reconnect() -> None:
    """MAVSDK's health says "no home" after every reconnect until the next HOME_POSITION: a disarmed
    drone waits for it (a rebooted autopilot's home is new), an armed one flies on with the home the
    gateway has (a late heartbeat in flight must not block a landing)."""
    from types import SimpleNamespace

    from pymavlink.dialects.v20 import ardupilotmega as mav

    from gateway.fleet.dialects import ARDUPILOT

    lk = link(ARDUPILOT)
    lk._mavsdk = SimpleNamespace(ekf_flags=mav.EKF_POS_HORIZ_ABS)  # type: ignore[assignment]
    lk.telemetry.put("home", object())
    lk.telemetry.put("armed", False)
    forgotten = _health(home_ok=False)
    assert lk._waiting_for(forgotten) == "waiting for the home position"
    lk.telemetry.put("armed", True)
    assert lk._waiting_for(forgotten) is None
    lk.telemetry.home = None  # never received: armed or not, no home
    assert lk._waiting_for(forgotten) == "waiting for the home position"


def test_a_health_stream_that_never_came_is_asked_for_again_alone() -> None:
    """A drone heard (heartbeats fresh, position and attitude streaming) whose SYS_STATUS never came is
    never ready: once the session is older than the link-lost limit, its health stream is asked for again,
    alone (a rate request reported set that never reached the autopilot)."""
    lk = _connected(link(link_lost_after_s=3.0))
    lk.telemetry.put("position", object())
    lk.telemetry.put("attitude", object())
    asked: list[tuple[str, frozenset[str] | None]] = []
    lk.schedule_rates = lambda why, force=False, only=None: asked.append((why, only))  # type: ignore[method-assign]
    lk.rates_to_ask_again = lambda: frozenset()  # type: ignore[method-assign]
    ask_for_rates(lk)
    assert asked == [("no health stream while heartbeats continue", frozenset({"health"}))]
    asked.clear()
    lk.telemetry.put("health", _health(home_ok=False))
    ask_for_rates(lk)
    assert asked == [] and silent_streams(lk) == frozenset()
    lk.telemetry.health = None
    lk._session_started = time.monotonic() - 1.0  # the first request may still be answered: not yet
    assert silent_streams(lk) == frozenset()
    lk._session_started = time.monotonic() - 10.0
    lk.facts.last_heartbeat = time.monotonic() - 5.0  # link lost: nothing to ask
    assert silent_streams(lk) == frozenset()


def test_a_px4_drone_initialises_until_its_pre_arm_bit_has_passed_once() -> None:
    """PX4 has its home and local position a moment before its heading ("Preflight Fail: no heading
    reference"), and then refuses to arm with "Resolve system health failures first": a disarmed PX4 is
    ready once its pre-arm bit said armable in the session; later, the bit follows the mode (LAND is not
    armable), which is not initialising."""
    from gateway.fleet.dialects import PX4_DIALECT

    lk = link(PX4_DIALECT)
    lk.telemetry.put("home", object())
    lk.telemetry.put("armed", False)
    heading_missing = HealthValue(True, True, True, True, True, True, False)
    assert lk._waiting_for(heading_missing) == "waiting for the autopilot's pre-arm checks"
    assert lk._waiting_for(_health(home_ok=True)) is None
    assert lk._waiting_for(heading_missing) is None  # passed once: LAND's "not armable" is not boot
    lk._prearm_passed = False  # a new session
    lk.telemetry.put("armed", True)  # found flying: it passed its checks before this session
    assert lk._waiting_for(heading_missing) is None
    assert lk._prearm_passed


def test_a_drone_is_not_ready_before_its_first_battery_reading_for_a_while() -> None:
    """The safety policy refuses a takeoff whose battery is unknown: a drone is still initialising until
    its first battery reading, unless none came in BATTERY_REPORT_WAIT_S (then it is ready without)."""
    from gateway.fleet.dialects import PX4_DIALECT
    from gateway.link.session import BATTERY_REPORT_WAIT_S

    lk = link(PX4_DIALECT)
    lk._session_started = time.monotonic()
    lk.telemetry.put("home", object())
    health = _health(home_ok=True)
    assert lk._waiting_for(health) == "waiting for a battery reading"
    lk.telemetry.put("battery", object())
    assert lk._waiting_for(health) is None
    lk.telemetry.battery = None
    lk._session_started = time.monotonic() - BATTERY_REPORT_WAIT_S - 1  # none came: ready without it
    assert lk._waiting_for(health) is None
