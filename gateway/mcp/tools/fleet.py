"""Fleet toolset: several drones as one group. Listing, status, formations, fleet takeoff, landing, RTL, hold.

Who takes part (the same rule for every fleet tool, also in docs/fleet.md):
- formation_goto and fleet_takeoff change the fleet's geometry: every named drone is checked first and
  if any cannot take part (unknown, not ready, locked, busy, low battery, on the ground...) nothing is
  sent and the error names each such drone with the reason (rule and numbers).
- fleet_land, fleet_return_to_launch and fleet_hold bring drones down or stop them: they go to every
  drone that can take them, and the result lists the others (not_sent) with the reason.

Commands go out to all drones at once; long ones wait (capped) like the single-drone tools and answer
'running' with an operation id that monitor_fleet continues.
"""

from __future__ import annotations

import asyncio
import contextlib
import dataclasses
import json
import logging
from typing import Annotated, Any, Literal

from mcp.server.mcpserver import Context, MCPServer
from mcp.server.subscriptions import ResourceUpdated
from pydantic import Field

from gateway.errors import GatewayError, InvalidArgument, SafetyRefusal, VehicleNotReady
from gateway.fleet import geo
from gateway.fleet.fleet_ops import (
    FORMATION_TOLERANCE_M,
    FleetOperation,
    FleetOperations,
    Unable,
    check_drone_ids,
    collect_members,
    default_rtl_base_m,
    formation_phases,
    land_phase,
    refuse_fleet,
    rtl_order,
    rtl_phases,
    set_rtl_altitude_param,
    slot_summaries,
    takeoff_phase,
)
from gateway.fleet.formation import DroneStart, plan_formation, rtl_altitudes, takeoff_altitudes
from gateway.fleet.operations import home, is_landed_and_disarmed, position, value
from gateway.mcp.access import FleetAccess
from gateway.mcp.results import plain
from gateway.mcp.toolkit import Result, Toolset, Wait

log = logging.getLogger(__name__)

toolset = Toolset("fleet")

FORMATION_URI = "fleet://formation"

DroneIds = Annotated[list[str], Field(min_length=1, max_length=64, description="Drone ids")]
SomeDrones = Annotated[list[str] | None, Field(description="Drone ids; default: all")]
Formation = Literal["line", "column", "wedge", "grid", "circle"]
StateFilter = Literal[
    "ready", "connecting", "connected", "registered", "link_lost", "failed", "flying", "landed"
]
Alt = Annotated[float, Field(gt=0, le=10_000, allow_inf_nan=False, description="m above home")]


# --- results -----------------------------------------------------------------------------------------


class DroneRow(Result):
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


class FleetOut(Result):
    """A fleet operation: per-drone outcomes in ``drones``; 'running' means call monitor_fleet."""

    operation_id: str
    kind: str
    status: str
    message: str
    phase: int
    phases: list[str]
    progress: float
    eta_s: float | None
    elapsed_s: float
    dispatch_s: list[float]
    drones: list[dict[str, Any]]
    not_sent: list[dict[str, Any]] = Field(default_factory=list)
    notes: list[str] = Field(default_factory=list)
    plan: dict[str, Any] | None = None


class FleetHoldOut(Result):
    held: list[str]
    failed: list[dict[str, Any]]
    not_sent: list[dict[str, Any]]
    superseded_fleet_operations: list[str]


# --- access to the fleet operations --------------------------------------------------------------------


def fleet_ops(fa: FleetAccess) -> FleetOperations:
    """The gateway's FleetOperations, created on first use over its OperationManager."""
    ops = getattr(fa.gateway, "fleet_operations", None)
    if ops is None:
        ops = FleetOperations(fa.operations, alive=lambda: getattr(fa.gateway, "registry", None) is not None)
        fa.gateway.fleet_operations = ops
    return ops


def _all_ids(fa: FleetAccess, drone_ids: list[str] | None) -> list[str]:
    if drone_ids is None:
        ids = [v.id for v in fa.registry.all()]
        if not ids:
            raise InvalidArgument("no drones are registered")
        return ids
    return check_drone_ids(drone_ids)


