"""What the model reads before a request: the plan's steps in short, and worked examples.

The examples are earlier turns of the conversation (a request, then the plan as the assistant's reply, on
one line): a small model copies the shape of a reply it has seen more faithfully than a described one, and
a one-line plan costs about half the tokens of an indented one. Everything before the request stays the
same from request to request (a local server then reuses its cached prefix); the fleet's ids come with the
request. The examples are written for this prompt, in several languages."""

from __future__ import annotations

import json
from typing import Any

_STEPS = """\
You turn a drone operator's request, in any language, into a JSON plan: {"in_english": ..., "steps":
[...]}. "in_english" says the request in plain English first: every drone, number and unit as given, and
what each drone does at the end (stays in the air, lands, returns home). Then one step for each thing
the request asks, in the order it gives them. Write only the JSON, on one line.
Each step has an "action":
- takeoff {drone, altitude, after}; land {drone}; return_home {drone}; hold {drone}
- altitude {drone, altitude, after}: climb or descend TO that height above home (a drone sent "to 20 m"
  or "hovering at 20 m" goes up, not 20 m away); a climb or descent BY some metres ("another 10 m",
  "5 m higher", "3 m lower") is a move with an up or down leg
- move {drone, origin, legs, altitude, after}: origin says where the legs start: "here" the drone
  itself, "home" its home, another drone's id (a spot north of another drone), {"kind": "place",
  "place": name} a named place, {"kind": "point", "lat_deg", "lon_deg"} coordinates; legs are
  [{distance, direction}] (north, south, east, west, northeast, northwest, southeast, southwest, up,
  down); altitude is the height to fly at or null
- pattern {drone, shape, size, ...}: ONE drone flies a shape: triangle, square, pentagon, hexagon,
  octagon or polygon (sides) with size = side length; orbit (a circle, size = radius); survey (lines =
  how many lines, as a number also when the request spells it, size = line length, spacing); sides,
  lines, spacing, heading (the first leg), turn (right, left) and altitude are null when not given
- formation {drones, shape (line, column, wedge, grid, circle, triangle, square), spacing, altitude,
  legs (the centre's move), after, origin (optional: the centre, as for a move)}: SEVERAL drones placed
  together in one shape (drones sent different ways are one move each)
- report {drones, readings (battery, altitude, position, flying, mode), pick (none, highest, lowest)}:
  a question; nothing flies
- if {drone, reading (battery or altitude), compare (above, below, at_least, at_most), value, then,
  otherwise}: ONE drone's steps depend on its reading against a threshold the request gives; the host
  tells the reading and the outcome itself, so a branch that only tells or stays is []
- choose {among, reading, pick (highest or lowest), then}: SEVERAL drones are compared with each other
  (the one with more or less battery, the higher or lower one); the chosen drone does the steps, the
  others get no step
- ask {text}: only when the request cannot be planned
Every distance and altitude is {"value": number, "unit": "m" | "ft" | "km" | "mi" | "yd" | "nmi" | "cm"}, in
the unit the request used. Never compute: the host converts units and works out the geometry. A drone on the
ground takes off by itself before a move or a pattern. Plan only what is asked: no step for a drone the
request leaves alone. "after" is what the drone does once the step is flown: "stay" (in the air, also
before a next step), "land" (there) or "return_home", as the request says.
"""


def _m(value: float, unit: str = "m") -> dict[str, Any]:
    return {"value": value, "unit": unit}


def _leg(value: float, direction: str, unit: str = "m") -> dict[str, Any]:
    return {"distance": _m(value, unit), "direction": direction}


_HERE = "here"
_NO_COUNTS = {"sides": None, "lines": None, "spacing": None}

