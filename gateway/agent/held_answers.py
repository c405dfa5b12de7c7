"""Answers the host sends back once before it takes them: given before anything ran, or silent about
a refusal. Each reason holds an answer back at most once a turn (``TurnMemory.held``)."""

from __future__ import annotations

import re
from collections.abc import Sequence

from gateway.agent import readings, wording
from gateway.agent.claims import Claim
from gateway.agent.turns import ToolCallRecord, TurnMemory, TurnResult

_NUMBER_RE = re.compile(r"-?\d+(?:\.\d+)?")


def nothing_ran(result: TurnResult, memory: TurnMemory, answer_tool: bool) -> str | None:
    """An answer given before any call reached the gateway in this turn is sent back once (a small
    model's habit, so with the answer tool): nothing was read or done, so it is a guess. Measured on
    the corpus's dev half with the 1.5B model: "only if charlie is above 40 percent, send it up to 12 m
    and back down" answered "Charlie is above 40 percent, sending it up ..." with no call at all, and
    "are any of the drones flying?" answered that all three flew (all three were on the ground). Once
    a turn: a model that answers again is believed (a greeting, or a question the roster answers)."""
    held = memory.held
    ran = any(c.status in ("ok", "error") for c in result.tool_calls)
    if not answer_tool or ran or "nothing_ran" in held:
        return None
    held.add("nothing_ran")
    return wording.NOTHING_RAN


def refusal_unsaid(result: TurnResult, memory: TurnMemory, text: str) -> str | None:
    """An answer that does not mention a refusal by the gateway's rules this turn is sent back once,
    quoting the refusal: every turn ends with a true answer, and a refused part of a request is part of
    it. Measured on the corpus's dev half (refuse-all-150m): refused 150 m, the 1.5B model flew alpha to
    120 m and answered "Alpha ... is now flying at 120 m above home", with no word of the refusal."""
    refusals = [c for c in result.tool_calls if wording.refused(c)]
    if not refusals or "refusal" in memory.held or wording.says_refused(text):
        return None
    memory.held.add("refusal")
    return wording.refusal_unsaid(refusals[-1])


def claims_unbacked(memory: TurnMemory, claims: list[Claim], offered: set[str]) -> str | None:
    """An answer that says a drone acted when no call this turn acted on it (claims.py) is sent back once,
    naming the drone, the words and where it is now; a model that answers the same again is believed, and
    the host adds what the gateway did (wording.with_unbacked)."""
    if not claims or "claims" in memory.held:
        return None
    memory.held.add("claims")
    return wording.claims_unbacked(claims, offered)


def written_blind(memory: TurnMemory, reads: Sequence[ToolCallRecord], text: str) -> str | None:
    """An answer written in the same reply as the reads it reports on, before their results came back, is
    sent back once with the readings, unless it already states one of their numbers. Measured on the
    corpus's dev half with the 1.5B model: "charlie up to 15 m, but only if its battery is over 60 %. Tell
    me what you decided" was get_battery and, in the same reply, "Charlie's battery is below 60%"; the
    reading (30 %) never reached the user."""
    if not reads or "blind" in memory.held:
        return None
    said = {float(n) for n in _NUMBER_RE.findall(text)}
    read = {float(n) for c in reads for n in _NUMBER_RE.findall(c.text or c.summary)}
    if any(abs(a - b) < 0.5 for a in said for b in read):
        return None
    memory.held.add("blind")
    return wording.written_blind(reads)


def pick_unsaid(memory: TurnMemory, result: TurnResult, fleet_ids: Sequence[str], text: str) -> str | None:
    """An answer to a question that picks a drone ("which has the most battery?") that does not name the
    drone the readings pick is sent back once with the readings (readings.pick_unsaid); a model that
    answers the same again is believed, and the host adds the pick (wording.with_pick)."""
    if "pick" in memory.held:
        return None
    pick = readings.pick_unsaid(memory.request, result.tool_calls, fleet_ids, text)
    if pick is None:
        return None
    memory.held.add("pick")
    return wording.pick_unsaid(pick)
