"""Params toolset: read, write (minus the safety deny list) and page through autopilot parameters."""

from __future__ import annotations

from typing import Annotated

from pydantic import Field

from gateway.mcp.access import ToolCall
from gateway.mcp.results import ParamListOut, ParamOut
from gateway.mcp.toolkit import DroneId, Toolset

toolset = Toolset("params")

ParamName = Annotated[str, Field(pattern=r"^[A-Za-z0-9_]{1,16}$", description="e.g. WPNAV_SPEED")]


@toolset.tool(read_only=True)
async def get_parameter(call: ToolCall, drone_id: DroneId, name: ParamName) -> ParamOut:
    """Read one autopilot parameter."""
    p = await call.commander.get_param(call.caller, drone_id, name)
    return ParamOut(drone_id=drone_id, name=p.name, value=p.value, type=p.type).say(
        f"{drone_id} {p.name} = {p.value:g}"
    )


@toolset.tool(idempotent=True)
async def set_parameter(
    call: ToolCall,
    drone_id: DroneId,
    name: ParamName,
    value: Annotated[float, Field(allow_inf_nan=False)],
) -> ParamOut:
    """Write one parameter (type taken from the drone). Safety parameters are refused."""
    p = await call.commander.set_param(call.caller, drone_id, name, value)
    return ParamOut(drone_id=drone_id, name=p.name, value=p.value, type=p.type).say(
        f"{drone_id} {p.name} set to {p.value:g}"
    )


@toolset.tool(read_only=True)
async def list_parameters(
    call: ToolCall,
    drone_id: DroneId,
    prefix: Annotated[str, Field(max_length=16, pattern=r"^[A-Za-z0-9_]*$", description="Name prefix")] = "",
    offset: Annotated[int, Field(ge=0)] = 0,
    limit: Annotated[int, Field(ge=1, le=500)] = 100,
) -> ParamListOut:
    """Parameters whose name starts with prefix, sorted, one page at a time."""
    page = await call.commander.list_params(call.caller, drone_id, prefix, offset, limit)
    more = f"; next page: offset={page.next_offset}" if page.next_offset is not None else ""
    return ParamListOut(
        drone_id=drone_id,
        prefix=page.prefix,
        total=page.total,
        offset=page.offset,
        params=page.params,
        next_offset=page.next_offset,
    ).say(f"{drone_id}: {len(page.params)} of {page.total} parameters starting with '{page.prefix}'{more}")