def _busy(fa: FleetAccess, vehicle: Any, action: str) -> None:
    op = fa.operations.running(vehicle.id)
    if op is not None:
        raise SafetyRefusal(
            "drone_busy",
            f"drone_busy: {vehicle.id} is still running {op.kind} (operation {op.id}: {op.message}); wait "
            f"for it (monitor_flight / monitor_fleet) or call fleet_hold before {action}",
            vehicle_id=vehicle.id,
            operation_id=op.id,
        )


def _fleet_out(fa: FleetAccess, fop: FleetOperation, not_sent: list[Unable] | None = None) -> FleetOut:
    d = fop.to_dict()
    plan = None
    if fop.plan is not None:
        plan = {k: fop.plan[k] for k in ("formation", "spacing_m", "heading_deg", "alt_m", "min_clearance_m")}
        plan["conflicts_resolved"] = len(fop.plan.get("conflicts", []))
    out = FleetOut(**d, not_sent=[u.to_dict() for u in not_sent or []], plan=plan)
    rows = "; ".join(f"{m['drone_id']} {m['status']}{_told(m)}" for m in d["drones"])
    skipped = f"; not sent: {', '.join(u.drone_id for u in not_sent)}" if not_sent else ""
    if fop.status == "running":
        eta = f", ETA {d['eta_s']:.0f} s" if d["eta_s"] is not None else ""
        text = (
            f"{fop.kind} {fop.id} still running ({d['progress']:.0%}{eta}, phase {fop.phase} of "
            f"{len(fop.phase_names)}): {rows}{skipped}. Call monitor_fleet(operation_id='{fop.id}') to keep "
            "waiting; send no other moves to these drones meanwhile."
        )
    else:
        text = f"{fop.kind} {fop.id} {fop.status}: {fop.message}. {rows}{skipped}"
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


async def _run(ctx: Context, fa: FleetAccess, fop: FleetOperation, wait: bool) -> FleetOperation:
    if not wait:
        return fop

    async def on_progress(f: FleetOperation) -> None:
        await ctx.report_progress(round(f.progress, 3), 1.0, f.message)

    return await fleet_ops(fa).wait(fop, fa.settings.mcp_wait_cap_s, on_progress)


def _stagger(fa: FleetAccess, stagger_m: float | None) -> float:
    """Default: the minimum separation plus 1 m of altitude-holding error for each of two drones."""
    return fa.settings.min_separation_m + 2 * FORMATION_TOLERANCE_M if stagger_m is None else stagger_m


# --- read tools ----------------------------------------------------------------------------------------


def _row(fa: FleetAccess, v: Any) -> DroneRow:
    pos = position(v)
    battery = value(v, "battery")
    sample = getattr(v.telemetry, "position", None)
    stale = sample is None or float(sample.age_s) > fa.settings.link_lost_after_s
    op = fa.operations.running(v.id)
    mode = value(v, "flight_mode")
    return DroneRow(
        drone_id=v.id,
        name=getattr(v.spec, "name", None),
        tags=list(getattr(v.spec, "tags", None) or []),
        state=str(plain(v.state)),
        armed=value(v, "armed"),
        in_air=value(v, "in_air"),
        battery_pct=None if battery is None else round(float(battery.remaining_pct), 1),
        lat_deg=None if pos is None else round(pos[0], 7),
        lon_deg=None if pos is None else round(pos[1], 7),
        alt_m=None if pos is None else round(pos[2], 1),
        flight_mode=None if mode is None else str(plain(mode)),
        operation=None if op is None else f"{op.kind} {op.status.value}",
        locked=fa.safety.locks.reason_for(v.id),
        stale=stale,
        initialising=v.initialising(),
    )


def _matches(row: DroneRow, state: str | None) -> bool:
    if state is None:
        return True
    if state == "flying":
        return bool(row.in_air)
    if state == "landed":
        return row.in_air is False
    return row.state == state


