"""Does a valid plan carry what its request gives? Read without words: the fleet's ids and the numbers.

A plan can validate and still leave out a drone the request names (a drone placed relative to another
drone, planned relative to itself), fly a drone the request does not name, or drop a number the request
gives (a height or a distance). Each such gap becomes a note that the planner sends back once for a
corrected plan. A request that names no drone (``all three``, ``the fullest one``) is not read for ids.
"""

from __future__ import annotations

from typing import Any

from fleet_agent.plan import Plan

_DRONE_FIELDS = ("drone", "drones", "among")


def gaps(request: str, fleet: list[str], plan: Plan) -> list[str]:
    """What the plan leaves out of (or adds to) the request: one short note each."""
    data = plan.model_dump(mode="json")
    notes = _drone_gaps(request, fleet, data)
    numbers = _plan_numbers(data)
    for given in _request_numbers(request, fleet):
        if not any(abs(given - n) < 1e-6 for n in numbers):
            notes.append(f"the request gives {given:g}, which no step of the plan has")
    return notes


def without_unasked(request: str, fleet: list[str], plan: Plan) -> Plan:
    """The plan without its steps for a drone the request does not name, when it names any: the model
    added a step for a drone it had seen in an example (a repair asked for it wrote the same plan)."""
    named = _named(request, fleet)
    if not named:
        return plan
    kept = [s for s in plan.steps if getattr(s, "drone", None) in (None, *named)]
    return plan if len(kept) == len(plan.steps) else plan.model_copy(update={"steps": kept})


def _named(request: str, fleet: list[str]) -> set[str]:
    by_lower = {d.lower(): d for d in fleet}
    return {by_lower[w] for w in _words(request.lower()) if w in by_lower}


def _drone_gaps(request: str, fleet: list[str], data: Any) -> list[str]:
    named = _named(request, fleet)
    if not named:
        return []
    planned = _plan_drones(data)
    notes = [
        f"the request names {d}, which no step of the plan does (as the drone that acts, or as a move's "
        f'origin "{d}")'
        for d in sorted(named - planned)
    ]
    notes += [f"the plan has {d}, which the request does not name" for d in sorted(planned - named)]
    return notes


def _words(text: str) -> list[str]:
    """The words of a text, in any script: runs of letters and digits (an id is matched against these)."""
    return "".join(c if c.isalnum() or c in "_-" else " " for c in text).split()


def _request_numbers(request: str, fleet: list[str]) -> list[float]:
    """The numbers of the request (digits, with a decimal point or comma), a drone id's digits left out."""
    ids = {d.lower() for d in fleet}
    text = " ".join(w for w in _words(request.replace(".", "_").replace(",", "_")) if w.lower() not in ids)
    runs = "".join(c if c.isdigit() or c == "_" else " " for c in text).split()
    numbers = []
    for run in runs:
        digits = run.strip("_").split("_")
        if digits[0]:
            numbers.append(float(".".join(digits[:2])))
    return numbers


def _plan_drones(data: Any) -> set[str]:
    found: set[str] = set()
    for key, value in _items(data):
        if key in _DRONE_FIELDS:
            items = [value] if isinstance(value, str) else value or []
            found.update(v for v in items if isinstance(v, str))
    return found


def _plan_numbers(data: Any) -> list[float]:
    return [float(v) for _, v in _items(data) if isinstance(v, int | float) and not isinstance(v, bool)]


def _items(data: Any) -> list[tuple[str, Any]]:
    """Every (key, value) of a decoded JSON document, nested ones included."""
    out: list[tuple[str, Any]] = []
    if isinstance(data, dict):
        for key, value in data.items():
            out.append((key, value))
            out += _items(value)
    elif isinstance(data, list):
        for value in data:
            out += _items(value)
    return out
