"""A mission is verified when it starts: every way to start or resume one (initiate_mission,
resume_mission, set_current_waypoint, set_flight_mode into the mission mode, the REST route) reads back
the mission the autopilot holds now and checks it against the limits and zones in force now, from where
the drone is now (`verify_held`). Nothing checked at upload is trusted: another ground station may have
replaced the mission, the drone may have flown elsewhere, an operator may have added a zone.
"""

from __future__ import annotations

from collections.abc import Iterable

from gateway.errors import InvalidArgument
from gateway.fleet.dialects import dialect_named
from gateway.fleet.missions import mission_files
from gateway.fleet.missions.mission import MissionItem
from gateway.fleet.policy.caller import Caller
from gateway.fleet.policy.mission_check import MissionSemantics, Unchecked
from gateway.fleet.policy.safety import SafetyPolicy
from gateway.fleet.policy.safety_inputs import VehicleContext
from gateway.fleet.vehicles.protocols import FlyingVehicle, VehicleView
from gateway.fleet.vehicles.readings import value


def semantics_of(vehicle: VehicleView) -> MissionSemantics:
    """The mission commands the drone's autopilot dialect models."""
    return dialect_named(vehicle.autopilot).mission_semantics


def resume_item(vehicle: VehicleView) -> int | None:
    """The item (1..N) the autopilot continues from when its mission mode is selected in the air."""
    prog = value(vehicle.telemetry.mission_progress)
    current = int(prog.current) if prog is not None else 0
    return current if current >= 1 else None


async def held_mission(vehicle: FlyingVehicle, ctx: VehicleContext) -> list[MissionItem]:
    """The mission the autopilot holds now (read back), as the policy reads it."""
    semantics = semantics_of(vehicle)
    held = await vehicle.download_mission()
    if not held:
        raise InvalidArgument(
            f"{ctx.vehicle_id} holds no mission; give waypoints to initiate_mission or upload_mission first"
        )
    return mission_files.held_items(
        held, ctx.home, ctx.position, zero_is_here=semantics.zero_position_is_here
    )


async def verify_held(
    safety: SafetyPolicy,
    caller: Caller,
    vehicle: FlyingVehicle,
    ctx: VehicleContext,
    starts: Iterable[int | None] = (1,),
) -> tuple[list[MissionItem], list[Unchecked]]:
    """Read the held mission back and check it whole: every item, every leg, and the leg from the drone
    to each item it may start from (``starts``). Refuses (nothing starts) with the item's number and
    the rule; returns the items and, for an operator, the items the gateway could not check."""
    items = await held_mission(vehicle, ctx)
    first = {k for k in starts if k is not None and 1 <= k <= len(items)} or {1}
    unchecked = safety.check_mission(ctx, items, caller.policy_via, semantics_of(vehicle), first)
    return items, unchecked


def unchecked_text(unchecked: list[Unchecked]) -> str:
    """How an operator's unchecked mission is marked (message, audit, operation parameters)."""
    return "unchecked by the gateway: " + "; ".join(u.text() for u in unchecked)