@toolset.tool(read_only=True)
async def list_drones(
    fa: FleetAccess,
    ctx: Context,
    tag: Annotated[str | None, Field(max_length=64, description="Only drones with this tag")] = None,
    state: Annotated[StateFilter | None, Field(description="Only drones in this state")] = None,
) -> DronesOut:
    """All drones: id, name, tags, state, armed, in air, battery %, position (m above home), mode, action."""
    rows = [_row(fa, v) for v in fa.registry.all()]
    rows = [r for r in rows if (tag is None or tag in r.tags) and _matches(r, state)]
    text = "; ".join(_row_text(r) for r in rows)
    return DronesOut(count=len(rows), drones=rows).say(
        f"{len(rows)} drone(s): {text}" if rows else "no drones"
    )


def _row_text(r: DroneRow) -> str:
    state = f"{r.state} ({r.initialising})" if r.initialising else r.state
    text = f"{r.drone_id} {state}{' flying' if r.in_air else ''} bat {r.battery_pct}% alt {r.alt_m} m"
    return text + (f" LOCKED: {r.locked}" if r.locked else "")


def _cell(x: Any, digits: int = 0) -> str:
    if x is None:
        return "-"
    if isinstance(x, bool):
        return "y" if x else "n"
    if isinstance(x, float):
        return f"{x:.{digits}f}"
    return str(x)


@toolset.tool(read_only=True)
async def fleet_status(fa: FleetAccess, ctx: Context) -> FleetStatusOut:
    """One compact table of all drones: state, armed, in air, battery %, alt m, mode, action, lock."""
    rows = [_row(fa, v) for v in fa.registry.all()]
    lines = ["id state arm air bat% alt_m mode action lock"]
    for r in rows:
        state = r.state + ("(stale)" if r.stale and r.state == "ready" else "")
        state = "initialising" if r.initialising else state
        op = (r.operation or "-").replace(" running", "").replace(" ", "_")
        lines.append(
            " ".join(
                [
                    r.drone_id,
                    state,
                    _cell(r.armed),
                    _cell(r.in_air),
                    _cell(r.battery_pct),
                    _cell(r.alt_m, 1),
                    _cell(r.flight_mode),
                    op,
                    "LOCKED" if r.locked else "-",
                ]
            )
        )
    table = "\n".join(lines)
    ready = sum(1 for r in rows if r.state == "ready")
    flying = sum(1 for r in rows if r.in_air)
    return FleetStatusOut(count=len(rows), ready=ready, flying=flying, table=table).say(table)


@toolset.tool(read_only=True)
async def monitor_fleet(
    fa: FleetAccess,
    ctx: Context,
    operation_id: Annotated[str | None, Field(max_length=64, description="Default: latest")] = None,
) -> FleetOut:
    """Wait (capped) for a fleet operation and report each drone; call again while 'running'."""
    ops = fleet_ops(fa)
    fop = ops.get(operation_id) if operation_id else ops.latest()
    if fop is None:
        raise InvalidArgument("no fleet operation has been started yet")
    fop = await _run(ctx, fa, fop, True)
    return _fleet_out(fa, fop)


# --- formation ----------------------------------------------------------------------------------------


