"""A small model's first step: the request split into numbered steps, one drone and one action each.

Measured with the 1.5B model: a request's first tool-calling reply decides the run (at temperature 0 it
repeats that plan after every note), and the plan goes wrong where one sentence carries several numbers
("up to 12 m, over 35 m to the west" flew takeoff(alt_m=35)). Asked first, without tools and with a
handful of examples, to write the request as steps ("alpha: take off to 12 m", "alpha: fly 35 m west"),
it keeps each number with its action; the steps then go to the tool-calling conversation under the request.
The request itself stays what the host's checks read: the steps only help the model, never the judge.

The examples use drones that are not in the fleet (delta, echo, foxtrot) and requests that are not in the
benchmark's corpus.
"""

from __future__ import annotations

import json
import re
from collections.abc import Sequence
from dataclasses import dataclass, field

from gateway.agent import readings
from gateway.agent.answer import ANSWER_TOOL
from gateway.agent.chat import ChatModel, Message
from gateway.agent.checks import BACK_ON_THE_GROUND
from gateway.agent.repair import request_climbs
from gateway.agent.roster import Roster, drones_named
from gateway.agent.step_calls import StepCall, call_of_step, leg_without_height
from gateway.agent.turns import ToolCallRecord, Usage
from gateway.agent.wording import already_so, first_line

PLAN_SYSTEM_PROMPT = (
    "Split the user's drone request into numbered steps: one drone and one action per step, in the order "
    "asked, with the numbers from the request. Hovering or staying up is no step. Write only the steps."
)

_EXAMPLE_FLEET = "delta, echo, foxtrot"
PLAN_EXAMPLES: tuple[tuple[str, str], ...] = (
    (
        "Could you send delta up to 14 metres, then 20 m south of there, and bring it down?",
        "1. delta: take off to 14 m\n2. delta: fly 20 m south\n3. delta: land",
    ),
    (
        "echo and delta 60 m north at 22 m, then home",
        "1. echo: fly 60 m north at 22 m\n2. delta: fly 60 m north at 22 m\n3. echo: return home\n"
        "4. delta: return home",
    ),
    (
        "If delta's battery is over 55 percent, take it 5 m higher; if not, just say how much it has",
        "1. delta: read battery\n2. if above 55 %: delta: climb 5 m\n3. otherwise: tell the battery",
    ),
    (
        "Put all of them in a wedge 9 m apart at 16 m, 30 m west of where they are",
        "1. delta, echo, foxtrot: wedge formation, 9 m apart, at 16 m, 30 m west",
    ),
    # a choice between drones by their readings: the host reads which one it is (dev half: "launch the
    # better charged one" flew both, one after the other)
    (
        "Whichever of echo and foxtrot has less charge, send it up to 7 m and land it; the other stays down",
        "1. echo: read battery\n2. foxtrot: read battery\n3. the one with less battery: take off to 7 m\n"
        "4. the one with less battery: land",
    ),
    ("How high is echo?", "1. echo: read position"),
    # one move that goes several ways is one step, and a drone left where it is gets no landing (dev half:
    # "25 m north and 8 m up" became two moves; "... and leave it there" got a landing)
    (
        "Take foxtrot 20 m east and 5 m up, then leave it hovering there",
        "1. foxtrot: fly 20 m east and 5 m up",
    ),
)

MAX_STEPS = 8


_STEP_RE = re.compile(r"^\s*(\d{1,2})[.)]\s+(\S.*)$")
# "alpha: hover", "bravo: keep up at 18 m": nothing to call for a drone the steps before put in the air
_NO_ACTION_RE = re.compile(
    r"^[\w ,]+:\s*(?:hover|stay|keep|remain|wait|leave|(?:on the )?(?:pad|ground)\b)", re.IGNORECASE
)
_OTHERWISE_RE = re.compile(r"^(?:otherwise|else|if not)\b", re.IGNORECASE)
# "the rest don't move", "the others stay on the ground", "charlie: does not fly": a step of drones that do
# nothing, with no condition before it (dev half with the 0.5B model: "the rest don't move" was asked for
# as a step, and the model flew charlie for it until the step limit)
_STAND_STILL_RE = re.compile(
    r"^(?!\s*(?:if|otherwise|else|when|unless)\b)(?!.*\d)(?:[^:]*:\s*)?"
    r"(?:(?:the )?(?:rest|others?|other \w+)\b.*\b(?:stay|remain|wait|keep|don'?t|do not)\b|"
    r"(?:[\w ,]*\b)?(?:don'?t|do(?:es)? not)\s+(?:move|fly|take off))",
    re.IGNORECASE,
)


def plan_request(fleet_ids: Sequence[str], request: str) -> str:
    """The user message asking for the steps of one request."""
    return f"Drones: {', '.join(fleet_ids)}\nRequest: {request}"


def plan_messages(fleet_ids: Sequence[str], request: str) -> list[Message]:
    """The whole conversation that asks for the steps (the same prefix every time: a server caches it)."""
    messages: list[Message] = [{"role": "system", "content": PLAN_SYSTEM_PROMPT}]
    for asked, steps in PLAN_EXAMPLES:
        messages.append({"role": "user", "content": f"Drones: {_EXAMPLE_FLEET}\nRequest: {asked}"})
        messages.append({"role": "assistant", "content": steps})
    messages.append({"role": "user", "content": plan_request(fleet_ids, request)})
    return messages


# "bravo: launch to 14 m" in the words of the tools (dev half: the 1.5B model called a "launch" tool)
# "charlie: hop to 6 m" too (dev half: "do a quick hop to 6 m" planned so, flown by a formation)
_LAUNCH_RE = re.compile(
    r"(?<!to )(?<!the )(?<!your )\b(?:launch|lift|hop)\b(?! (?:point|site|spot|pad))", re.I
)


# "charlie: take off to 20 m north at 12 m" is a move (which takes off first): said as one (dev half: the
# 1.5B model sent the takeoff 17 times for it, each held back as a repeat)
_TAKE_OFF_TO_RE = re.compile(r"\btake off(?: to)?\b(?=.*\b(?:north|south|east|west)\b)", re.I)


def _in_tool_words(step: str) -> str:
    """A step in the words of the tools that carry it out: "launch" is a takeoff, a takeoff with a compass
    direction is a flight."""
    return _TAKE_OFF_TO_RE.sub("fly", _LAUNCH_RE.sub("take off", step))


