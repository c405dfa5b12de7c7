"""The link monitor: one per connected link, which records the connection state's changes and asks
for the telemetry rates again when the streams stopped while heartbeats go on (a reboot), or while the
autopilot has a home position the gateway has not received; and for the streams whose rate request got
no answer (a timeout on a busy link), with a growing wait.

It checks once a second (``MONITOR_PERIOD_S``), at the ticks every link of the event loop shares
(`gateway.util.ticks`: one timer for the fleet, not one per drone), and when the last heartbeat (or,
before the first, the session's start) reaches the link-lost limit before the next tick,
``MONITOR_LATE_S`` after it (so the heartbeat is then older than the limit)."""

from __future__ import annotations

import asyncio
import time
from typing import Protocol

from gateway.config import Settings
from gateway.link.rawlink import LinkFacts
from gateway.link.telemetry import TelemetryCache
from gateway.util import ticks

MONITOR_PERIOD_S = 1.0
MONITOR_LATE_S = 0.01


class MonitorHost(Protocol):
    """What the monitor needs of its link (``gateway.link.session.Link`` has all of it)."""

    settings: Settings
    telemetry: TelemetryCache
    facts: LinkFacts

    @property
    def last_heartbeat_age_s(self) -> float | None: ...

    @property
    def session_started(self) -> float | None: ...

    def note_state(self) -> None: ...

    def schedule_rates(self, why: str, force: bool = False, only: frozenset[str] | None = None) -> None: ...

    def rates_to_ask_again(self) -> frozenset[str]: ...


class LinkMonitor:
    """Logs state changes and asks for the rates again when streams stopped while heartbeats go on.

    Checks at once, then every ``MONITOR_PERIOD_S`` at the ticks all links share, and when the last
    heartbeat (or, before the first, the session's start) reaches the link-lost limit before the next
    tick: the one change that comes with nothing arriving. Changes that come with data are noted as it
    arrives (the HEARTBEAT loop) or when ``state`` is read; the health and the rate check can wait a
    second."""

    def __init__(self, link: MonitorHost) -> None:
        self._link = link
        loop = asyncio.get_running_loop()
        self._late: asyncio.Handle | None = loop.call_soon(self.check)
        self._tick = ticks.every(MONITOR_PERIOD_S, self.check)

    def check(self) -> None:
        link = self._link
        link.note_state()
        ask_for_rates(link)
        if self._late is not None:
            self._late.cancel()
            self._late = None
        wait = monitor_wait_s(link)
        if wait < MONITOR_PERIOD_S:
            self._late = asyncio.get_running_loop().call_later(wait, self.check)

    def stop(self) -> None:
        self._tick.cancel()
        if self._late is not None:
            self._late.cancel()
            self._late = None


def ask_for_rates(link: MonitorHost) -> None:
    """Every rate again when ``rates_wanted_again`` says why; else the streams whose request got no
    answer, once their retry is due. The session throttles both (``RATE_RETRY_S``)."""
    why = rates_wanted_again(link)
    if why is not None:
        link.schedule_rates(why)
    elif unanswered := link.rates_to_ask_again():
        link.schedule_rates(f"no answer to the rate of {', '.join(sorted(unanswered))}", only=unanswered)
    elif silent := silent_streams(link):
        link.schedule_rates(f"no {', '.join(sorted(silent))} stream while heartbeats continue", only=silent)


#: Streams that every autopilot sends once asked and that a drone cannot be ready without: asked for
#: again alone when silent while heartbeats come (a rate request reported set that never reached the
#: autopilot, as mavsdk_server once did, or one lost on a lossy link)
NEEDED_STREAMS = ("health",)


def silent_streams(link: MonitorHost) -> frozenset[str]:
    """The ``NEEDED_STREAMS`` that have sent nothing for the link-lost limit while heartbeats come, once
    the session is older than that limit (its first request had time to be answered)."""
    hb = link.last_heartbeat_age_s
    started = link.session_started
    lost_after = link.settings.link_lost_after_s
    if started is None or hb is None or hb >= lost_after or time.monotonic() - started < lost_after:
        return frozenset()
    t = link.telemetry
    samples = {"health": t.health}
    return frozenset(
        name for name in NEEDED_STREAMS if (sample := samples[name]) is None or sample.age_s > lost_after
    )


def rates_wanted_again(link: MonitorHost) -> str | None:
    """Why the telemetry rates are to be asked for again while heartbeats come, or None: both requested
    streams silent (a reboot forgets them; a vehicle without GPS may never send a position), or the
    autopilot reports a home position the gateway never received (a drone is ready only with one, home
    comes every few seconds at rest, and a request of it lost on a busy link is not answered again)."""
    hb = link.last_heartbeat_age_s
    if link.session_started is None or hb is None or hb >= link.settings.link_lost_after_s:
        return None
    limit = max(2.0, link.settings.link_lost_after_s * 0.66)
    t = link.telemetry
    if all(sample is None or sample.age_s > limit for sample in (t.position, t.attitude)):
        return "telemetry streams silent while heartbeats continue (reboot?)"
    health = t.health
    if t.home is None and health is not None and health.age_s <= limit and health.value.home_position_ok:
        return "the autopilot has a home position the gateway has not received"
    return None


def monitor_wait_s(link: MonitorHost) -> float:
    """Until the next check: ``MONITOR_PERIOD_S``, or less when the link-lost limit comes first."""
    wait = MONITOR_PERIOD_S
    if (started := link.session_started) is not None:
        hb = link.facts.last_heartbeat
        since = hb if hb is not None else started
        until_lost = since + link.settings.link_lost_after_s - time.monotonic()
        if until_lost >= 0.0:
            wait = min(wait, until_lost + MONITOR_LATE_S)
    return max(MONITOR_LATE_S, wait)