@toolset.tool()
async def formation_goto(
    fa: FleetAccess,
    ctx: Context,
    drone_ids: DroneIds,
    formation: Formation,
    center_lat: Annotated[float, Field(ge=-90, le=90, allow_inf_nan=False)],
    center_lon: Annotated[float, Field(ge=-180, le=180, allow_inf_nan=False)],
    alt_m: Alt,
    spacing_m: Annotated[
        float, Field(gt=0, le=1000, allow_inf_nan=False, description="m between slots")
    ] = 10.0,
    heading_deg: Annotated[
        float | None, Field(ge=0, lt=360, allow_inf_nan=False, description="Facing; default: travel")
    ] = None,
    wait: Wait = True,
) -> FleetOut:
    """Fly airborne drones into a formation around a point, kept apart. All must join or nothing is sent."""
    ids = check_drone_ids(drone_ids)
    policy = fa.safety

    def check(v: Any) -> None:
        v.require_ready()
        fa.guard_takeoff(v, "formation_goto")
        fa.require_airborne(v, "formation_goto")
        _busy(fa, v, "formation_goto")
        if position(v) is None:
            raise VehicleNotReady(f"no position received from {v.id} yet")
        policy.check_actuation(fa.context(v))

    vehicles, unable = collect_members(ids, fa.vehicle, check)
    if unable:
        raise refuse_fleet("formation_goto", unable, len(ids))
    starts = [DroneStart(d, *position(vehicles[d])) for d in ids]  # type: ignore[misc]
    if heading_deg is None:
        heading_deg = _travel_heading(starts, center_lat, center_lon)
    low, high = policy.altitude_band(ids)
    plan = plan_formation(
        starts,
        formation,
        center_lat,
        center_lon,
        alt_m,
        spacing_m,
        heading_deg,
        fa.settings.min_separation_m,
        max_altitude_m=high,
        min_transit_alt_m=low,
    )
    contexts = {d: fa.context(v) for d, v in vehicles.items()}
    for slot in plan.slots:  # per drone first, so every refused drone is named
        try:
            policy.check_formation(
                {slot.drone_id: contexts[slot.drone_id]}, dataclasses.replace(plan, slots=[slot])
            )
        except SafetyRefusal as exc:
            unable.append(Unable.from_error(slot.drone_id, exc))
    if unable:
        raise refuse_fleet("formation_goto", unable, len(ids))
    policy.check_formation(contexts, plan)
    params = {
        "formation": formation,
        "center_lat": center_lat,
        "center_lon": center_lon,
        "alt_m": alt_m,
        "spacing_m": spacing_m,
        "heading_deg": round(plan.heading_deg, 1),
    }
    fop = await fleet_ops(fa).start(
        "formation_goto",
        ids,
        formation_phases(plan, vehicles, lambda v: fa.guard_takeoff(v, "formation_goto")),
        params,
        fa.session_key(),
        plan=plan.to_dict(),
        slots=slot_summaries(plan),
        notes=plan.notes,
    )
    return _fleet_out(fa, await _run(ctx, fa, fop, wait))


def _travel_heading(starts: list[DroneStart], lat: float, lon: float) -> float:
    """Bearing from the drones' centroid to the formation centre (0 when already there)."""
    c_lat = sum(s.lat for s in starts) / len(starts)
    c_lon = sum(s.lon for s in starts) / len(starts)
    if geo.horizontal_distance_m(c_lat, c_lon, lat, lon) < 1.0:
        return 0.0
    return round(geo.bearing_deg(c_lat, c_lon, lat, lon) % 360.0, 1)


# --- takeoff, land, return, hold ------------------------------------------------------------------------


@toolset.tool()
async def fleet_takeoff(
    fa: FleetAccess,
    ctx: Context,
    drone_ids: DroneIds,
    alt_m: Alt,
    stagger_m: Annotated[
        float | None, Field(ge=0, le=100, allow_inf_nan=False, description="m between drones' altitudes")
    ] = None,
    wait: Wait = True,
) -> FleetOut:
    """Take off drones at once to alt_m, alt_m+stagger, ... (given order). All must be able, or none go."""
    ids = check_drone_ids(drone_ids)
    policy = fa.safety
    _low, high = policy.altitude_band(ids)
    altitudes = takeoff_altitudes(ids, alt_m, _stagger(fa, stagger_m), high)
    await _initialised(fa, ids)

    def check(v: Any) -> None:
        v.require_ready()
        if value(v, "in_air"):
            raise InvalidArgument(f"{v.id} is already flying; use formation_goto or go_to_location")
        _busy(fa, v, "fleet_takeoff")
        policy.check_takeoff(fa.context(v), altitudes[v.id])

    vehicles, unable = collect_members(ids, fa.vehicle, check)
    if unable:
        raise refuse_fleet("fleet_takeoff", unable, len(ids))
    params = {"alt_m": alt_m, "altitudes_m": altitudes}
    fop = await fleet_ops(fa).start(
        "fleet_takeoff",
        ids,
        [takeoff_phase(vehicles, altitudes, lambda v: fa.guard_takeoff(v, "fleet_takeoff"))],
        params,
        fa.session_key(),
        slots={d: {"target_alt_m": a} for d, a in altitudes.items()},
    )
    return _fleet_out(fa, await _run(ctx, fa, fop, wait))