def split_steps(text: str | None, fleet_ids: Sequence[str], request: str = "") -> list[str]:
    """The numbered steps of a reply, one drone each (a formation excepted); none when a step names a drone
    of the examples that the fleet does not have (the model copied an example, so the steps would mislead),
    when there is only one, or more than MAX_STEPS."""
    lines: list[str] = []
    written = [m.group(2).strip() for line in (text or "").splitlines() if (m := _STEP_RE.match(line))]
    for step in (one for both in written for one in _landing_apart(both, fleet_ids)):
        if _STAND_STILL_RE.match(step):
            continue
        if _NO_ACTION_RE.match(step):
            if _height_for_a_bare_takeoff(step, lines):
                continue
            step = _hover_from_the_ground(step, lines, fleet_ids) or ""
        if step:
            lines.append(_in_tool_words(step))
    foreign = {d for d in _EXAMPLE_FLEET.split(", ") if d not in fleet_ids}
    if any(re.search(rf"\b{d}\b", s, re.IGNORECASE) for s in lines for d in foreign):
        return []
    asked = asked_drones(request, fleet_ids)
    lines = _within_the_formation(formation_for_drones(lines, request, fleet_ids), fleet_ids)
    steps = [one for line in lines for one in _per_drone(line, fleet_ids, asked)]
    if len(steps) == 1 and _call_of(steps[0], fleet_ids, request) is not None:
        return steps  # the one call the request is, read from its step (step_calls.py)
    if len(steps) < 2:
        # one step is the request itself, with only the planner's errors added (dev half: "side by side,
        # 15 m apart, at 20 m" for two drones became a step naming all three)
        return []
    if len(steps) > MAX_STEPS:
        # a plan cut short would call the request done before its end; without one the model reads it whole
        return []
    return steps


# "bravo: fly up to 10 m and land", "alpha: go 20 m east, then land it": two actions of one drone in one
# step (dev half with the 0.5B model: "charlie: fly back to your launch spot and land" was flown as neither)
_AND_LAND_RE = re.compile(
    r"^([^:]+:\s*)(\S.*?),?\s+(?:and|then)(?: then)?\s+"
    r"(land(?: (?:it|there|here))?|(?:set|put|bring) (?:it )?(?:back )?down)\s*\.?$",
    re.IGNORECASE,
)


def _landing_apart(step: str, fleet_ids: Sequence[str]) -> list[str]:
    """A step that acts and then lands, as two steps; one when its first action is the way home, which
    return_to_launch ends with a landing."""
    m = _AND_LAND_RE.match(step)
    if m is None:
        return [step]
    first = m.group(1) + m.group(2)
    said = call_of_step(first, fleet_ids)
    if said is not None and said[0] == "return_to_launch":
        return [first]
    return [first, m.group(1) + "land"]


_BARE_TAKEOFF_RE = re.compile(r"^([\w ,&]+):\s*take off\s*\.?$", re.IGNORECASE)


# the formation a request's words name; one only, or the steps are left as written
_REQUEST_SHAPES: tuple[tuple[str, re.Pattern[str]], ...] = (
    (
        "line",
        re.compile(r"\b(?:line(?:d)? up|in a (?:line|row)|side by side|abreast|line formation)\b", re.I),
    ),
    ("column", re.compile(r"\b(?:column|single file|one behind the other)\b", re.I)),
    ("wedge", re.compile(r"\b(?:wedge|v(?:-| )?(?:shape|formation))\b", re.I)),
    ("circle", re.compile(r"\b(?:circle|ring)\b", re.I)),
    ("grid", re.compile(r"\bgrid\b", re.I)),
)
_SHAPE_WORD_RE = re.compile(r"\b(?:line|row|column|wedge|v|circle|grid)\b", re.I)
_FLY_VERB_RE = re.compile(r"^(?:fly|move|go|get|spread(?: out)?|form(?: up)?)\s+", re.I)
_TAKEOFF_STEP_RE = re.compile(
    r"^([\w ,&]+):\s*take off(?: to)? (\d+(?:\.\d+)?)\s*(?:m|metres?|meters?)\s*\.?$", re.I
)


def formation_for_drones(lines: Sequence[str], request: str, fleet_ids: Sequence[str]) -> list[str]:
    """One formation step for the same formation words written once per drone ("alpha: fly 8 metres
    apart", "bravo: fly 8 metres apart"), with the request's shape when the words give none and the
    height of the takeoffs before it (the formation takes grounded drones off itself, so those steps go).
    Dev half with the 0.5B model: "line up alpha, bravo and charlie at 20 m, 8 metres apart" planned as a
    takeoff and "fly 8 metres apart" for each drone; the steps were dropped and no formation flew."""
    groups: dict[str, list[str]] = {}
    for line in lines:
        head = _HEAD_RE.match(line)
        drones = _drones_in(head.group(1), fleet_ids) if head else []
        if head and len(drones) == 1 and _FORMATION_WORDS_RE.search(head.group(2)):
            action = _FLY_VERB_RE.sub("", re.sub(r"\s+", " ", head.group(2)).strip().rstrip("."))
            if drones[0] not in groups.setdefault(action.lower(), []):
                groups[action.lower()].append(drones[0])
    formed = {a: ds for a, ds in groups.items() if len(ds) > 1}
    if len(formed) != 1:
        return list(lines)
    action, drones = next(iter(formed.items()))
    heights = {
        float(m.group(2))
        for line in lines
        if (m := _TAKEOFF_STEP_RE.match(line)) and set(_drones_in(m.group(1), fleet_ids)) <= set(drones)
    }
    if not _SHAPE_WORD_RE.search(action):
        shapes = [shape for shape, words in _REQUEST_SHAPES if words.search(request)]
        if len(shapes) != 1:
            return list(lines)
        action = f"{shapes[0]} formation, {action}"
    if not heights:
        # the request's altitude when the steps give none (dev half with the 0.5B model: "in a circle with
        # 10 m between neighbours, at 25 m" planned as "fly 10 m between neighbours" for each drone)
        heights = {float(a or b) for a, b in _ALTITUDE_RE.findall(request)}
    if not _METRES_AT_RE.search(action) and len(heights) == 1:
        action = f"{action}, at {heights.pop():g} m"
    step = f"{', '.join(drones)}: {action}"
    read: list[str] = []
    for line in lines:
        head = _HEAD_RE.match(line)
        mine = head is not None and set(_drones_in(head.group(1), fleet_ids)) <= set(drones)
        takeoff = _TAKEOFF_STEP_RE.match(line)
        if mine and (takeoff or (head and _FORMATION_WORDS_RE.search(head.group(2)))):
            if step not in read:
                read.append(step)
            continue
        read.append(line)
    return read


