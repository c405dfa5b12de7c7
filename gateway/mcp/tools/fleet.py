"""Fleet toolset: several drones as one group. Listing, status, formations, fleet takeoff, landing, RTL, hold.

Who takes part (the same rule for every fleet tool, also in docs/fleet.md):
- formation_goto and fleet_takeoff change the fleet's geometry: every named drone is checked first and
  if any cannot take part (unknown, not ready, locked, busy, low battery, on the ground...) nothing is
  sent and the error names each such drone with the reason (rule and numbers).
- fleet_land, fleet_return_to_launch and fleet_hold bring drones down or stop them: they go to every
  drone that can take them, and the result lists the others (not_sent) with the reason.

Who takes part in each is decided by the Commander (`gateway.fleet.commands.fleet_verbs`); commands go out to
all drones at once; long ones wait (capped) like the single-drone tools and answer 'running' with an
operation id that monitor_fleet continues.
"""

from __future__ import annotations

from typing import Annotated, Any, Literal

from pydantic import BaseModel, Field

from gateway.fleet.commands.fleet_verbs import Formation
from gateway.fleet.operations.views import FleetHoldResult, FleetView
from gateway.fleet.vehicles.protocols import VehicleView
from gateway.fleet.vehicles.readings import value
from gateway.mcp.access import ToolCall
from gateway.mcp.results import Result, plain
from gateway.mcp.toolkit import Metres, Toolset, Wait

toolset = Toolset("fleet")

DroneIds = Annotated[list[str], Field(min_length=1, max_length=64, description="Drone ids")]
SomeDrones = Annotated[list[str] | None, Field(description="Drone ids; default: all")]
StateFilter = Literal[
    "ready", "connecting", "connected", "registered", "link_lost", "failed", "flying", "landed"
]
Alt = Annotated[float, Field(gt=0, le=10_000, allow_inf_nan=False, description="m above home")]


# --- results -----------------------------------------------------------------------------------------


# a plain model, not a Result: a row has no text of its own, and without a private attribute pydantic-core
# builds each row with no Python hook (no docstring either: it would go into the output schema)
class DroneRow(BaseModel):
    drone_id: str
    name: str | None
    tags: list[str]
    state: str
    armed: bool | None
    in_air: bool | None
    battery_pct: float | None
    lat_deg: float | None
    lon_deg: float | None
    alt_m: float | None
    flight_mode: str | None
    operation: str | None
    locked: str | None
    stale: bool
    initialising: str | None = None  # while connected, what the drone still waits for before it can fly


class DronesOut(Result):
    count: int
    drones: list[DroneRow]


class FleetStatusOut(Result):
    count: int
    ready: int
    flying: int
    table: str


class FleetOut(FleetView, Result):
    """A fleet operation: per-drone outcomes in ``drones``; 'running' means call monitor_fleet."""


class FleetHoldOut(FleetHoldResult, Result):
    """Which drones hold now, which failed, which were not sent the hold."""


# --- presenting ------------------------------------------------------------------------------------------


def fleet_out(view: FleetView) -> FleetOut:
    out = FleetOut(**view.model_dump())
    rows = "; ".join(f"{m['drone_id']} {m['status']}{_told(m)}" for m in view.drones)
    skipped = f"; not sent: {', '.join(str(u['drone_id']) for u in view.not_sent)}" if view.not_sent else ""
    if view.running:
        eta = f", ETA {view.eta_s:.0f} s" if view.eta_s is not None else ""
        text = (
            f"{view.kind} {view.operation_id} still running ({view.progress:.0%}{eta}, phase "
            f"{view.phase} of {len(view.phases)}): {rows}{skipped}. Call "
            f"monitor_fleet(operation_id='{view.operation_id}') to keep waiting; send no other moves to "
            "these drones meanwhile."
        )
    else:
        text = f"{view.kind} {view.operation_id} {view.status}: {view.message}. {rows}{skipped}"
    return out.say(text)


def _told(member: dict[str, Any]) -> str:
    """What one drone was told, in words: its altitude, the altitude it transits at, where it returns."""
    parts = []
    if member.get("transit_alt_m") is not None:
        parts.append(f"transit at {member['transit_alt_m']:g} m")
    if member.get("target_alt_m") is not None:
        parts.append(f"to {member['target_alt_m']:g} m")
    if member.get("rtl_alt_m") is not None:
        parts.append(f"returning at {member['rtl_alt_m']:g} m")
    return f" ({', '.join(parts)})" if parts else ""


