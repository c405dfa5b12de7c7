"""Conditions a request puts on readings, as a plan's steps write them: a battery threshold ("if above
40 %: ..."), a choice between drones ("the one with less battery: ..."), a comparison of two drones ("if
alpha > charlie: ..."); and the battery readings of a turn they are judged on. The host judges them, not the
model: measured with the 1.5B model, it called 45 % "below 40 %" and picked a drone by a battery it never
read."""

from __future__ import annotations

import re
from collections.abc import Sequence

from gateway.agent.turns import ToolCallRecord

# "above 40 %", "at least 70 percent": a relation and a threshold on a battery reading
_THRESHOLD = (
    r"\b(above|over|more than|at least|below|under|less than|at most)\s+(\d+(?:\.\d+)?)\s*"
    r"(?:%|percent\b|per cent\b)"
)
CONDITION_RE = re.compile(rf"^if\b[^:%]*?{_THRESHOLD}\s*:\s*(.*)$", re.IGNORECASE)
_PERCENT_RE = re.compile(r"(\d+(?:\.\d+)?)\s*%")
_BATTERY_TOOLS = frozenset({"get_battery"})
# "the one with less battery: take off to 7 m": a step for whichever drone the readings pick
PICK_RE = re.compile(
    r"^(?:the (?:one|drone)|whichever(?: one| drone)?)\s+(?:with|that has|has)\s+(?:the\s+)?"
    r"(more|most|higher|highest|fuller|fullest|better|best|stronger|strongest|"
    r"less|least|lower|lowest|weaker|weakest)\s+(?:battery|charge)\b[^:]*:\s*(\S.*)$",
    re.IGNORECASE,
)
# "if alpha > charlie: alpha: fly 20 m north", "if bravo has more battery than charlie: ...": a comparison of
# two drones' readings
VERSUS_RE = re.compile(
    r"^if\s+(\w+)(?:'s)?(?:\s+(?:battery|charge))?\s*"
    r"(>=?|<=?|has (?:more|less)|is (?:higher|lower|more|less))"
    r"(?:\s+(?:battery|charge))?(?:\s+than)?\s+(\w+)(?:'s)?\b[^:]*:\s*(\S.*)$",
    re.IGNORECASE,
)
_FEWER_RE = re.compile(r"^(?:less|least|lower|lowest|weaker|weakest)$", re.IGNORECASE)
_RELATION = (
    r"(more|most|higher|highest|fuller|fullest|better|best|stronger|strongest|"
    r"less|least|lower|lowest|weaker|weakest)"
)
# "only if charlie is above 40 percent", "if bravo has at least 70 % battery": a request's threshold on a
# battery reading
REQUEST_THRESHOLD_RE = re.compile(rf"\b(?:if|when|provided|as long as)\b[^.;:]*?{_THRESHOLD}", re.IGNORECASE)
# "which drone has the most battery left?", "between alpha and charlie, which one is running lower on
# battery?", "which drone's charge is the lowest?": a question that picks a drone by its battery
ASKED_PICK_RE = re.compile(
    rf"\bwhich\b[^?.]*?(?:\b{_RELATION}\b[^?.]*?\b(?:battery|charge|charged)\b|"
    rf"\b(?:battery|charge)\b[^?.]*?\b{_RELATION}\b)",
    re.IGNORECASE,
)


# "the better charged one", "the one with less charge", "whichever drone has the most battery", "compare
# them on battery and send the fuller one": a request's choice of a drone by its battery
_REQUEST_PICK_RE = re.compile(
    rf"\b{_RELATION}(?:[- ]charged\b|\s+(?:battery|charge)\b)|"
    rf"\b(?:the|whichever)\s+{_RELATION}\s+(?:one|drone)\b",
    re.IGNORECASE,
)
_BATTERY_WORD_RE = re.compile(r"\b(?:battery|charge|charged)\b", re.IGNORECASE)


def request_pick(request: str) -> str | None:
    """The relation of a request's choice of a drone by its battery ("more", "less", ...), or None; a
    question that picks a drone (ASKED_PICK_RE) is no choice to fly."""
    if ASKED_PICK_RE.search(request) or not _BATTERY_WORD_RE.search(request):
        return None
    m = _REQUEST_PICK_RE.search(request)
    return (m.group(1) or m.group(2)) if m else None