def _within_the_formation(lines: Sequence[str], fleet_ids: Sequence[str]) -> list[str]:
    """The steps without a move of one drone, before the formation step, that only repeats the formation's
    numbers: the formation flies each drone there itself (dev half with the 0.5B model: "alpha: fly 12 m,
    20 m east" before "alpha, bravo, charlie: line formation, 10 m apart, at 12 m, 20 m east" flew alpha
    alone, and the formation never)."""
    formations = [
        (i, head)
        for i, line in enumerate(lines)
        if (head := _HEAD_RE.match(line))
        and len(_drones_in(head.group(1), fleet_ids)) > 1
        and _FORMATION_WORDS_RE.search(head.group(2))
    ]
    if len(formations) != 1:
        return list(lines)
    at, formation = formations[0]
    drones = set(_drones_in(formation.group(1), fleet_ids))
    numbers = set(_METRES_RE.findall(formation.group(2)))

    def repeats(line: str) -> bool:
        head = _HEAD_RE.match(line)
        if head is None or _TAKEOFF_STEP_RE.match(line) or _read_of(line, fleet_ids) is not None:
            return False
        mine = _drones_in(head.group(1), fleet_ids)
        said = set(_METRES_RE.findall(head.group(2)))
        return len(mine) == 1 and mine[0] in drones and bool(said) and said <= numbers

    return [line for i, line in enumerate(lines) if i >= at or not repeats(line)]


_METRES_AT_RE = re.compile(r"\bat \d+(?:\.\d+)?\s*(?:m|metres?|meters?)\b", re.I)


def _height_for_a_bare_takeoff(step: str, before: list[str]) -> bool:
    """Give the height of a hover step ("bravo: stay up at 25 m") to the takeoff just before it that has
    none ("bravo: take off"), in place; whether it did (dev half with the 0.5B model: "take off and stay
    up at 25 m" planned so, the hover dropped as no action, and a bare takeoff is no plan)."""
    heights = _METRES_RE.findall(step)
    head = _HEAD_RE.match(step)
    bare = _BARE_TAKEOFF_RE.match(before[-1]) if before else None
    if len(heights) != 1 or head is None or bare is None or bare.group(1).strip() != head.group(1).strip():
        return False
    before[-1] = f"{bare.group(1).strip()}: take off to {heights[0]} m"
    return True


def _hover_from_the_ground(step: str, before: Sequence[str], fleet_ids: Sequence[str]) -> str | None:
    """A step of hovering at a height ("alpha: hover at 15 m") for drones no step before names: a takeoff
    to that height, since nothing put them in the air (dev half: "get alpha hovering at 15 m" was dropped
    as no action, and alpha flew to another drone's 6 m)."""
    heights = _METRES_RE.findall(step)
    head = _HEAD_RE.match(step)
    drones = _drones_in(step, fleet_ids)
    if len(heights) != 1 or head is None or not drones:
        return None
    if any(d in _drones_in(earlier, fleet_ids) for earlier in before for d in drones):
        return None
    return f"{head.group(1)}: take off to {heights[0]} m"


def steps_from_reply(text: str | None, fleet_ids: Sequence[str], request: str = "") -> list[str]:
    """The steps of a reply (split_steps) when they carry the request, else none."""
    steps = steps_as_meant(text, fleet_ids, request)
    return steps if steps and carries_the_request(steps, request) else []


def steps_as_meant(text: str | None, fleet_ids: Sequence[str], request: str) -> list[str]:
    """The steps of a reply (split_steps), a landing or a way home the request does not speak of read as
    it meant (home_for_landing, landing_for_home), an altitude the steps leave out given to the legs it is
    for (height_for_legs)."""
    steps = landing_for_home(home_for_landing(split_steps(text, fleet_ids, request), request), request)
    steps = conditions_of_the_request(_only_under_the_condition(steps, fleet_ids), request, fleet_ids)
    steps = landings_for_each(steps, request, fleet_ids)
    return height_for_legs(height_steps_into_legs(steps, request, fleet_ids), request, fleet_ids)


def _conditional(step: str) -> bool:
    return bool(
        readings.CONDITION_RE.match(step)
        or readings.PICK_RE.match(step)
        or readings.VERSUS_RE.match(step)
        or _OTHERWISE_RE.match(step)
    )


# the request says what is done when the condition does not hold, or that nothing is: the steps are left as
# written ("if under 30 %, don't launch it; otherwise put it up at 8 m")
_NEGATED_RE = re.compile(
    r"\b(?:don'?t|do not|never|unless)\b|\botherwise,?\s+(?:put|take|send|fly|launch|bring|move|go|lift)\b",
    re.IGNORECASE,
)


def conditions_of_the_request(steps: Sequence[str], request: str, fleet_ids: Sequence[str]) -> list[str]:
    """The steps of a request conditional on a battery reading, written as the condition's steps when the
    planner left the condition out: a choice of a drone ("the better charged one") is each candidate's read
    and the actions for "the one with more battery"; a threshold on one drone ("only if charlie is above 40
    percent") is its read and each of its actions under "if above 40 %". Dev half with the 0.5B model: "of
    bravo and charlie, launch the better charged one to 14 m" planned as a takeoff of each; "only if charlie
    is above 40 percent, send it up to 12 m and back down" with the takeoff first and the read after it."""
    pick = readings.request_pick(request)
    threshold = None if pick else readings.REQUEST_THRESHOLD_RE.search(request)
    if not steps or (pick is None and threshold is None) or _NEGATED_RE.search(request):
        return list(steps)
    acting = [s for s in steps if _read_of(s, fleet_ids) is None and not _OTHERWISE_RE.match(s)]
    if pick is not None:
        if any(_conditional(s) for s in steps):
            return list(steps)
        candidates = asked_drones(request, fleet_ids)
        actions: list[str] = []
        for step in acting:
            head = _HEAD_RE.match(step)
            if head is None or not set(_drones_in(head.group(1), fleet_ids)) <= set(candidates):
                return list(steps)
            if head.group(2).strip() not in actions:
                actions.append(head.group(2).strip())
        if len(candidates) < 2 or not actions:
            return list(steps)
        which = "less" if readings.fewer(pick) else "more"
        return [f"{d}: read battery" for d in candidates] + [
            f"the one with {which} battery: {a}" for a in actions
        ]
    assert threshold is not None
    named = _drones_in(request, fleet_ids)
    if len(named) != 1 or all(readings.CONDITION_RE.match(s) for s in acting):
        return list(steps)
    inner = [m.group(3).strip() if (m := readings.CONDITION_RE.match(s)) else s for s in acting]
    if any(_conditional(s) for s in inner):
        return list(steps)
    kept = [s for s in inner if _drones_in(s.split(":")[0], fleet_ids) == named]
    if not kept:
        return list(steps)
    condition = f"if {threshold.group(1).lower()} {threshold.group(2)} %"
    return [f"{named[0]}: read battery"] + [f"{condition}: {s}" for s in kept]