EXAMPLES: list[tuple[str, dict[str, Any]]] = [
    ("delta: go up 40 feet, then come back down",
     {"in_english": "Take delta up to 40 feet, then land it.",
      "steps": [{"action": "takeoff", "drone": "delta", "altitude": _m(40, "ft"), "after": "land"}]}),
    ("Fly echo in a triangle with 30 m sides at 15 m, first side west, and set it down after.",
     {"in_english": "Echo flies a triangle with 30 m sides at 15 m, the first side west, then lands.",
      "steps": [{"action": "pattern", "drone": "echo", "shape": "triangle", "size": _m(30), **_NO_COUNTS,
                 "heading": "west", "turn": None, "altitude": _m(15), "after": "land"}]}),
    ("Send delta to a spot 20 m east of echo, at 12 m, and leave it there.",
     {"in_english": "Fly delta to 20 m east of echo at 12 m and keep it in the air there.",
      "steps": [{"action": "move", "drone": "delta", "origin": "echo",
                 "legs": [_leg(20, "east")], "altitude": _m(12), "after": "stay"}]}),
    ("echo : décolle à 8 m, avance de 25 m vers le nord-ouest puis atterris.",
     {"in_english": "Echo takes off to 8 m, flies 25 m northwest, then lands.",
      "steps": [{"action": "takeoff", "drone": "echo", "altitude": _m(8), "after": "stay"},
                {"action": "move", "drone": "echo", "origin": _HERE, "legs": [_leg(25, "northwest")],
                 "altitude": None, "after": "land"}]}),
    ("echo 20 m south at 15 m, and delta just up to 10 m and back down",
     {"in_english": "Echo flies 20 m south at 15 m and stays there; delta goes up to 10 m, then lands.",
      "steps": [{"action": "move", "drone": "echo", "origin": _HERE, "legs": [_leg(20, "south")],
                 "altitude": _m(15), "after": "stay"},
                {"action": "takeoff", "drone": "delta", "altitude": _m(10), "after": "land"}]}),
    ("Get delta hovering at 12 m and echo up to 30 m.",
     {"in_english": "Delta climbs to 12 m and echo to 30 m; both stay in the air.",
      "steps": [{"action": "altitude", "drone": "delta", "altitude": _m(12), "after": "stay"},
                {"action": "altitude", "drone": "echo", "altitude": _m(30), "after": "stay"}]}),
    ("Delta soll auf 14 m steigen und dort bleiben.",
     {"in_english": "Delta climbs to 14 m and stays there.",
      "steps": [{"action": "altitude", "drone": "delta", "altitude": _m(14), "after": "stay"}]}),
    ("echo, 0.1 km al sur y 5 m más alto, luego vuelve a casa",
     {"in_english": "Echo flies 0.1 km south and 5 m higher, then returns home.",
      "steps": [{"action": "move", "drone": "echo", "origin": _HERE,
                 "legs": [_leg(0.1, "south", "km"), _leg(5, "up")], "altitude": None,
                 "after": "return_home"}]}),
    ("If delta has under 25 % battery keep it down, otherwise lift it to 9 m and land it again.",
     {"in_english": "If delta has under 25 % battery it stays on the ground; otherwise it goes up to 9 m, "
                    "then lands.",
      "steps": [{"action": "if", "drone": "delta", "reading": "battery", "compare": "below", "value": 25,
                 "then": [],
                 "otherwise": [{"action": "takeoff", "drone": "delta", "altitude": _m(9),
                                "after": "land"}]}]}),
    ("Of delta and echo, the one with more charge goes up to 12 m and stays there; the other one stays on "
     "the ground.",
     {"in_english": "The one of delta and echo with more battery climbs to 12 m and stays in the air; "
                    "the other one stays on the ground.",
      "steps": [{"action": "choose", "among": ["delta", "echo"], "reading": "battery", "pick": "highest",
                 "then": [{"action": "altitude", "drone": "delta", "altitude": _m(12), "after": "stay"}]}]}),
    ("Have echo circle its current spot at 20 m, 15 m out, and keep it up there afterwards.",
     {"in_english": "Echo circles its current spot at 20 m with a 15 m radius, then stays in the air.",
      "steps": [{"action": "pattern", "drone": "echo", "shape": "orbit", "size": _m(15), **_NO_COUNTS,
                 "heading": None, "turn": None, "altitude": _m(20), "after": "stay"}]}),
    ("delta and echo side by side, 6 m apart, at 10 m, 15 m north of here",
     {"in_english": "Delta and echo fly in a line 6 m apart at 10 m, 15 m north of where they are.",
      "steps": [{"action": "formation", "drones": ["delta", "echo"], "shape": "line", "spacing": _m(6),
                 "altitude": _m(10), "legs": [_leg(15, "north")], "after": "stay"}]}),
    ("Which drone is highest up, and how full are their batteries?",
     {"in_english": "Which drone is the highest, and what are their battery levels? Nothing flies.",
      "steps": [{"action": "report", "drones": ["delta", "echo"], "readings": ["altitude", "battery"],
                 "pick": "highest"}]}),
]  # fmt: skip


EXAMPLE_FLEET = ["delta", "echo"]


def prefix_messages(fleet: list[str] | None = None) -> list[dict[str, str]]:
    """The system prompt, then each example as a user turn and the assistant's plan. The examples are
    written for a fleet of delta and echo; they are shown with the fleet's own first two ids instead (a
    decoder held to the fleet's ids cannot write an example's id, and a small model that wanted to then
    writes whichever id the grammar lets through). The prefix stays the same while the fleet does."""
    names = _renaming(fleet or EXAMPLE_FLEET)
    messages = [{"role": "system", "content": _STEPS}]
    for text, plan in EXAMPLES:
        messages.append({"role": "user", "content": _renamed(user_message(text, EXAMPLE_FLEET), names)})
        messages.append({"role": "assistant", "content": _renamed(_compact(plan), names)})
    return messages


def _renaming(fleet: list[str]) -> dict[str, str]:
    ids = (list(fleet) * 2)[:2] if fleet else EXAMPLE_FLEET
    return dict(zip(EXAMPLE_FLEET, ids, strict=True))


def _renamed(text: str, names: dict[str, str]) -> str:
    for old, new in names.items():
        text = text.replace(old, f"\0{new}").replace(old.capitalize(), f"\0{new.capitalize()}")
    return text.replace("\0", "")


def messages_for(request: str, fleet: list[str], places: list[str] | None = None) -> list[dict[str, str]]:
    """What the model is sent for a request: the fixed prefix, then the request."""
    return [*prefix_messages(fleet), {"role": "user", "content": user_message(request, fleet, places)}]


def system_prompt(fleet: list[str] | None = None) -> str:
    """The fixed prefix as one text (its size is what a request costs before its own words)."""
    return "\n".join(m["content"] for m in prefix_messages(fleet))


def _compact(plan: dict[str, Any]) -> str:
    return json.dumps(plan, separators=(",", ":"), ensure_ascii=False)


def user_message(request: str, fleet: list[str], places: list[str] | None = None) -> str:
    lines = [f"Fleet: {', '.join(fleet)}"]
    if places:
        lines.append(f"Named places: {', '.join(places)}")
    lines.append(f"Request: {request}")
    return "\n".join(lines)