def holds(relation: str, reading: float, threshold: float) -> bool:
    """Whether a reading meets a threshold condition ("above", "at least", ...)."""
    relation = relation.lower()
    if relation in ("above", "over", "more than"):
        return reading > threshold
    if relation == "at least":
        return reading >= threshold
    if relation in ("below", "under", "less than"):
        return reading < threshold
    return reading <= threshold  # at most


def battery_readings(calls: Sequence[ToolCallRecord], fleet_ids: Sequence[str]) -> dict[str, float]:
    """Each drone's latest battery percent read in the turn: from get_battery, or a fleet_status table
    (``alpha ready n n 90 0.0 ...``: the fifth column)."""
    found: dict[str, float] = {}
    for call in calls:
        if not call.ok:
            continue
        text = call.text or call.summary
        if call.name in _BATTERY_TOOLS and (m := _PERCENT_RE.search(text)):
            found[str((call.arguments or {}).get("drone_id", ""))] = float(m.group(1))
        elif call.name == "fleet_status":
            for d in fleet_ids:
                row = re.search(rf"^{re.escape(d)}\s+\S+\s+\S+\s+\S+\s+(\d+(?:\.\d+)?)\b", text, re.M)
                if row:
                    found[d] = float(row.group(1))
    return found


def pick(
    relation: str, candidates: Sequence[str], readings: dict[str, float]
) -> tuple[str | None, list[str]]:
    """The drone the readings pick (most or least battery) among the candidates, or None with the
    candidates not read yet."""
    unread = [d for d in candidates if d not in readings]
    if unread or not candidates:
        return None, unread
    return (min if fewer(relation) else max)(candidates, key=lambda d: readings[d]), []


def asked_pick(request: str, fleet_ids: Sequence[str]) -> tuple[str, list[str]] | None:
    """The relation and the candidates of a question that picks a drone by its battery ("which has the
    least charge?"): the drones the request names when it names two or more, else the whole fleet."""
    m = ASKED_PICK_RE.search(request)
    if m is None:
        return None
    named = [d for d in fleet_ids if re.search(rf"\b{re.escape(d)}\b", request, re.IGNORECASE)]
    return (m.group(1) or m.group(2)), (named if len(named) >= 2 else list(fleet_ids))


def pick_unsaid(
    request: str, calls: Sequence[ToolCallRecord], fleet_ids: Sequence[str], answer: str
) -> str | None:
    """For a question that picks a drone, the host's line on the pick when the answer does not name the
    drone this turn's readings pick (None when it does, or when not every candidate was read). Measured on
    the corpus's dev half with the 1.5B model: the three batteries read (54, 69, 91 %), "which drone has the
    most battery left?" was answered "alpha has the most battery left with 54%"."""
    asked = asked_pick(request, fleet_ids)
    if asked is None:
        return None
    relation, candidates = asked
    found = battery_readings(calls, fleet_ids)
    chosen, _unread = pick(relation, candidates, found)
    if chosen is None or re.search(rf"\b{re.escape(chosen)}\b", answer, re.IGNORECASE):
        return None
    which = "least" if fewer(relation) else "most"
    read = ", ".join(f"{d} {found[d]:g} %" for d in candidates)
    return f"{chosen} has the {which} battery ({read})"


def fewer(relation: str) -> bool:
    """The choice is of the drone with the least battery ("less", "lowest", "weaker")."""
    return bool(_FEWER_RE.match(relation))


def first_leads(relation: str, first: float, second: float) -> bool:
    """Whether a comparison of two readings ("alpha > charlie", "has less") holds."""
    more = relation.startswith(">") or relation.lower().endswith(("more", "higher"))
    return first > second if more else first < second


def last_reading(calls: Sequence[ToolCallRecord]) -> tuple[str, float] | None:
    """The latest battery reading of the turn: which drone, what percent."""
    for call in reversed(calls):
        if call.ok and call.name in _BATTERY_TOOLS:
            m = _PERCENT_RE.search(call.text or call.summary)
            if m:
                return str((call.arguments or {}).get("drone_id", "")), float(m.group(1))
    return None
