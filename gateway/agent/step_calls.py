"""The call a plan step is, when the step's words say it exactly: the host makes it instead of asking.

A small model's plan step ("alpha: take off to 12 m", "bravo: fly 30 m south at 10 m", "charlie: land")
already holds every argument of the call that carries it out; what goes wrong is the second writing, as
a JSON tool call (measured with the 1.5B model on the corpus's dev half: "fly over 20 m north while
climbing another 6 m" planned right, then called with alt_m=6; the 0.5B model writes ``drone_ids`` lists
into one-drone tools). So a step in one of the few shapes below is read here into its call, and the host
sends it through the same checks as a call the model wrote (host.py ``_plan_calls``). A step in any
other words (a condition, a choice, "fly 10 m above the ground") returns None and the model is asked.

Nothing is guessed: every word of the step must be read, or it is not a call.
"""

from __future__ import annotations

import re
from collections.abc import Sequence

from gateway.agent.repair import DIRECTION_AXES, in_metres

StepCall = tuple[str, dict[str, object]]  # tool name, arguments

_N = r"(\d+(?:\.\d+)?)"
_M = r"\s*(?:m|metres?|meters?)\b"
_HEAD_RE = re.compile(r"^\s*([\w ,&]+?)\s*:\s*(\S.*?)\s*\.?\s*$")
_JOINERS_RE = re.compile(r"^(?:,|and|&|\s)+$", re.IGNORECASE)

# "take off to 12 m and hover there", "take off and stay up at 25 m" (the 0.5B model's plan, dev half)
_STAY = r"(?:hover|stay|hold|wait|remain)(?: up)?(?: there)?"
_TAKEOFF_RE = re.compile(
    rf"^take ?off(?:(?: to)? {_N}{_M}(?: and {_STAY})?| and {_STAY} at {_N}{_M})$", re.IGNORECASE
)
_LAND_RE = re.compile(
    r"^(?:land|(?:set|put|bring|come|touch)(?: it)?(?: straight)?(?: back)? down)(?: (?:it|there|here|now|"
    r"on the spot|again))?$",
    re.IGNORECASE,
)
# the way home, which return_to_launch flies and ends with a landing ("and land there" is part of it): dev
# half with the 0.5B model, "return to your take-off point and land there", "come back the way you came"
_HOME_RE = re.compile(
    r"^(?:return (?:to launch|home)|(?:fly|go|come|head|return)(?: back)? "
    r"(?:home|the way (?:it|you|they) came|"
    r"to (?:the |your |its |their )?(?:launch|home|(?:launch|take-?off) (?:point|spot|site|pad)|"
    r"start(?:ing)? point|where (?:it|you|they) (?:took off|started))))"
    r"(?:,? (?:and|then)(?: then)? land(?: (?:it|there))?)?$",
    re.IGNORECASE,
)
_MOVE_VERB_RE = re.compile(
    r"^(?:(?:fly|go|come|move|head|shift|nudge|travel|spread)\s+)?(?:(?:over|out|on)\b\s*)?", re.IGNORECASE
)
# "rise to 12 m", "drop down to 10 m there", "climb to 20 m": an altitude and nothing else, which
# move_to_relative flies both from the ground (it takes off first) and in the air (dev half with the 0.5B
# model: "bravo: rise to 12 m" was called with alt_m=120, "charlie: drop down to 10 m there" with down_m)
_TO_HEIGHT_RE = re.compile(
    rf"^(?:climb|rise|raise|ascend|descend|drop|sink|up|down|"
    rf"(?:go|come|get|move|fly|head|drop|bring it|take it)(?: back)? (?:up|down))(?: back)? to {_N}{_M}"
    r"(?: (?:there|here|altitude|above (?:the )?(?:ground|home)))?(?: (?:first|now|then))?$",
    re.IGNORECASE,
)
# "20 m west", "20 m back east" (the way back, said as its direction), "up 10 m" (dev half, 0.5B's plan)
_LEG_RE = re.compile(
    rf"{_N}{_M}\s+(?:back\s+|to the\s+)?(north|south|east|west|higher|up|lower|down)\b|"
    rf"\b(north|south|east|west|up|down)\s+{_N}{_M}",
    re.IGNORECASE,
)
_CLIMB_RE = re.compile(
    rf"\b(climb(?:ing)?|descend(?:ing)?)\s+(?:(?:another|a further|an extra)\s+)?{_N}{_M}", re.IGNORECASE
)
_AT_RE = re.compile(rf"\bat {_N}{_M}(?:\s+(?:altitude|high|up))?", re.IGNORECASE)
_MOVE_GLUE_RE = re.compile(r"^(?:,|and|while|then\s+climb|\s)*$", re.IGNORECASE)

_SHAPES = {"line": "line", "row": "line", "column": "column", "wedge": "wedge", "v": "wedge"}
_SHAPES |= {"circle": "circle", "grid": "grid", "side by side": "line", "abreast": "line"}
_SHAPE_RE = re.compile(
    r"^(?:(?:in|into) an? )?(line|row|column|wedge|v|circle|grid|side by side|abreast)"
    r"(?:[ -](?:formation|shape))?$",
    re.IGNORECASE,
)
# "10 m apart", "10 m between neighbours" (dev half, the 0.5B model's plan)
_APART_RE = re.compile(
    rf"^(?:(?:fly|spread(?: out)?)\s+)?{_N}{_M} (?:apart|between (?:neighbou?rs|drones|them|each other))$",
    re.IGNORECASE,
)
_FORMATION_AT_RE = re.compile(rf"^at {_N}{_M}(?: altitude)?$", re.IGNORECASE)
_OFFSET_RE = re.compile(
    rf"^{_N}{_M}\s+(?:to the )?(north|south|east|west)(?: of (?:where they are|here|them))?$", re.IGNORECASE
)


