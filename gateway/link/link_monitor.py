"""The link monitor: one task per connected link that records the connection state's changes and asks
for the telemetry rates again when the streams stopped while heartbeats go on (a reboot).

It wakes once a second (``MONITOR_PERIOD_S``), and when the last heartbeat (or, before the first, the
session's start) reaches the link-lost limit, ``MONITOR_LATE_S`` after it (so the heartbeat is then
older than the limit)."""

from __future__ import annotations

import asyncio
import time
from typing import Protocol

from gateway.config import Settings
from gateway.link.rawlink import LinkFacts
from gateway.link.telemetry import TelemetryCache

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

    def schedule_rates(self, why: str, force: bool = False) -> None: ...


async def run_monitor(link: MonitorHost) -> None:
    """Log state changes and re-request rates when streams stopped while heartbeats go on.

    Wakes once a second (``MONITOR_PERIOD_S``), and when the last heartbeat (or, before the first, the
    session's start) reaches the link-lost limit: the one change that comes with nothing arriving.
    Changes that come with data are noted as it arrives (the HEARTBEAT loop) or when ``state`` is
    read; the health and the rate check can wait a second."""
    while True:
        link.note_state()
        if link.session_started is not None:
            hb = link.last_heartbeat_age_s
            heartbeats_fresh = hb is not None and hb < link.settings.link_lost_after_s
            limit = max(2.0, link.settings.link_lost_after_s * 0.66)
            # both requested streams silent (a vehicle without GPS may never send a position)
            streams_silent = all(
                sample is None or sample.age_s > limit
                for sample in (link.telemetry.position, link.telemetry.attitude)
            )
            if heartbeats_fresh and streams_silent:
                link.schedule_rates("telemetry streams silent while heartbeats continue (reboot?)")
        await asyncio.sleep(monitor_wait_s(link))


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