def _only_under_the_condition(steps: Sequence[str], fleet_ids: Sequence[str]) -> list[str]:
    """The steps without an unconditional step that a condition's step later does again (the same drone,
    the same metres): the request asks for it only if the condition holds. Dev half with the 0.5B model:
    "charlie goes up to 15 m, but only if its battery is over 60 %" planned as "charlie: fly 15 m",
    "charlie: read battery", "if over 60 %: charlie: take off to 15 m"; charlie flew at 30 %."""
    conditional = [
        (_drones_in(m.group(3), fleet_ids), set(_METRES_RE.findall(m.group(3))))
        for s in steps
        if (m := readings.CONDITION_RE.match(s))
    ]

    def again(step: str) -> bool:
        metres = set(_METRES_RE.findall(step))
        drones = _drones_in(step.split(":")[0], fleet_ids)
        return bool(metres) and any(drones == d and metres == m for d, m in conditional)

    return [s for s in steps if readings.CONDITION_RE.match(s) or not again(s)]


# "land them", "land both of them", "land the pair", "then both land": a landing for every drone named
_LAND_THEM_RE = re.compile(
    r"\bland (?:them|both|all|each|the (?:pair|two|three|lot))\b|\b(?:they|both|all) (?:\w+ )?land\b", re.I
)


def landings_for_each(steps: Sequence[str], request: str, fleet_ids: Sequence[str]) -> list[str]:
    """The steps with a landing for each drone the request names when it lands them all and the steps fly
    it but land only some, added after the last landing (dev half with the 0.5B model: "take alpha and
    charlie 40 m west ... and land them over there" planned with "alpha: land" only; charlie was left in
    the air)."""
    if not _LAND_THEM_RE.search(request):
        return list(steps)
    named = _drones_in(request, fleet_ids)
    landing = [i for i, s in enumerate(steps) if (c := call_of_step(s, fleet_ids)) and c[0] == "land"]
    if len(named) < 2 or not landing:
        return list(steps)
    landed = {d for i in landing for d in _drones_in(steps[i].split(":")[0], fleet_ids)}
    flown = {d for s in steps[: landing[-1]] for d in _drones_in(s.split(":")[0], fleet_ids)}
    action = steps[landing[-1]].split(":", 1)[1].strip()
    added = [f"{d}: {action}" for d in named if d in flown and d not in landed]
    return [*steps[: landing[-1] + 1], *added, *steps[landing[-1] + 1 :]]


# "at 15 m", "at 20 metres altitude", "10 m above the ground": an altitude the request names
_ALTITUDE_RE = re.compile(
    r"\bat (\d+(?:\.\d+)?)\s*(?:m|metres?|meters?)\b|"
    r"(\d+(?:\.\d+)?)\s*(?:m|metres?|meters?)\s+(?:above the ground|altitude|high)\b",
    re.IGNORECASE,
)


def _height_only(step: str, drone: str, altitudes: set[float], fleet_ids: Sequence[str]) -> float | None:
    """The altitude of the request a step for this drone asks for and nothing else ("charlie: fly 14 m",
    "bravo: fly 10 m above the ground"), or None."""
    heights = {float(n) for n in _METRES_RE.findall(step)}
    if _kind(step) != _HEIGHT_KIND or _drones_in(step, fleet_ids) != [drone] or len(heights) != 1:
        return None
    height = heights.pop()
    return height if height in altitudes and call_of_step(step, fleet_ids) is None else None


def height_steps_into_legs(steps: Sequence[str], request: str, fleet_ids: Sequence[str]) -> list[str]:
    """A leg flown without a height and, next to it, a step of that drone asking only for an altitude the
    request names, as one leg at that altitude ("charlie: fly 35 metres to the east", "charlie: fly 14 m"
    for "35 metres to the east, at 14 m"). Dev half with the 0.5B model: from the ground the leg without
    a height was the model's to write, and it never wrote it right."""
    altitudes = {float(a or b) for a, b in _ALTITUDE_RE.findall(request)}
    read = list(steps)
    i = 0
    while i < len(read):
        call = call_of_step(read[i], fleet_ids)
        drone = call[1].get("drone_id") if call is not None else None
        if call is not None and isinstance(drone, str) and leg_without_height(call):
            for j in (i + 1, i - 1):
                if 0 <= j < len(read) and (height := _height_only(read[j], drone, altitudes, fleet_ids)):
                    read[i] = f"{read[i].rstrip(' .')} at {height:g} m"
                    del read[j]
                    break
        i += 1
    return read


_BARE_HEIGHT_RE = re.compile(r",\s*(\d+(?:\.\d+)?)\s*(?:m|metres?|meters?)\s*\.?$", re.IGNORECASE)


def _bare_altitude(step: str, altitudes: set[float]) -> str:
    """A step ending in a bare height the request names as an altitude, with its "at" ("alpha: spread out,
    25 m to the east, 10 m" for "... both at 10 m": the 0.5B model's plan, dev half)."""
    m = _BARE_HEIGHT_RE.search(step)
    if m is None or float(m.group(1)) not in altitudes:
        return step
    return f"{step[: m.start()]} at {m.group(1)} m"


def height_for_legs(steps: Sequence[str], request: str, fleet_ids: Sequence[str]) -> list[str]:
    """The steps with an altitude of the request that none of them gives, given to each drone's first leg
    flown without a height ("bravo: fly 30 m north and 30 m west" for "... at 15 m"). Dev half with the
    0.5B model: the height was left out, the plan dropped for it, and the model flew without one; from the
    ground such a leg is refused."""
    altitudes = {float(a or b) for a, b in _ALTITUDE_RE.findall(request)}
    steps = [_bare_altitude(step, altitudes) for step in steps]
    said = {float(n) for n in _AMOUNT_RE.findall(" ".join(steps))}
    heights = altitudes - said
    if len(heights) != 1:
        return list(steps)
    height = heights.pop()
    given: set[str] = set()
    read: list[str] = []
    for step in steps:
        call = call_of_step(step, fleet_ids)
        drone = call[1].get("drone_id") if call is not None else None
        if call is not None and isinstance(drone, str) and leg_without_height(call) and drone not in given:
            given.add(drone)
            step = f"{step.rstrip(' .')} at {height:g} m"
        read.append(step)
    return read


