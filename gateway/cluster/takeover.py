"""What a node does with the operations of a vehicle it has just taken over from a lost node.

The lost node could not record how its running operations ended. The new owner reads them from the
database: the newest one it can follow again (takeoff, goto-like moves, land, RTL, yaw, mission) it
tracks from its own telemetry under the same operation id, saying so in its message; any other is
recorded as interrupted with what happened. Either way a client that asks (monitor_flight,
get_operation, the audit) reads the truth.

A row the previous owner kept while the database was down (its spool) may reach the database after the
new owner read what was running: at each tick the owner also picks up the running operations of the
drones it holds that it does not follow (`pick_up_late_operations`), so no row stays running with nobody
following or closing it.
"""

from __future__ import annotations

import logging
from collections.abc import Mapping

from gateway.cluster.runtime_view import NodeRuntime
from gateway.fleet.operations.fleet_steps import FORMATION_TOLERANCE_M
from gateway.fleet.operations.operation_state import OpStatus
from gateway.fleet.operations.trackers import (
    GotoTracker,
    LandingTracker,
    MissionTracker,
    TakeoffTracker,
    Tracker,
    YawTracker,
)
from gateway.fleet.vehicles.protocols import FlyingVehicle
from gateway.fleet.vehicles.registry import Registry
from gateway.fleet.vehicles.vehicle import Vehicle
from gateway.registry.records import OperationRecord, utcnow
from gateway.util.json_types import JsonObject, json_float

log = logging.getLogger("gateway.cluster.takeover")

#: operations of fleet formations are held to the formation's tolerance, single gotos to the setting
FORMATION_KINDS = frozenset({"formation", "fleet_climb"})
#: running rows read at a tick to find those nobody follows (a node holds a few hundred drones at most)
LATE_LIMIT = 2000


def tracker_for(kind: str, params: JsonObject, arrival_tolerance_m: float) -> Tracker | None:
    """A tracker that follows an operation of ``kind`` again from its stored params, or None."""
    try:
        if kind == "takeoff":
            # a takeoff is an operation once the drone took the command, armed: disarmed now, it ended
            # (else a drone found on the ground, disarmed, would be "still taking off" for ever)
            return TakeoffTracker(json_float(params["alt_m"], "alt_m"), _seen_armed=True)
        if params.get("takeoff_first"):
            # a relative move that took off first: whether its leg was sent before the node was lost is
            # not recorded, so it is closed as interrupted (the message says to check the drone) rather
            # than followed as a goto that may never have been sent
            return None
        if kind in ("land", "return_to_launch"):
            return LandingTracker(kind=kind)
        if kind == "set_yaw":
            return YawTracker(json_float(params["heading_deg"], "heading_deg"))
        if kind == "mission":
            return MissionTracker()
        if {"lat_deg", "lon_deg", "alt_m"} <= set(params):
            tolerance = FORMATION_TOLERANCE_M if kind in FORMATION_KINDS else arrival_tolerance_m
            lat, lon, alt = (json_float(params[key], key) for key in ("lat_deg", "lon_deg", "alt_m"))
            return GotoTracker(lat, lon, alt, tolerance, kind=kind)
    except (KeyError, TypeError, ValueError):
        return None
    return None


async def pick_up_operations(
    gateway: NodeRuntime, node_id: str, vehicle: FlyingVehicle, epoch: int, previous: str | None
) -> int:
    """Resume or close the running operations the previous owner left in the database; how many."""
    store = gateway.store
    if store is None:
        return 0
    records = await store.list_operations(vehicle_id=vehicle.id, status="running", limit=20)
    return await _pick_up(gateway, node_id, vehicle, epoch, previous, records)


async def pick_up_late(
    gateway: NodeRuntime, node_id: str, registry: Registry, epochs: Mapping[str, int]
) -> None:
    """At a lease tick: `pick_up_late_operations` for the drones of ``epochs`` (id -> lease epoch) whose
    link runs in this process; a failure is logged, and tried again at the next tick."""
    held = [(vid, epoch) for vid, epoch in epochs.items() if registry.is_local(vid)]
    vehicles = {vid: (found, epoch) for vid, epoch in held if isinstance(found := registry.get(vid), Vehicle)}
    try:
        await pick_up_late_operations(gateway, node_id, vehicles)
    except Exception as exc:
        log.warning("looking for operations nobody follows failed: %r", exc)


async def pick_up_late_operations(
    gateway: NodeRuntime, node_id: str, vehicles: Mapping[str, tuple[FlyingVehicle, int]]
) -> int:
    """Resume or close the running operations of the drones this node holds (``vehicles``: each with its
    lease epoch) that it does not follow: rows a previous owner kept while the database was down and
    wrote after this node had taken the drone over (and read what was running then). Without this they
    would stay running with nobody following or closing them. How many."""
    store = gateway.store
    if store is None or not vehicles:
        return 0
    ops = gateway.operations
    found: dict[str, list[OperationRecord]] = {}
    for record in await store.list_operations(status="running", limit=LATE_LIMIT):
        if record.vehicle_id not in vehicles:
            continue
        if (
            ops is None
            or not ops.knows(record.id)
            or await ops.settle_running_row(record.id, vehicles[record.vehicle_id][0])
        ):
            found.setdefault(record.vehicle_id, []).append(record)
    count = 0
    for vehicle_id, records in found.items():
        vehicle, epoch = vehicles[vehicle_id]
        log.warning("%s: %d operation(s) written as running after this node took it over: %s",
                    vehicle_id, len(records), ", ".join(r.id for r in records))  # fmt: skip
        count += await _pick_up(gateway, node_id, vehicle, epoch, None, records)
    return count


async def _pick_up(
    gateway: NodeRuntime,
    node_id: str,
    vehicle: FlyingVehicle,
    epoch: int,
    previous: str | None,
    records: list[OperationRecord],
) -> int:
    """Resume the newest of ``records`` (running rows, newest first) when it can be followed and this
    node runs nothing newer on the drone; record every other one as interrupted."""
    store = gateway.require_store()
    ops = gateway.operations
    records = [r for r in records if ops is None or not ops.knows(r.id)]
    mine = None if ops is None else ops.latest(vehicle.id)
    lost = f"node {previous} was lost" if previous and previous != node_id else "its node gave the drone up"
    for index, record in enumerate(records):  # newest first
        tracker = tracker_for(record.kind, record.params, gateway.settings.arrival_tolerance_m)
        newer_here = mine is not None and (not mine.finished or mine.created_at >= record.created_at)
        if index == 0 and ops is not None and tracker is not None and not newer_here:
            note = (
                f"{lost} while this {record.kind} ran; node {node_id} took {vehicle.id} over "
                f"(lease epoch {epoch}) and has tracked it since"
            )
            await ops.resume(record, vehicle, tracker, note)
            log.warning("%s: resumed %s %s after taking the drone over", vehicle.id, record.kind, record.id)
            continue
        now = utcnow()
        why = "a newer operation was running" if index or newer_here else "it cannot be followed again"
        message = (
            f"{lost} while this {record.kind} ran; node {node_id} took {vehicle.id} over and "
            f"stopped tracking it ({why}); the drone keeps flying its last command on its own: "
            "check get_telemetry before the next command"
        )
        await store.save_operation(
            record.model_copy(
                update={
                    "status": OpStatus.interrupted.value,
                    "message": message,
                    "updated_at": now,
                    "finished_at": now,
                }
            )
        )
    return len(records)
