"""What a small model is shown: about ten tools, and none of the advanced optional arguments.

A 1.5B-parameter model handed the gateway's 54 tools (about 5,900 tokens in its own tokenizer) mostly
picks the wrong one or none. The ``small`` profile keeps the tools a person's requests need (fleet
status, takeoff, land, return home, relative move, goto, battery, position, formation, waiting) and
drops optional arguments whose server-side default is what a person means (``wait``: wait until done;
``alt_frame``: metres above home; ``heading_deg``: facing the way of travel; ...). The gateway still
accepts them from any client; only what the model reads changes.

This is a host-side selection on purpose: the gateway serves every client at once (a large model, an
operator's tools, the console), and which tools a model can handle is a property of the model, which
only the host knows. ``GATEWAY_MCP_TOOLSETS`` stays the server-side switch for what may be called at all.
"""

from __future__ import annotations

import copy
from collections.abc import Sequence

from gateway.agent.toolbox import ToolInfo, ToolSelectionError

PROFILES = ("full", "small")

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
    "monitor_flight",
)

# Optional arguments left out of what a small model is shown (the gateway's defaults apply).
ADVANCED_ARGUMENTS = frozenset(
    {"wait", "alt_frame", "heading_deg", "stagger_m", "land_on_arrival", "tag", "state"}
)


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
    return ToolInfo(tool.name, tool.description, trimmed, tool.toolset, tool.read_only)


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
    return [without_arguments(t, ADVANCED_ARGUMENTS) for t in tools]
