"""What a small model is shown: about ten tools, and none of the advanced optional arguments.

A 1.5B-parameter model handed the gateway's 54 tools (about 5,900 tokens in its own tokenizer) mostly
picks the wrong one or none. The ``small`` profile keeps the tools a person's requests need (fleet
status, takeoff, land, return home, relative move, goto, battery, position, formation; the host itself
waits for actions that outlast the gateway's capped wait) and
drops optional arguments whose server-side default is what a person means (``wait``: wait until done;
``alt_frame``: metres above home; ``heading_deg``: facing the way of travel; ...). The gateway still
accepts them from any client; only what the model reads changes.

This is a host-side selection on purpose: the gateway serves every client at once (a large model, an
operator's tools, the console), and which tools a model can handle is a property of the model, which
only the host knows. ``GATEWAY_MCP_TOOLSETS`` stays the server-side switch for what may be called at all.
"""

from __future__ import annotations

import copy
import dataclasses
import re
from collections.abc import Sequence
from typing import TypedDict

from gateway.agent.toolbox import ToolInfo, ToolSelectionError

PROFILES = ("full", "small")

# The small profile's system prompt: short, one rule a line, naming the tools it means. The second example
# is from the NL corpus's dev half: "Alpha to 10 m and bravo to 20 m" (multi-two-heights) was planned as
# move_to_relative(north_m=10, alt_m=0), the shape of the only example, for drones on the ground; with
# the second example, as takeoff(10) and takeoff(20).
SMALL_MODEL_SYSTEM_PROMPT = (
    "You fly drones by calling tools, one tool call at a time. After each tool result, call the tool for "
    'the next step of the request, in the order the user asked. Use only the drone ids in "Fleet now". '
    "Altitudes are metres above home. If a tool refuses, tell the user why and stop. When every step is "
    "done, answer in one short sentence.\n"
    'Example: "bravo: 50 m east at 20 m, then land" is move_to_relative(drone_id="bravo", east_m=50, '
    'alt_m=20), then land(drone_id="bravo"); "alpha to 10 m" is takeoff(drone_id="alpha", alt_m=10). Use '
    "go_to_location only with coordinates the user gave."
)


def system_prompt_for(profile: str, default: str) -> str:
    """The system prompt a model of this profile gets unless one is given."""
    return SMALL_MODEL_SYSTEM_PROMPT if profile == "small" else default


class HostOptions(TypedDict):
    """Keyword arguments of ``AgentHost`` that depend on the profile."""

    answer_tool: bool
    follow_running: bool
    plan_first: bool


def host_options_for(profile: str) -> HostOptions:
    """How the host helps a model of this profile (keyword arguments of ``AgentHost``).

    ``answer_tool``: the host's answer_user tool (gateway/agent/answer.py); small models end a turn far
    more reliably with a tool call than with prose. ``follow_running``: the host waits for an action still
    running after the gateway's capped wait, so the model never needs monitor_flight (measured: the 1.5B
    model called it after every finished action, and read an older operation's result as news).
    ``plan_first``: the model writes the request as numbered steps before it calls a tool (planning.py)."""
    small = profile == "small"
    return HostOptions(answer_tool=small, follow_running=small, plan_first=small)


SMALL_MODEL_TOOLS = (
    "fleet_status",
    "takeoff",
    "land",
    "return_to_launch",
    "move_to_relative",
    "go_to_location",
    "get_position",
    "get_battery",
    "formation_goto",
)

# What a small model reads about each tool: when to use it, in the words a request uses. Measured: with the
# gateway's own terse texts the 1.5B model climbed with go_to_location(0, 0) and wrote plans as prose.
SMALL_MODEL_DESCRIPTIONS = {
    "fleet_status": "Table of all drones: state, flying or not, battery %, altitude in metres.",
    "takeoff": "Take off a drone that is on the ground and climb to alt_m metres above home. "
    "Waits until reached.",
    "land": "Land the drone where it is now. Waits until landed.",
    "return_to_launch": "Fly the drone back home (its launch point) and land there. Waits until landed.",
    "move_to_relative": "Fly a drone some metres from where it is: north_m (negative: south), east_m "
    "(negative: west), and either up_m (metres up, negative: down) or alt_m (metres above home). A drone on "
    "the ground takes off first. Waits until arrived.",
    "go_to_location": "Fly a flying drone to the lat_deg, lon_deg the user gave, at alt_m metres above "
    "home. Waits until arrived.",
    "get_position": "Where the drone is: lat_deg, lon_deg, alt_m metres above home.",
    "get_battery": "Battery of one drone: remaining percent and voltage.",
    "formation_goto": "Fly drones into a formation (line, column, wedge, grid or circle) at alt_m metres "
    "above home, spacing_m metres apart, centred where they are now, moved north_m/east_m metres. "
    "center_lat_deg, center_lon_deg only for coordinates the user gave. Drones on the ground take off first.",
}