def call_of_step(step: str, fleet_ids: Sequence[str]) -> StepCall | None:
    """The one call this step says exactly, or None (the model is asked for it)."""
    head = _HEAD_RE.match(in_metres(step))
    if head is None:
        return None
    drones = _drones_of_head(head.group(1), fleet_ids)
    action = re.sub(r"\s+", " ", head.group(2)).strip()
    if not drones:
        return None
    if len(drones) > 1:
        return _formation(drones, action)
    drone = drones[0]
    if m := _TAKEOFF_RE.match(action):
        return ("takeoff", {"drone_id": drone, "alt_m": float(m.group(1) or m.group(2))})
    if _LAND_RE.match(action):
        return ("land", {"drone_id": drone})
    if _HOME_RE.match(action):
        return ("return_to_launch", {"drone_id": drone})
    if m := _TO_HEIGHT_RE.match(action):
        return (
            "move_to_relative",
            {"drone_id": drone, "north_m": 0.0, "east_m": 0.0, "alt_m": float(m.group(1))},
        )
    move = _move(action)
    return ("move_to_relative", {"drone_id": drone, **move}) if move is not None else None


def _drones_of_head(head: str, fleet_ids: Sequence[str]) -> list[str]:
    """The drones a step's head names, when it names nothing else ("alpha, bravo and charlie")."""
    known = {d.lower(): d for d in fleet_ids}
    drones: list[str] = []
    rest = head
    for word in re.findall(r"[\w-]+", head):
        if word.lower() in known:
            drones.append(known[word.lower()])
            rest = rest.replace(word, " ", 1)
    if not _JOINERS_RE.match(rest or " ") or len(set(drones)) != len(drones):
        return []
    return drones


def _move(action: str) -> dict[str, object] | None:
    """``fly 30 m south and 5 m up at 10 m``, ``climb another 6 m``: a relative move, every word read."""
    text = _MOVE_VERB_RE.sub("", action, count=1)
    args: dict[str, float] = {}
    spans: list[tuple[int, int]] = []

    def put(axis: str, value: float) -> bool:
        if axis in args:
            return False  # the same axis twice: two moves, not one
        args[axis] = value
        return True

    for m in _LEG_RE.finditer(text):
        direction, metres = (m.group(2), m.group(1)) if m.group(2) else (m.group(3), m.group(4))
        axis, sign = DIRECTION_AXES[direction.lower()]
        if not put(axis, sign * float(metres)):
            return None
        spans.append(m.span())
    for m in _CLIMB_RE.finditer(text):
        if any(s <= m.start(2) < e for s, e in spans):
            continue  # "climb 10 m higher": read with its direction already
        sign = 1 if m.group(1).lower().startswith("climb") else -1
        if not put("up_m", sign * float(m.group(2))):
            return None
        spans.append(m.span())
    for m in _AT_RE.finditer(text):
        if not put("alt_m", float(m.group(1))):
            return None
        spans.append(m.span())
    if not args or ("up_m" in args and "alt_m" in args):
        return None
    left = text
    for start, end in sorted(spans, reverse=True):
        left = left[:start] + " " + left[end:]
    if "up_m" in args:
        left = re.sub(r"\b(?:climb|descend)\b", " ", left, flags=re.IGNORECASE)
    if not _MOVE_GLUE_RE.match(left):
        return None  # a word not read: the step may mean more than these numbers
    moved = {"north_m": args.get("north_m", 0.0), "east_m": args.get("east_m", 0.0)}
    if not (moved["north_m"] or moved["east_m"] or args.get("up_m")):
        return None  # only an altitude: a takeoff or a climb to it, which the model tells apart
    return {**moved, **{k: v for k, v in args.items() if k in ("up_m", "alt_m")}}


def _formation(drones: list[str], action: str) -> StepCall | None:
    """``line formation, 8 m apart, at 20 m, 25 m south``: every part read, or no call."""
    args: dict[str, object] = {"drone_ids": drones}
    for part in (p.strip() for p in re.split(r",|\band\b", action) if p.strip()):
        if (m := _SHAPE_RE.match(part)) and "formation" not in args:
            args["formation"] = _SHAPES[m.group(1).lower()]
        elif (m := _APART_RE.match(part)) and "spacing_m" not in args:
            args["spacing_m"] = float(m.group(1))
        elif (m := _FORMATION_AT_RE.match(part)) and "alt_m" not in args:
            args["alt_m"] = float(m.group(1))
        elif m := _OFFSET_RE.match(part):
            axis, sign = DIRECTION_AXES[m.group(2).lower()]
            if axis in args:
                return None
            args[axis] = sign * float(m.group(1))
        else:
            return None
    if not {"formation", "spacing_m", "alt_m"} <= set(args):
        return None
    return ("formation_goto", args)


def leg_without_height(call: StepCall) -> bool:
    """A relative move with neither ``alt_m`` nor ``up_m``: from the ground the gateway refuses it (it must
    know how high to fly), so the host does not make it for a drone on the ground. Seen with the 0.5B
    model's plan on the dev half ("bravo: fly 50 m east", then "bravo: fly 10 m above the ground") and on
    the test half with the 1.5B model, where the model, asked after the refusal, sent alt_m=0."""
    name, args = call
    return name == "move_to_relative" and "alt_m" not in args and "up_m" not in args