async def _initialised(fa: FleetAccess, ids: list[str]) -> None:
    """Drones still initialising (connected, waiting for a position estimate) are waited for (capped),
    all at once; whatever they are then is judged by the members' checks."""
    waits = []
    for drone_id in ids:
        with contextlib.suppress(GatewayError):
            waits.append(fa.vehicle(drone_id).wait_initialised())
    await asyncio.gather(*waits, return_exceptions=True)


def _recovery_members(
    fa: FleetAccess, drone_ids: list[str] | None, action: str, check: Any
) -> tuple[list[str], dict[str, Any], list[Unable]]:
    ids = _all_ids(fa, drone_ids)
    vehicles, unable = collect_members(ids, fa.vehicle, check)
    if not vehicles:
        raise refuse_fleet(action, unable, len(ids))
    return ids, vehicles, unable


@toolset.tool(idempotent=True)
async def fleet_land(
    fa: FleetAccess, ctx: Context, drone_ids: SomeDrones = None, wait: Wait = True
) -> FleetOut:
    """Land drones in place, all at once; done when disarmed. Those that cannot are listed in not_sent."""

    def check(v: Any) -> None:
        v.require_ready()
        if is_landed_and_disarmed(v):
            raise InvalidArgument(f"{v.id} is already on the ground and disarmed")
        fa.safety.check_actuation(fa.context(v))

    ids, vehicles, unable = _recovery_members(fa, drone_ids, "fleet_land", check)
    fop = await fleet_ops(fa).start(
        "fleet_land", list(vehicles), [land_phase(vehicles)], {"drone_ids": ids}, fa.session_key()
    )
    return _fleet_out(fa, await _run(ctx, fa, fop, wait), unable)