_DIRECTION_RE = re.compile(r"\b(north|south|east|west)\b", re.IGNORECASE)
_AMOUNT_RE = re.compile(r"(\d+(?:\.\d+)?)\s*(?:m\b|metres?\b|meters?\b|%|percent\b)", re.IGNORECASE)
_HOME_RE = re.compile(
    r"\b(?:home|(?:launch|take-?off) (?:point|site|spot|pad)|"
    r"where (?:it|they|you) (?:took off|started|launched)|"
    r"start(?:ing)? point|the way (?:it|they|you) came|"
    r"(?:come|fly|head|go|bring \w+) back\b(?!\s+(?:down|up|\d|north|south|east|west)))",
    re.IGNORECASE,
)
_GO_HOME_RE = re.compile(r"\b(?:home|return\w*)\b", re.IGNORECASE)
_LANDING_RE = re.compile(r"\b(?:land\w*|down|touch\w*|ground)\b", re.IGNORECASE)
_LAND_STEP_RE = re.compile(r"\bland\b", re.IGNORECASE)
# a landing said outright ("land it", "put it down", "straight back down"), not a descent ("down to 5 m")
_ASKS_TO_LAND_RE = re.compile(
    r"\b(?:land(?:s|ing|ed)?|touch(?:es|ing)? down|(?:set|put|bring|come|straight|back)(?: \w+)? down|"
    rf"{BACK_ON_THE_GROUND})\b"
    r"(?!\s+(?:to|by|\d))",
    re.IGNORECASE,
)


def plan_gaps(steps: Sequence[str], request: str) -> list[str]:
    """What the steps leave out of the request, or add to it: each of its distances, heights and
    percentages, each compass direction, a way home exactly when it asks for one, and a landing only when
    it speaks of one. Steps with a gap would walk the model past the request, so they are no plan.
    Measured on the corpus's dev half with the 1.5B model: "then bring it home" planned as "charlie: land"
    (landed 28 m from home); "bring alpha back down but keep bravo up" got "alpha: return home" from the
    ground; "launch alpha ... and leave it hovering there" got a landing."""
    said = " ".join(steps)
    gaps: list[str] = []
    amounts = {float(n) for n in _AMOUNT_RE.findall(said)}
    left = [m.group(0) for m in _AMOUNT_RE.finditer(request) if float(m.group(1)) not in amounts]
    left += sorted(
        {d.lower() for d in _DIRECTION_RE.findall(request)} - {d.lower() for d in _DIRECTION_RE.findall(said)}
    )
    home_said = _GO_HOME_RE.search(said) or _HOME_RE.search(said)
    if _HOME_RE.search(request) and not home_said:
        left.append("the way home")
    if left:
        gaps.append(f"leave out {', '.join(left)}")
    if home_said and not _HOME_RE.search(request):
        gaps.append("add a flight home the request does not ask for")
    if _LAND_STEP_RE.search(said) and not _LANDING_RE.search(request):
        gaps.append("add a landing the request does not ask for")
    if _ASKS_TO_LAND_RE.search(request) and not (_LANDING_RE.search(said) or home_said):
        gaps.append("leave out the landing")
    return gaps


def home_for_landing(steps: Sequence[str], request: str) -> list[str]:
    """The steps with a landing the request does not speak of read as it meant: the way home when it asks
    for home ("then bring it home" planned as "charlie: land"), else left out ("send the fuller one 20 m
    north at 12 m" planned with a landing after it). Dev half: both twice in a row, so the plan was
    dropped and the model flew without one."""
    said = " ".join(steps)
    if not _LAND_STEP_RE.search(said):
        return list(steps)
    if _LANDING_RE.search(request):
        if _HOME_RE.search(request) and not (_GO_HOME_RE.search(said) or _HOME_RE.search(said)):
            # "send it home to land" planned as "bravo: land": a return home, which lands (dev half with
            # the 0.5B model: the plan had no way home, so it was dropped and the model flew without one)
            return [_LAND_STEP_RE.sub("return home", s) if _LAND_ONLY_RE.match(s) else s for s in steps]
        return list(steps)
    if not _HOME_RE.search(request):
        return [s for s in steps if not _LAND_ONLY_RE.match(s)]
    if _GO_HOME_RE.search(said):
        return list(steps)
    return [_LAND_STEP_RE.sub("return home", s) if _LAND_STEP_RE.search(s) else s for s in steps]


def landing_for_home(steps: Sequence[str], request: str) -> list[str]:
    """The steps with a way home the request does not ask for read as the landing it speaks of: dev half,
    "do a quick hop to 6 m and come straight back down" planned as "charlie: return home", so the plan was
    dropped for a flight home nobody asked for."""
    if _HOME_RE.search(request) or not _LANDING_RE.search(request):
        return list(steps)
    read: list[str] = []
    for step in steps:
        landing = _RETURN_HOME_RE.sub(r"\1land", step)
        if landing == step or landing not in read:  # a drone landed by a step already lands once
            read.append(landing)
    return read


_RETURN_HOME_RE = re.compile(r"^([^:]*:\s*)(?:return|go|fly|come)(?: back)? home\s*\.?$", re.IGNORECASE)
_LAND_ONLY_RE = re.compile(r"^[^:]*:\s*land\b(?:\s+(?:it|there|here|now))?\s*\.?$", re.IGNORECASE)


def carries_the_request(steps: Sequence[str], request: str) -> bool:
    """The steps leave nothing of the request out and add nothing to it (plan_gaps)."""
    return not plan_gaps(steps, request)


