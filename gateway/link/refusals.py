"""Why the autopilot refused a command, in its own words, for the error the caller gets.

Autopilots explain a refusal in STATUSTEXT (ArduPilot: one "Arm: ..." text per failing check, sent just
before the COMMAND_ACK; PX4: STATUSTEXT or an event), not in the ACK. MAVSDK delivers those texts on
another stream than the command's result, so they can arrive a little after it: ``explain`` waits a
moment for them. When the autopilot said nothing, the error names what the vehicle was doing instead,
so that a refusal never reads as a bare ``Failed (FAILED)``.
"""

from __future__ import annotations

import asyncio
from collections.abc import Callable, Iterable

from gateway.link.telemetry import StatusTextValue

#: severities that can explain a refusal (PX4 reports some refusals as "notice" events)
RELEVANT = frozenset({"notice", "warning", "error", "critical", "alert", "emergency"})
MAX_TEXTS = 4  # ArduPilot reports every failing arming check; the first few say enough
MAX_CHARS = 200
TEXT_GRACE_S = 0.5  # how long to wait for a first text after the command's result
SETTLE_S = 0.1  # after a first text, how long to wait for the rest of the same report


def said_since(texts: Iterable[StatusTextValue], since: float, limit: int = MAX_TEXTS) -> list[str]:
    """The distinct warning-or-worse texts received at or after ``since`` (wall clock), oldest first;
    the newest ``limit`` when there are more."""
    out: list[str] = []
    for item in texts:
        if item.t < since or item.severity not in RELEVANT:
            continue
        text = " ".join(item.text.split())[:MAX_CHARS]
        if text and text not in out:
            out.append(text)
    return out[-limit:]


def quoted(said: list[str]) -> str:
    """``'A'; 'B'`` for a message."""
    return "; ".join(f"'{text}'" for text in said)


async def wait_said(
    texts: Callable[[], Iterable[StatusTextValue]], since: float, grace_s: float = TEXT_GRACE_S
) -> list[str]:
    """``said_since``, waiting up to ``grace_s`` for a first text and briefly for the rest of a report."""
    loop = asyncio.get_running_loop()
    deadline = loop.time() + grace_s
    said = said_since(texts(), since)
    while not said and loop.time() < deadline:
        await asyncio.sleep(0.05)
        said = said_since(texts(), since)
    if said:
        await asyncio.sleep(SETTLE_S)
        said = said_since(texts(), since)
    return said


def explain(said: list[str], facts: str) -> str:
    """The tail of a refusal message: the autopilot's words, or what the vehicle was doing."""
    if said:
        return f" (autopilot says: {quoted(said)})"
    return f" (the autopilot gave no reason; {facts})"