@toolset.tool(idempotent=True)
async def fleet_return_to_launch(
    fa: FleetAccess,
    ctx: Context,
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
    stagger = _stagger(fa, stagger_m)
    sep = fa.settings.min_separation_m
    if stagger < sep:
        raise SafetyRefusal(
            "min_separation",
            f"min_separation: return altitudes {stagger:g} m apart are closer than the minimum separation "
            f"of {sep:g} m",
            stagger_m=stagger,
            limit_m=sep,
        )

    def check(v: Any) -> None:
        v.require_ready()
        fa.require_airborne(v, "fleet_return_to_launch")
        if position(v) is None:
            raise VehicleNotReady(f"no position received from {v.id} yet")
        fa.safety.check_actuation(fa.context(v))
        fa.safety.check_param_write(v.return_altitude_param()[0], vehicle_id=v.id)

    ids, vehicles, unable = _recovery_members(fa, drone_ids, "fleet_return_to_launch", check)
    positions = {d: position(v) for d, v in vehicles.items()}
    homes = {d: (h[0], h[1]) for d, v in vehicles.items() if (h := home(v)) is not None}
    order, notes = rtl_order(positions, homes, sep)  # type: ignore[arg-type]
    base = rtl_alt_m if rtl_alt_m is not None else default_rtl_base_m(positions.values())  # type: ignore[arg-type]
    _low, high = fa.safety.altitude_band(order)
    try:
        altitudes = rtl_altitudes(order, base, stagger, high)
    except SafetyRefusal:
        if stagger_m is not None or stagger <= sep:
            raise
        # many drones: the default margin does not fit under the limit; the separation itself may
        altitudes = rtl_altitudes(order, base, sep, high)
        notes.append(f"return altitudes {sep:g} m apart (the minimum separation): {stagger:g} m did not fit")
    params = {"drone_ids": ids, "rtl_altitudes_m": altitudes}
    fop = await fleet_ops(fa).start(
        "fleet_return_to_launch",
        order,
        rtl_phases(vehicles, altitudes, positions, set_rtl_altitude_param),  # type: ignore[arg-type]
        params,
        fa.session_key(),
        slots={d: {"rtl_alt_m": a} for d, a in altitudes.items()},
        notes=notes,
    )
    return _fleet_out(fa, await _run(ctx, fa, fop, wait), unable)


@toolset.tool(idempotent=True)
async def fleet_hold(fa: FleetAccess, ctx: Context, drone_ids: SomeDrones = None) -> FleetHoldOut:
    """Stop drones where they are (GUIDED hover), ending their actions. Those that cannot: not_sent."""

    def check(v: Any) -> None:
        v.require_ready()
        fa.require_airborne(v, "fleet_hold")
        fa.safety.check_actuation(fa.context(v))

    _ids, vehicles, unable = _recovery_members(fa, drone_ids, "fleet_hold", check)
    superseded = await fleet_ops(fa).supersede(vehicles, "fleet_hold")
    failed: list[dict[str, Any]] = []

    async def hold(drone_id: str, v: Any) -> None:
        try:
            await v.hold()
            await fa.operations.supersede(drone_id, "fleet_hold")
        except GatewayError as exc:
            failed.append({"drone_id": drone_id, "code": exc.code, "message": exc.message})

    await asyncio.gather(*(hold(d, v) for d, v in vehicles.items()))
    held = [d for d in vehicles if d not in {f["drone_id"] for f in failed}]
    text = f"holding: {', '.join(held) or 'none'}"
    if failed:
        text += "; failed: " + "; ".join(f"{f['drone_id']}: {f['message']}" for f in failed)
    if unable:
        text += "; not sent: " + "; ".join(f"{u.drone_id}: {u.message}" for u in unable)
    return FleetHoldOut(
        held=held,
        failed=failed,
        not_sent=[u.to_dict() for u in unable],
        superseded_fleet_operations=[f.id for f in superseded],
    ).say(text)


# --- fleet://formation ------------------------------------------------------------------------------


def formation_json(fa: FleetAccess) -> dict[str, Any]:
    """The last formation: its plan and progress (per drone), or a note that none was flown."""
    fop = fleet_ops(fa).latest("formation_goto")
    if fop is None:
        return {"formation": None, "message": "no formation flown yet"}
    return {**fop.to_dict(), "plan": fop.plan}


def register_resources(server: MCPServer, fa: FleetAccess) -> None:
    """fleet://formation, with an update notification when a formation changes phase or a drone's
    outcome changes (not on every progress tick)."""

    @server.resource(FORMATION_URI, mime_type="application/json", description="Last formation: plan+progress")
    def fleet_formation() -> str:
        return json.dumps(formation_json(fa), default=str)

    pending: set[asyncio.Task[None]] = set()  # keeps the notification tasks alive until they ran

    def on_change(fop: FleetOperation) -> None:
        if fop.kind == "formation_goto":
            task = asyncio.get_running_loop().create_task(_publish(server, FORMATION_URI))
            pending.add(task)
            task.add_done_callback(pending.discard)

    fleet_ops(fa).listeners.append(on_change)


async def _publish(server: MCPServer, uri: str) -> None:
    try:
        await server._subscriptions.publish(ResourceUpdated(uri=uri))  # type: ignore[attr-defined]
        notifier = getattr(server, "resource_notifier", None)
        for session in list(getattr(notifier, "legacy", {}).get(uri, ())):
            try:
                await session.send_resource_updated(uri)
            except Exception:
                notifier.legacy[uri].discard(session)  # type: ignore[union-attr]
    except Exception:  # a notification must never break a flight
        log.exception("could not publish %s", uri)


toolset.register_resources = register_resources  # type: ignore[attr-defined]