async def _finish(call: ToolCall, view: FleetView, wait: bool) -> FleetOut:
    if wait and view.running:

        async def progress(v: FleetView) -> None:
            await call.ctx.report_progress(round(v.progress, 3), 1.0, v.message)

        view = await call.commander.wait_fleet(
            view.operation_id, call.settings.mcp_wait_cap_s, progress, view.not_sent
        )
    return fleet_out(view)


# --- read tools ----------------------------------------------------------------------------------------


def _row(call: ToolCall, v: VehicleView) -> dict[str, Any]:
    """One drone's row, each value computed once (its state too), as the plain values of a ``DroneRow``:
    the listing validates all rows at once when it builds its ``DronesOut`` (one pass in pydantic-core
    instead of a model per row)."""
    state = v.state
    sample = v.telemetry.position
    pos = None if sample is None else sample.value
    battery = value(v, "battery")
    op = call.commander.current_operation(v.id)  # on a cluster node also a drone owned elsewhere
    mode = value(v, "flight_mode")
    landed = v.on_ground(fresh=False)
    return {
        "drone_id": v.id,
        "name": v.spec.name,
        "tags": list(v.spec.tags),
        "state": str(plain(state)),
        "armed": value(v, "armed"),
        "in_air": None if landed is None else not landed,
        "battery_pct": None if battery is None else round(float(battery.remaining_pct), 1),
        "lat_deg": None if pos is None else round(float(pos.lat_deg), 7),
        "lon_deg": None if pos is None else round(float(pos.lon_deg), 7),
        "alt_m": None if pos is None else round(float(pos.rel_alt_m), 1),
        "flight_mode": None if mode is None else str(plain(mode)),
        "operation": None if op is None or op["status"] != "running" else f"{op['kind']} running",
        "locked": call.commander.locks.reason_for(v.id),
        "stale": sample is None or float(sample.age_s) > call.settings.link_lost_after_s,
        # only a connected drone initialises (Link.initialising): the state is not computed again otherwise
        "initialising": v.initialising() if state == "connected" else None,
    }


def _matches(row: dict[str, Any], state: str | None) -> bool:
    if state is None:
        return True
    if state == "flying":
        return bool(row["in_air"])
    if state == "landed":
        return row["in_air"] is False
    return bool(row["state"] == state)


@toolset.tool(read_only=True)
async def list_drones(
    call: ToolCall,
    tag: Annotated[str | None, Field(max_length=64, description="Only drones with this tag")] = None,
    state: Annotated[StateFilter | None, Field(description="Only drones in this state")] = None,
) -> DronesOut:
    """All drones: id, name, tags, state, armed, in air, battery %, position (m above home), mode, action."""
    vehicles = call.commander.registry.all()
    if tag is not None:
        vehicles = [v for v in vehicles if tag in v.spec.tags]
    rows = [r for r in (_row(call, v) for v in vehicles) if _matches(r, state)]
    text = "; ".join(_row_text(r) for r in rows)
    return DronesOut.model_validate({"count": len(rows), "drones": rows}).say(
        f"{len(rows)} drone(s): {text}" if rows else "no drones"
    )


def _row_text(r: dict[str, Any]) -> str:
    state = f"{r['state']} ({r['initialising']})" if r["initialising"] else r["state"]
    flying = " flying" if r["in_air"] else ""
    text = f"{r['drone_id']} {state}{flying} bat {r['battery_pct']}% alt {r['alt_m']} m"
    return text + (f" LOCKED: {r['locked']}" if r["locked"] else "")


def _cell(x: Any, digits: int = 0) -> str:
    if x is None:
        return "-"
    if isinstance(x, bool):
        return "y" if x else "n"
    if isinstance(x, float):
        return f"{x:.{digits}f}"
    return str(x)


@toolset.tool(read_only=True)
async def fleet_status(call: ToolCall) -> FleetStatusOut:
    """One compact table of all drones: state, armed, in air, battery %, alt m, mode, action, lock."""
    rows = [_row(call, v) for v in call.commander.registry.all()]
    lines = ["id state arm air bat% alt_m mode action lock"]
    for r in rows:
        state = r["state"] + ("(stale)" if r["stale"] and r["state"] == "ready" else "")
        state = "initialising" if r["initialising"] else state
        op = (r["operation"] or "-").replace(" running", "").replace(" ", "_")
        lines.append(
            " ".join(
                [
                    r["drone_id"],
                    state,
                    _cell(r["armed"]),
                    _cell(r["in_air"]),
                    _cell(r["battery_pct"]),
                    _cell(r["alt_m"], 1),
                    _cell(r["flight_mode"]),
                    op,
                    "LOCKED" if r["locked"] else "-",
                ]
            )
        )
    table = "\n".join(lines)
    ready = sum(1 for r in rows if r["state"] == "ready")
    flying = sum(1 for r in rows if r["in_air"])
    return FleetStatusOut(count=len(rows), ready=ready, flying=flying, table=table).say(table)


