"""Fleet toolset: several drones as one group. Listing, status and monitoring here; formations, fleet
takeoff, landing, RTL and hold are commands, declared with their verbs.

Who takes part in each is decided by the Commander (`gateway.fleet.commands.fleet_verbs`, whose docstring
and docs/fleet.md state the rule); commands go out to all drones at once; long ones wait (capped) like the
single-drone tools and answer 'running' with an operation id that monitor_fleet continues
(`gateway.mcp.presenters` presents them).
"""

from __future__ import annotations

from typing import Annotated, Literal, NotRequired

from pydantic import Field
from typing_extensions import TypedDict  # pydantic takes typing's TypedDict from Python 3.12 on

from gateway.fleet.vehicles.protocols import VehicleView
from gateway.fleet.vehicles.readings import value
from gateway.mcp.access import ToolCall
from gateway.mcp.presenters import FleetOut, finish_fleet
from gateway.mcp.results import Result, plain
from gateway.mcp.toolkit import Toolset

toolset = Toolset("fleet")

StateFilter = Literal[
    "ready", "connecting", "connected", "registered", "link_lost", "failed", "flying", "landed"
]


# --- results -----------------------------------------------------------------------------------------


# a plain TypedDict, not a Result: a row has no text of its own; the listing builds each row as a dict and
# validates all rows at once (one pass in pydantic-core, no Python hook per row; no docstring either: it
# would go into the output schema)
class DroneRow(TypedDict):
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
    initialising: NotRequired[str | None]  # while connected, what the drone still waits for before it can fly


class DronesOut(Result):
    count: int
    drones: list[DroneRow]


class FleetStatusOut(Result):
    count: int
    ready: int
    flying: int
    table: str


# --- read tools ----------------------------------------------------------------------------------------


def _row(call: ToolCall, v: VehicleView) -> DroneRow:
    """One drone's row, each value computed once (its state too), as the plain values of a ``DroneRow``:
    the listing validates all rows at once when it builds its ``DronesOut`` (one pass in pydantic-core
    instead of a model per row)."""
    state = v.state
    sample = v.telemetry.position
    pos = None if sample is None else sample.value
    battery = value(v.telemetry.battery)
    battery_pct = None if battery is None else battery.remaining_pct  # None: the autopilot does not know
    op = call.commander.current_operation(v.id)  # on a cluster node also a drone owned elsewhere
    mode = value(v.telemetry.flight_mode)
    landed = v.on_ground(fresh=False)
    return {
        "drone_id": v.id,
        "name": v.spec.name,
        "tags": list(v.spec.tags),
        "state": str(plain(state)),
        "armed": value(v.telemetry.armed),
        "in_air": None if landed is None else not landed,
        "battery_pct": None if battery_pct is None else round(battery_pct, 1),
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


def _matches(row: DroneRow, state: str | None) -> bool:
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


def _row_text(r: DroneRow) -> str:
    state = f"{r['state']} ({r['initialising']})" if r["initialising"] else r["state"]
    flying = " flying" if r["in_air"] else ""
    text = f"{r['drone_id']} {state}{flying} bat {r['battery_pct']}% alt {r['alt_m']} m"
    return text + (f" LOCKED: {r['locked']}" if r["locked"] else "")


def _cell(x: object, digits: int = 0) -> str:
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
    return await finish_fleet(call, view.model_copy(update={"not_sent": []}), True)


# here: the fleet commands, declared with their verbs (@command(tool=Tool(..., "fleet")) in
# gateway/fleet/commands/fleet_verbs.py), built by gateway/mcp/declared.py
toolset.declared_here()