# Arguments a small model is shown first, in this order (the rest follow in the gateway's order). A small
# model fills arguments in the order it reads them: measured on the corpus's dev half with the 1.5B model,
# "8 metres apart, right where they are" (form-line-here) and "15 m apart ... where they are now"
# (form-pair-abreast) put the distance into north_m, the first metres argument after the centre, and left
# spacing_m at its default, so the formation was flown off where it was asked.
FIRST_ARGUMENTS = {"formation_goto": ("drone_ids", "formation", "alt_m", "spacing_m")}

# Optional arguments left out of what a small model is shown (the gateway's defaults apply). south_m and
# west_m are not shown either (north_m and east_m take negative values), but the gateway takes them when a
# small model writes them, as it does for "40 m west".
ADVANCED_ARGUMENTS = frozenset(
    {"wait", "alt_frame", "heading_deg", "stagger_m", "land_on_arrival", "tag", "state", "south_m", "west_m"}
)

# Schema bounds a small model is not shown (the gateway checks them and its refusal names the limit): they
# cost tokens on every turn and a person's request never comes near them. alt_m's maximum stays.
BOUNDS_LEFT_TO_THE_GATEWAY = ("minimum", "maximum", "exclusiveMinimum", "minItems", "maxItems")


def without_arguments(tool: ToolInfo, names: frozenset[str]) -> ToolInfo:
    """The tool without the given optional arguments (required ones always stay)."""
    schema = tool.input_schema or {}
    props = schema.get("properties") or {}
    required = set(schema.get("required") or [])
    drop = [n for n in props if n in names and n not in required]
    if not drop:
        return tool
    trimmed = copy.deepcopy(schema)
    for n in drop:
        del trimmed["properties"][n]
    return dataclasses.replace(tool, input_schema=trimmed, hidden=tool.hidden | set(drop))


def apply_profile(tools: Sequence[ToolInfo], profile: str, *, keep_selection: bool = False) -> list[ToolInfo]:
    """The tools as a model of this profile sees them. ``keep_selection``: the caller already chose the
    tools (``--tools`` / ``--toolsets``), so only the advanced arguments are dropped."""
    if profile == "full":
        return list(tools)
    if profile != "small":
        raise ToolSelectionError(f"unknown profile {profile!r}; known: {', '.join(PROFILES)}")
    if not keep_selection:
        offered = {t.name: t for t in tools}
        missing = [n for n in SMALL_MODEL_TOOLS if n not in offered]
        if len(missing) == len(SMALL_MODEL_TOOLS):
            raise ToolSelectionError(
                f"the server offers none of the small profile's tools ({', '.join(SMALL_MODEL_TOOLS)})"
            )
        tools = [offered[n] for n in SMALL_MODEL_TOOLS if n in offered]
    return [_described(without_arguments(t, ADVANCED_ARGUMENTS)) for t in tools]


def _described(tool: ToolInfo) -> ToolInfo:
    """The small model's description, and argument descriptions that no longer name hidden arguments."""
    schema = copy.deepcopy(tool.input_schema or {})
    hidden = "|".join(sorted(ADVANCED_ARGUMENTS))
    for name, prop in (schema.get("properties") or {}).items():
        if not isinstance(prop, dict):
            continue
        if isinstance(prop.get("description"), str):
            prop["description"] = re.sub(rf";? unless (?:{hidden})=\w+", "", prop["description"])
        for bound in BOUNDS_LEFT_TO_THE_GATEWAY:
            if not (name == "alt_m" and bound == "maximum"):  # the altitude limit is worth reading
                prop.pop(bound, None)
    first = [n for n in FIRST_ARGUMENTS.get(tool.name, ()) if n in (schema.get("properties") or {})]
    if first:
        props = schema["properties"]
        schema["properties"] = {n: props[n] for n in [*first, *(n for n in props if n not in first)]}
    description = SMALL_MODEL_DESCRIPTIONS.get(tool.name, tool.description)
    return dataclasses.replace(tool, description=description, input_schema=schema)