# A request that speaks of the whole fleet may mean drones it does not name ("each" and "the other" speak
# of drones it names: dev half, "of bravo and charlie, ... leave the other on the pad" had alpha read and
# flown)
_WHOLE_FLEET_RE = re.compile(r"\b(?:all|every\w*|fleet|whole|rest|others)\b", re.IGNORECASE)
# Words of drones placed together: such a step is one formation, not one move per drone (dev half: "alpha,
# charlie: side by side, 15 m apart, at 20 m" split per drone flew each 15 m east)
_FORMATION_WORDS_RE = re.compile(
    r"\b(?:formation|side by side|abreast|in a (?:row|line|column|circle)|line up|wedge|grid|circle|column|"
    r"apart|between)\b",
    re.IGNORECASE,
)
_HEAD_RE = re.compile(r"^([\w ,&]+):\s*(\S.*)$")


def _drones_in(text: str, fleet_ids: Sequence[str]) -> list[str]:
    """The fleet's drones a text names, in the order it names them."""
    found = [
        (m.start(), d) for d in fleet_ids if (m := re.search(rf"\b{re.escape(d)}\b", text, re.IGNORECASE))
    ]
    return [d for _, d in sorted(found)]


def asked_drones(request: str, fleet_ids: Sequence[str]) -> list[str]:
    """The drones a step may name: those the request names, or every drone when it names none or speaks
    of the whole fleet."""
    named = _drones_in(request, fleet_ids)
    return list(fleet_ids) if not named or _WHOLE_FLEET_RE.search(request) else named


def _per_drone(step: str, fleet_ids: Sequence[str], asked: Sequence[str]) -> list[str]:
    """A step for several drones as one step per drone, in the order written ("alpha, charlie: take off
    to 15 m"); a formation stays one step, for the drones asked. Drones the request does not name are
    left out. Measured on the corpus's dev half with the 1.5B model: a step for two drones counted as done
    after the call for the first, so the second never flew; "alpha 25 m east and bravo 25 m north, both at
    10 m" got a step flying charlie to 10 m."""
    m = _HEAD_RE.match(step)
    if m is None:
        return [step]
    head, action = m.group(1), m.group(2)
    written = _drones_in(head, fleet_ids)
    if not written:
        return [step]
    kept = [d for d in written if d in asked]
    if not kept and len(written) == 1 and len(asked) == 1:
        # the request speaks of one drone only: a step for another one is that drone's, its name copied
        # from the fleet list (dev half with the 0.5B model: "get charlie airborne" planned as "alpha:
        # hover at around 12 metres")
        kept = list(asked)
    if not kept:
        return []
    if _FORMATION_WORDS_RE.search(action):
        return [f"{', '.join(kept)}: {action}"] if len(kept) > 1 else []
    return [f"{d}: {action}" for d in kept]


def steps_text(steps: Sequence[str]) -> str:
    """The steps as the tool-calling conversation reads them, under the request."""
    lines = "\n".join(f"{i}. {s}" for i, s in enumerate(steps, 1))
    return f"Steps:\n{lines}\nCall one tool for each step, in this order."


_READ_BATTERY_TOOLS = frozenset({"get_battery", "fleet_status"})
_READ_POSITION_TOOLS = frozenset({"get_position", "fleet_status"})
_LAND_KIND_RE = re.compile(r"\bland\b", re.I)
_LAND_TOOLS = frozenset({"land", "return_to_launch"})
# The tools that carry out a step, by the words of the step (the examples' verbs); a step of none of these
# kinds is done by any call that succeeds on its drones.
_STEP_KINDS: tuple[tuple[re.Pattern[str], frozenset[str]], ...] = (
    (re.compile(r"^(?:tell|say|answer|report)\b", re.I), frozenset({ANSWER_TOOL})),
    (re.compile(r"\bformation\b", re.I), frozenset({"formation_goto"})),
    (re.compile(r"\b(?:battery|charge)\b", re.I), _READ_BATTERY_TOOLS),
    (re.compile(r"\b(?:position|status|where|how high)\b", re.I), _READ_POSITION_TOOLS),
    # "alpha: take off to 40 m west at 15 m" is a move, which takes off first from the ground (dev half:
    # done by the takeoff, the 40 m west was never flown)
    (re.compile(r"\b(?:north|south|east|west)\b", re.I), frozenset({"move_to_relative", "go_to_location"})),
    # "launch" and "lift" are written "take off" when the steps are read (_in_tool_words)
    (re.compile(r"\btake off\b", re.I), frozenset({"takeoff", "move_to_relative"})),
    # "bravo: fly 18 m", "climb to 30 m", "fly 10 m up": only a height, which a takeoff reaches from the
    # ground (dev half: "alpha to 10 m" planned as "alpha: fly 10 m up", and the takeoff that flew it did
    # not count, so the model was asked for the step again and flew alpha 10 m north)
    (
        re.compile(
            r"^[^:]*:\s*(?:fly|go|climb|move)\b"
            r"(?!.*\b(?:north|south|east|west|higher|lower|back|home|land)\b)",
            re.I,
        ),
        frozenset({"takeoff", "move_to_relative", "go_to_location"}),
    ),
    # "bravo: take up at 20 m", "alpha: up 10 m": a height and no verb of another kind (dev half with the
    # 0.5B model: the takeoff to 20 m did not carry "take up at 20 m", so it was sent again to the step limit)
    (
        re.compile(
            r"^[^:]*:(?!.*\b(?:north|south|east|west|higher|lower|back|home|land|down|apart|formation)\b)"
            r".*\d+(?:\.\d+)?\s*(?:m|metres?|meters?)\b",
            re.I,
        ),
        frozenset({"takeoff", "move_to_relative", "go_to_location"}),
    ),
    # the way home, by a return to launch or a flight back (dev half: "charlie: fly back to launch spot" was
    # not done by return_to_launch, so the model was asked for it again and flew 35 m on)
    (
        re.compile(r"\b(?:return|home|back to|launch (?:point|site|spot|pad)|the way \w+ came)\b", re.I),
        frozenset({"return_to_launch", "move_to_relative", "go_to_location"}),
    ),
    (_LAND_KIND_RE, _LAND_TOOLS),
    (
        re.compile(r"\b(?:fly|climb|move|go|up|down|higher|lower|north|south|east|west)\b", re.I),
        frozenset({"move_to_relative", "go_to_location"}),
    ),
)
_KNOWN_TOOLS = frozenset().union(*(tools for _, tools in _STEP_KINDS))


def _kind(step: str) -> frozenset[str] | None:
    """The tools that carry out a step of this wording; None for a step of no known kind."""
    return next((t for pattern, t in _STEP_KINDS if pattern.search(step)), None)