@toolset.tool(read_only=True)
async def monitor_fleet(
    call: ToolCall,
    operation_id: Annotated[str | None, Field(max_length=64, description="Default: latest")] = None,
) -> FleetOut:
    """Wait (capped) for a fleet operation and report each drone; call again while 'running'."""
    view = call.commander.fleet_operation(operation_id)
    return await _finish(call, view.model_copy(update={"not_sent": []}), True)


# --- formation, takeoff, land, return, hold -------------------------------------------------------------


@toolset.tool()
async def formation_goto(
    call: ToolCall,
    drone_ids: DroneIds,
    formation: Formation,
    alt_m: Alt,
    center_lat_deg: Annotated[float | None, Field(ge=-90, le=90, allow_inf_nan=False)] = None,
    center_lon_deg: Annotated[float | None, Field(ge=-180, le=180, allow_inf_nan=False)] = None,
    north_m: Annotated[Metres, Field(description="Centre moved north; default: where they are")] = 0.0,
    east_m: Annotated[Metres, Field(description="Centre moved east")] = 0.0,
    spacing_m: Annotated[
        float, Field(gt=0, le=1000, allow_inf_nan=False, description="m between slots")
    ] = 10.0,
    heading_deg: Annotated[
        float | None, Field(ge=0, lt=360, allow_inf_nan=False, description="Facing; default: travel")
    ] = None,
    wait: Wait = True,
) -> FleetOut:
    """Fly drones into a formation at a centre (default: theirs), kept apart; grounded ones take off first."""
    view = await call.commander.formation_goto(
        call.caller,
        drone_ids,
        formation,
        center_lat_deg,
        center_lon_deg,
        alt_m,
        spacing_m,
        heading_deg,
        north_m,
        east_m,
        notify=call.notify,
    )
    return await _finish(call, view, wait)


@toolset.tool()
async def fleet_takeoff(
    call: ToolCall,
    drone_ids: DroneIds,
    alt_m: Alt,
    stagger_m: Annotated[
        float | None, Field(ge=0, le=100, allow_inf_nan=False, description="m between drones' altitudes")
    ] = None,
    wait: Wait = True,
) -> FleetOut:
    """Take off drones at once to alt_m, alt_m+stagger, ... (given order). All must be able, or none go."""
    view = await call.commander.fleet_takeoff(call.caller, drone_ids, alt_m, stagger_m, notify=call.notify)
    return await _finish(call, view, wait)


@toolset.tool(idempotent=True)
async def fleet_land(call: ToolCall, drone_ids: SomeDrones = None, wait: Wait = True) -> FleetOut:
    """Land drones in place, all at once; done when disarmed. Those that cannot are listed in not_sent."""
    return await _finish(call, await call.commander.fleet_land(call.caller, drone_ids), wait)


@toolset.tool(idempotent=True)
async def fleet_return_to_launch(
    call: ToolCall,
    drone_ids: SomeDrones = None,
    rtl_alt_m: Annotated[
        float | None, Field(gt=0, le=10_000, allow_inf_nan=False, description="Lowest return alt, m")
    ] = None,
    stagger_m: Annotated[
        float | None, Field(ge=0, le=100, allow_inf_nan=False, description="m between return altitudes")
    ] = None,
    wait: Wait = True,
) -> FleetOut:
    """Fly drones home at separate altitudes and land. Those that cannot are listed in not_sent."""
    view = await call.commander.fleet_return_to_launch(call.caller, drone_ids, rtl_alt_m, stagger_m)
    return await _finish(call, view, wait)


@toolset.tool(idempotent=True)
async def fleet_hold(call: ToolCall, drone_ids: SomeDrones = None) -> FleetHoldOut:
    """Stop drones where they are (GUIDED hover), ending their actions. Those that cannot: not_sent."""
    result = await call.commander.fleet_hold(call.caller, drone_ids)
    text = f"holding: {', '.join(result.held) or 'none'}"
    if result.failed:
        text += "; failed: " + "; ".join(f"{f['drone_id']}: {f['message']}" for f in result.failed)
    if result.not_sent:
        text += "; not sent: " + "; ".join(f"{u['drone_id']}: {u['message']}" for u in result.not_sent)
    return FleetHoldOut(**result.model_dump()).say(text)
