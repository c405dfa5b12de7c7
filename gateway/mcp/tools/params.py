"""Params toolset: read, write (minus the safety deny list) and page through autopilot parameters."""

from __future__ import annotations

from typing import Annotated

from mcp.server.mcpserver import Context
from pydantic import Field

from gateway.mcp.access import FleetAccess
from gateway.mcp.results import ParamListOut, ParamOut
from gateway.mcp.toolkit import DroneId, Toolset

toolset = Toolset("params")

ParamName = Annotated[str, Field(pattern=r"^[A-Za-z0-9_]{1,16}$", description="e.g. WPNAV_SPEED")]


@toolset.tool(read_only=True)
async def get_parameter(fa: FleetAccess, ctx: Context, drone_id: DroneId, name: ParamName) -> ParamOut:
    """Read one autopilot parameter."""
    v = fa.ready(drone_id)
    name = name.upper()
    val, kind = await v.get_param(name)
    return ParamOut(drone_id=drone_id, name=name, value=val, type=kind).say(f"{drone_id} {name} = {val:g}")


@toolset.tool(idempotent=True)
async def set_parameter(
    fa: FleetAccess,
    ctx: Context,
    drone_id: DroneId,
    name: ParamName,
    value: Annotated[float, Field(allow_inf_nan=False)],
) -> ParamOut:
    """Write one parameter (type taken from the drone). Safety parameters are refused."""
    v = fa.ready(drone_id)
    name = name.upper()
    fa.safety.check_param_write(name, vehicle_id=v.id, protected=v.protected_params)
    fa.safety.check_actuation(fa.context(v))
    val, kind = await v.set_param(name, value)
    return ParamOut(drone_id=drone_id, name=name, value=val, type=kind).say(
        f"{drone_id} {name} set to {val:g}"
    )


@toolset.tool(read_only=True)
async def list_parameters(
    fa: FleetAccess,
    ctx: Context,
    drone_id: DroneId,
    prefix: Annotated[str, Field(max_length=16, pattern=r"^[A-Za-z0-9_]*$", description="Name prefix")] = "",
    offset: Annotated[int, Field(ge=0)] = 0,
    limit: Annotated[int, Field(ge=1, le=500)] = 100,
) -> ParamListOut:
    """Parameters whose name starts with prefix, sorted, one page at a time."""
    v = fa.ready(drone_id)
    prefix = prefix.upper()
    every = await v.list_params()
    names = sorted(n for n in every if n.startswith(prefix))
    page = names[offset : offset + limit]
    nxt = offset + limit if offset + limit < len(names) else None
    more = f"; next page: offset={nxt}" if nxt is not None else ""
    return ParamListOut(
        drone_id=drone_id,
        prefix=prefix,
        total=len(names),
        offset=offset,
        params={n: every[n] for n in page},
        next_offset=nxt,
    ).say(f"{drone_id}: {len(page)} of {len(names)} parameters starting with '{prefix}'{more}")