def step_done_by(step: str, call: ToolCallRecord, fleet_ids: Sequence[str]) -> bool:
    """Whether a call that succeeded carries out this step: a tool of the step's kind, on its drones."""
    tools = _kind(step)
    said = call_of_step(step, fleet_ids)
    if said is not None and tools is not None:
        tools = tools | {said[0]}  # the call the step's words say too ("charlie: set back down": land)
    if tools is not None and call.name not in tools and call.name in _KNOWN_TOOLS:
        return False  # a tool of another kind (takeoff for "fly 40 m west"); another server's tools count
    named = set(_drones_in(step, fleet_ids))
    return not named or bool(named & (drones_named(call.arguments) or set())) or call.name == "fleet_status"


@dataclass(frozen=True)
class Where:
    """Where a turn is in its plan: whether only the answer is left, the note for the step whose turn it
    is, and the call the host makes for that step (a reading it needs, or the call its words say), if any."""

    finished: bool
    note: str
    call: StepCall | None = None
    passed_over: tuple[str, ...] = ()  # drones a choice between drones did not pick, for this step


_HEIGHT_KIND = frozenset({"takeoff", "move_to_relative", "go_to_location"})
_METRES_RE = re.compile(r"(\d+(?:\.\d+)?)\s*(?:m\b|metres?\b|meters?\b)", re.IGNORECASE)


def _height_flown(step: str, last: ToolCallRecord, fleet_ids: Sequence[str], request: str = "") -> bool:
    """A step that asks only for a height (an altitude or a climb) that the move before it, a leg flown
    with that height, already flew its drone to; or the takeoff before it, when the request names no climb
    of that size (dev half with the 0.5B model: "both up to 18 m" planned as "bravo: take off to 18 m",
    "bravo: fly 18 m up")."""
    if _kind(step) != _HEIGHT_KIND or not step_done_by(step, last, fleet_ids):
        return False
    args = last.arguments or {}
    if last.name == "takeoff":
        heights = {float(m) for m in _METRES_RE.findall(step)}
        alt = args.get("alt_m")
        return (
            len(heights) == 1
            and isinstance(alt, int | float)
            and float(alt) in heights
            and not {float(alt), -float(alt)} & request_climbs(request)
        )
    if last.name != "move_to_relative":
        return False
    if not any(
        isinstance(args.get(a), int | float) and args.get(a)
        for a in ("north_m", "east_m", "south_m", "west_m")
    ):
        return False  # not a leg: the step may be a climb after it
    heights = {float(m) for m in _METRES_RE.findall(step)}
    flown = {float(v) for a in ("alt_m", "up_m") if isinstance(v := args.get(a), int | float) and v}
    return len(heights) == 1 and bool(heights & flown)


def _battery_read(drones: Sequence[str]) -> StepCall:
    return ("get_battery", {"drone_id": drones[0]}) if len(drones) == 1 else ("fleet_status", {})


def _call_of(step: str, fleet_ids: Sequence[str], request: str) -> StepCall | None:
    """The call the host makes for a step: a reading it needs, or the one call its words say exactly
    (step_calls.py); None when the model is to write it. A climb or descent the request does not name is
    not made (dev half with the 0.5B model: "climb to thirty metres" planned as "alpha: climb 30 m", after
    a takeoff to 30 m): the model is asked, and the request's checks read its call."""
    read = _read_of(step, fleet_ids)
    if read is not None:
        return read
    call = call_of_step(step, fleet_ids)
    if call is None:
        return None
    up = call[1].get("up_m")
    if isinstance(up, float) and up not in request_climbs(request):
        return None
    return call


# a step that acts or gives metres is no reading, whatever else it says ("line up ..., right where they
# are" is no position read: dev half, read so as a one-step plan, the formation was never flown)
_NO_READ_RE = re.compile(
    r"\b(?:fly|go|move|take off|land|climb|descend|line|formation|apart|hover|return|head|up|down)\b|"
    r"\d+(?:\.\d+)?\s*(?:m|metres?|meters?)\b",
    re.IGNORECASE,
)


def _read_of(step: str, fleet_ids: Sequence[str]) -> StepCall | None:
    """The read-only call a step of a reading kind is (battery, position), for the drones it names."""
    if _NO_READ_RE.search(step.split(":", 1)[-1]):
        return None
    kind = _kind(step)
    drones = _drones_in(step.split(":")[0] if ":" in step else step, fleet_ids) or _drones_in(step, fleet_ids)
    if kind == _READ_BATTERY_TOOLS:
        return _battery_read(drones)
    if kind == _READ_POSITION_TOOLS:
        return ("get_position", {"drone_id": drones[0]}) if len(drones) == 1 else ("fleet_status", {})
    return None


