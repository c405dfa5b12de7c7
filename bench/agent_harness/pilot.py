"""The scripted "ideal pilot" of the benchmark's harness self-check (not a model).

It answers the host's request for a plan with the plan that the mission's ideal call sequence spells:
a takeoff, a move, a landing, a formation, a reading each become the typed step the host compiles back
into those calls. It exercises the whole harness (gateway, MCP, the host's compiler and checks, figures)
without a model; its numbers say nothing about any model and are labelled so.
"""

from __future__ import annotations

import json
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from bench.agent_harness.missions import PlannedCall
from bench.agent_harness.scripted import ScriptedReply

SELF_CHECK_MODEL = "harness-self-check (scripted, not a model)"


def _m(value: float) -> dict[str, Any]:
    """A length in metres with its sign kept: a negative altitude is left for the plan's schema to refuse."""
    return {"value": float(value), "unit": "m"}


def _move(args: dict[str, Any]) -> dict[str, Any]:
    legs = []
    for key, positive, negative in (
        ("north_m", "north", "south"),
        ("east_m", "east", "west"),
        ("up_m", "up", "down"),
    ):
        value = float(args.get(key) or 0.0)
        if value:
            legs.append({"distance": _m(abs(value)), "direction": positive if value > 0 else negative})
    alt = args.get("alt_m")
    altitude = None if alt is None else _m(alt)
    return {
        "action": "move",
        "drone": args["drone_id"],
        "legs": legs,
        "altitude": altitude,
        "origin": {"kind": "here"},
        "after": "stay",
    }


def _formation(args: dict[str, Any]) -> dict[str, Any]:
    legs = [
        {"distance": _m(abs(args[k])), "direction": (p if args[k] > 0 else n)}
        for k, p, n in (("north_m", "north", "south"), ("east_m", "east", "west"))
        if args.get(k)
    ]
    spacing, altitude = _m(args.get("spacing_m", 10.0)), _m(args["alt_m"])
    step = {
        "action": "formation",
        "drones": args["drone_ids"],
        "shape": args["formation"],
        "spacing": spacing,
        "altitude": altitude,
        "legs": legs,
    }
    if args.get("center_lat_deg") is not None:
        step["origin"] = {
            "kind": "point",
            "lat_deg": args["center_lat_deg"],
            "lon_deg": args["center_lon_deg"],
        }
    return step


def _goto(args: dict[str, Any], fleet: list[str]) -> dict[str, Any]:
    step = _move({"drone_id": args["drone_id"], "alt_m": args.get("alt_m")})
    return {**step, "origin": {"kind": "point", "lat_deg": args["lat_deg"], "lon_deg": args["lon_deg"]}}


def _report(args: dict[str, Any], fleet: list[str], reading: str) -> dict[str, Any]:
    drones = [args["drone_id"]] if "drone_id" in args else fleet
    return {"action": "report", "drones": drones, "readings": [reading, "battery"], "pick": "none"}


_STEPS: dict[str, Callable[[dict[str, Any], list[str]], dict[str, Any]]] = {
    "takeoff": lambda a, f: {"action": "takeoff", "drone": a["drone_id"], "altitude": _m(a["alt_m"])},
    "land": lambda a, f: {"action": "land", "drone": a["drone_id"]},
    "return_to_launch": lambda a, f: {"action": "return_home", "drone": a["drone_id"]},
    "hold_position": lambda a, f: {"action": "hold", "drone": a["drone_id"]},
    "move_to_relative": lambda a, f: _move(a),
    "go_to_location": _goto,
    "reposition": _goto,
    "formation_goto": lambda a, f: _formation(a),
    "get_battery": lambda a, f: _report(a, f, "battery"),
    "fleet_status": lambda a, f: _report(a, f, "flying"),
    "get_position": lambda a, f: _report(a, f, "altitude"),
}


def plan_of(calls: list[PlannedCall], fleet: list[str]) -> dict[str, Any]:
    """The typed plan whose compilation sends ``calls`` (the reads become report steps)."""
    steps = []
    for name, args in calls:
        if name == "fleet_takeoff":
            each = [{"drone_id": d, "alt_m": args["alt_m"]} for d in args["drone_ids"]]
            steps += [_STEPS["takeoff"](a, fleet) for a in each]
        elif name in _STEPS:
            steps.append(_STEPS[name](args, fleet))
    return {"steps": steps}


@dataclass
class ScriptedPilot:
    """Callable reply source for ``ScriptedModelServer``; ``load`` each mission's plan before it runs."""

    plan: list[PlannedCall] = field(default_factory=list)
    answer: str = "Done."

    def load(self, plan: list[PlannedCall], answer: str) -> None:
        self.plan, self.answer = list(plan), answer

    def __call__(self, request: dict[str, Any]) -> ScriptedReply:
        users = [m.get("content") or "" for m in request.get("messages", []) if m.get("role") == "user"]
        user = users[-1] if users else ""  # the request (the earlier user turns are the examples)
        fleet_line = next((line for line in user.splitlines() if line.startswith("Fleet: ")), "Fleet: ")
        fleet = [d.strip() for d in fleet_line.removeprefix("Fleet: ").split(",") if d.strip()]
        return ScriptedReply(content=json.dumps(plan_of(self.plan, fleet)))
