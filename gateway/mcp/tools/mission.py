"""Mission toolset: waypoint missions (user waypoint 1 is the first item; the home slot is hidden). The
tools here present missions as they stand; the commands (upload, start, pause, resume, clear, next
item) are declared with their verbs."""

from __future__ import annotations

from gateway.fleet.commands.arguments import in_caller_words
from gateway.mcp.access import ToolCall
from gateway.mcp.results import MissionItemOut, MissionOut, MissionProgressOut, ValueOut
from gateway.mcp.toolkit import DroneId, Toolset

toolset = Toolset("mission")


@toolset.tool(read_only=True)
async def download_mission(call: ToolCall, drone_id: DroneId) -> MissionOut:
    """The mission stored on the drone (alt_m above home)."""
    mission = await call.commander.download_mission(call.caller, drone_id)
    out = [
        MissionItemOut.model_validate({"index": n, **in_caller_words(i)})
        for n, i in enumerate(mission.items, 1)
    ]
    return MissionOut(drone_id=drone_id, count=len(out), items=out).say(
        f"{drone_id}: mission of {len(out)} items"
    )


@toolset.tool(read_only=True)
async def print_mission_progress(call: ToolCall, drone_id: DroneId) -> MissionProgressOut:
    """Current item (1..N) of the mission and whether it finished."""
    p = await call.commander.mission_progress(call.caller, drone_id)
    return MissionProgressOut(
        drone_id=drone_id,
        current=p.current,
        total=p.total,
        finished=p.finished,
        operation_status=p.operation_status,
    ).say(f"{drone_id}: item {p.current} of {p.total}" + (", finished" if p.finished else ""))


@toolset.tool(read_only=True)
async def is_mission_finished(call: ToolCall, drone_id: DroneId) -> ValueOut:
    """true when the mission has run to its end."""
    finished = (await call.commander.mission_progress(call.caller, drone_id)).finished
    return ValueOut(drone_id=drone_id, age_s=0.0, stale=False, value=finished).say(
        f"{drone_id}: mission {'finished' if finished else 'not finished'}"
    )


# here: the tools the verbs declare for this toolset (@command(tool=Tool(..., "mission")), mostly in
# gateway/fleet/commands/mission_verbs.py), built by gateway/mcp/declared.py (the hand-written: this module)
toolset.declared_here()