@dataclass
class Plan:
    """The request's steps and where the turn is in them, judged from the calls that succeeded."""

    steps: list[str]
    fleet_ids: list[str] = field(default_factory=list)
    candidates: list[str] = field(default_factory=list)  # the drones a "the one with more battery" is among
    request: str = ""  # the request the steps were written for (a climb the host makes must be in it)

    def prompt(
        self, request: str, calls: Sequence[ToolCallRecord], roster: Roster | None, lead: str = ""
    ) -> str:
        """The turn so far as one user message: the fleet now, the request, its steps, the calls that ran
        (written as the model writes a call, with what came of each), ``lead`` and the step whose turn
        it is."""
        ran = [c for c in calls if c.status in ("ok", "error") and c.name != ANSWER_TOOL]
        lines = [
            f"- {json.dumps({'name': c.name, 'arguments': c.arguments})} -> "
            f"{'' if c.ok else 'failed: '}{first_line(c.text) or c.summary}"
            for c in ran
        ]
        parts = [roster.text()] if roster is not None else []
        parts += [request, steps_text(self.steps)]
        if lines:
            parts.append("Done so far:\n" + "\n".join(lines))
        parts.append(f"{lead} {self.next_note(calls)}".strip())
        return "\n\n".join(parts)

    def next_note(self, calls: Sequence[ToolCallRecord]) -> str:
        """What the model is told after a call or an empty reply: the step whose turn it is. A condition
        on a battery reading is read here (the 1.5B model called 45 % "below 40 %"), and the branch it
        does not take is passed over."""
        return self.where(calls).note

    def finished(self, calls: Sequence[ToolCallRecord]) -> bool:
        """Every step is done, or a condition did not hold: only the answer is left."""
        return self.where(calls).finished

    def call_due(self, calls: Sequence[ToolCallRecord]) -> StepCall | None:
        """The call the host makes for the step whose turn it is (a reading it needs, or the call its words
        say exactly), or None."""
        return self.where(calls).call

    def _read_first(self, i: int, step: str, unread: Sequence[str]) -> Where:
        """Step ``i`` waits for the battery of these drones: the host reads the first (``Where.call``)."""
        return Where(
            False,
            f"Now step {i + 1} of {len(self.steps)}: {step}. Read the battery of {', '.join(unread)} first: "
            "reply with the get_battery call.",
            _battery_read(unread[:1]),
        )

    def where(self, calls: Sequence[ToolCallRecord]) -> Where:
        """Where the turn is in the steps, judged from the calls so far."""
        # a call held back as a repeat counts for the step whose turn it is: what it did still holds
        # (nothing has acted on its drone since), and the model sent it as that step (dev half: "keep
        # bravo up" planned as "bravo: fly up"; bravo already was, and the move that put it there was sent
        # again twelve times, to the step limit)
        # a call refused because the drone already is as it asks ("already on the ground") did its step
        done = [c for c in calls if (c.ok or c.status == "repeat" or already_so(c)) and c.name != ANSWER_TOOL]
        i, used, held = 0, 0, False
        passed_over: tuple[str, ...] = ()
        while i < len(self.steps):
            step = self.steps[i]
            versus = readings.VERSUS_RE.match(step)
            if versus and {versus.group(1).lower(), versus.group(3).lower()} <= set(self.fleet_ids):
                first, relation, second = (
                    versus.group(1).lower(),
                    versus.group(2).lower(),
                    versus.group(3).lower(),
                )
                levels = readings.battery_readings(done, self.fleet_ids)
                unread = [d for d in (first, second) if d not in levels]
                if unread:
                    return self._read_first(i, step, unread)
                held = readings.first_leads(relation, levels[first], levels[second])
                if not held:
                    i += 1  # the branch not taken; an "otherwise" step after it is the one
                    continue
                step = versus.group(4).strip()
            cond = None if versus else readings.CONDITION_RE.match(step)
            if cond:
                reading = readings.last_reading(done)
                if reading is None:
                    named = _drones_in(step, self.fleet_ids) or self.candidates
                    return Where(
                        False,
                        f"Now step {i + 1} of {len(self.steps)}: {step}. Read the battery first: reply with "
                        "the get_battery call.",
                        _battery_read(named[:1]) if len(named) == 1 else None,
                    )
                drone, percent = reading
                relation, threshold = cond.group(1).lower(), float(cond.group(2))
                if not readings.holds(relation, percent, threshold):
                    fact = f"{drone} battery {percent:g} % is not {relation} {threshold:g} %"
                    return Where(
                        True,
                        f"The condition does not hold ({fact}), so nothing is to be flown. Reply with the "
                        "answer_user call saying so, with the reading.",
                    )
                step = cond.group(3).strip()
            elif _OTHERWISE_RE.match(step):
                if held or not i or not readings.VERSUS_RE.match(self.steps[i - 1]):
                    i += 1  # the branch not taken: the condition before it held
                    continue
                step = re.sub(r"^(?:otherwise|else|if not)\b[\s,:]*", "", step, flags=re.IGNORECASE)
            pick = readings.PICK_RE.match(step)
            if pick:
                candidates = self.candidates or self.fleet_ids
                levels = readings.battery_readings(done, self.fleet_ids)
                chosen, unread = readings.pick(pick.group(1), candidates, levels)
                if chosen is None:
                    return self._read_first(i, step, unread)
                step = f"{chosen}: {pick.group(2).strip()}"
                passed_over = tuple(d for d in candidates if d != chosen)
                said = ", ".join(f"{d} {levels[d]:g} %" for d in candidates)
                most = "least" if readings.fewer(pick.group(1)) else "most"
            answer_only = _kind(step) == frozenset({ANSWER_TOOL})
            if _kind(step) == _LAND_TOOLS and used and done[used - 1].name == "return_to_launch":
                # a return to launch lands: the landing after "return home" is done by it (dev half:
                # the land sent after it failed, "already on the ground", and was answered as an error)
                if step_done_by(step, done[used - 1], self.fleet_ids):
                    i += 1
                    continue
            if used and _height_flown(step, done[used - 1], self.fleet_ids, self.request):
                # "bravo: fly 10 m above the ground" after a move that flew bravo at 10 m (dev half: the
                # planner split "50 m east, 10 m above the ground" in two, and the height was asked again)
                i += 1
                continue
            while not answer_only and used < len(done) and not step_done_by(step, done[used], self.fleet_ids):
                used += 1
            if answer_only or used >= len(done):
                lead = f" (the battery is {cond.group(1).lower()} {cond.group(2)} %)" if cond else ""
                if pick:
                    lead = f" ({chosen} has the {most} battery: {said})"
                where = f"Now step {i + 1} of {len(self.steps)}{lead}"
                if answer_only:
                    # only the answer is left (dev half: "if below 30 %: tell me the number" was answered
                    # with get_battery, sent again 19 times)
                    return Where(
                        True, f"{where}: {step}. Reply with the answer_user call, with the numbers read."
                    )
                return Where(
                    False,
                    f"{where}: {step}. Reply with only the tool call for it.",
                    _call_of(step, self.fleet_ids, self.request),
                    passed_over,
                )
            used += 1
            i += 1
        return Where(True, "Every step is done. Reply with the answer_user call saying what was done.")


async def plan_steps(chat: ChatModel, fleet_ids: Sequence[str], request: str, usage: Usage) -> list[str]:
    """Ask the model for the request's steps (no tools offered); an empty list when it gives none. Steps
    with a gap (plan_gaps) are sent back once, naming it; steps with a gap again are no plan."""
    messages = plan_messages(fleet_ids, request)
    reply = await chat.ask(messages, [], {}, usage)
    steps = steps_as_meant(reply.content, fleet_ids, request)
    gaps = plan_gaps(steps, request) if steps else []
    if not gaps:
        return steps
    messages += [
        {"role": "assistant", "content": reply.content or ""},
        {"role": "user", "content": gaps_note(gaps)},
    ]
    again = await chat.ask(messages, [], {}, usage)
    return steps_from_reply(again.content, fleet_ids, request)


def gaps_note(gaps: Sequence[str]) -> str:
    """What the planner is told about steps with a gap."""
    return (
        f"Those steps {'; '.join(gaps)}. Write the steps again: every number and direction of the request, "
        "and nothing it does not ask for."
    )
