"""The Commander: the one path every command takes, whichever door it came through.

Every verb (takeoff, goto, land, hold, mission start, formation, fleet stop...) does the same five
things, in this order, here and nowhere else:

1. resolve the drone (UnknownVehicle names the known ids; VehicleNotReady names the state and why);
2. build one `VehicleContext` from fresh telemetry (`gateway.fleet.readings.vehicle_context`);
3. run the safety policy on it, judged by who asked (`Caller.via`: operators are not held by locks
   or the simulators-only switch, may kill in flight and interrupt a takeoff; agents are);
4. start a tracked operation under the drone's command lock (`OperationManager.start`: the takeoff
   guard runs inside the lock, so a goto racing a takeoff that is still being sent is refused), or
   send an instant command;
5. return a result model (`gateway.fleet.views`): an `OperationView` to wait on, or an `ActionResult`.

MCP tools (`gateway.mcp.tools`) and REST routes (`gateway.api`) are one call to a verb plus presenting
its result; they hold no checks of their own.

The cluster seam
----------------
Every verb can also be called by name with JSON-serialisable arguments::

    result = await commander.call("goto", caller, drone_id="alpha", lat_deg=47.39, lon_deg=8.54,
                                  alt_m=20)          # -> a JSON-serialisable dict
    final = await commander.wait(result["operation_id"], cap_s=45, on_progress=report)

``VERBS`` below is the explicit table of verb names; each verb's arguments are
the keyword parameters of its method after ``caller`` (validated by a pydantic model built from the
signature, so a forwarded call is checked exactly as a local one), and its result is the method's
result model dumped to JSON. Waiting is a separate step (`wait`, `wait_fleet`), so a node that does not
own a drone can forward the call to the owner (NATS request/reply) and then forward the wait, with
progress, the same way. Callbacks (progress, "still initialising" notices) are never part of a verb's
arguments.
"""

from __future__ import annotations

from typing import Any

from gateway.errors import InvalidArgument
from gateway.fleet.caller import Caller
from gateway.fleet.fleet_verbs import FleetVerbs
from gateway.fleet.ids import canonical_arguments, canonical_drone_id
from gateway.fleet.protocols import Notify
from gateway.fleet.routing import Verb


class Commander(FleetVerbs):
    """Every command on one drone or on the fleet, for every door. Built once by `gateway.runtime`."""

    def canonical_id(self, drone_id: str) -> str:
        """The registered id ``drone_id`` names ignoring case (`gateway.fleet.ids`): doors call this
        before a verb, since operations and locks are keyed by the exact id."""
        return canonical_drone_id(self.registry, drone_id)

    async def call(
        self, verb: str, caller: Caller, /, *, notify: Notify | None = None, **arguments: Any
    ) -> dict[str, Any]:
        """Run ``verb`` with JSON-serialisable ``arguments``; the result as JSON-serialisable data.
        Unknown verbs and bad arguments raise InvalidArgument naming them; nothing is sent then.
        ``notify`` hears what a verb waits for before it can send (arm, takeoff). Drone ids are made
        canonical first ('Alpha' is alpha)."""
        entry = VERBS.get(verb)
        if entry is None:
            raise InvalidArgument(f"unknown verb {verb!r}; verbs: {', '.join(sorted(VERBS))}")
        parsed = entry.parse(canonical_arguments(self.registry, arguments))
        if notify is not None and "notify" in entry.callbacks:
            parsed["notify"] = notify
        result = await entry.method(self, caller, **parsed)
        return result.model_dump(mode="json")


#: The verbs every door (and a forwarding cluster node) may call by name.
VERBS: dict[str, Verb] = {
    # flight
    "arm": Verb(Commander.arm),
    "disarm": Verb(Commander.disarm),
    "takeoff": Verb(Commander.takeoff),
    "land": Verb(Commander.land),
    "return_to_launch": Verb(Commander.return_to_launch),
    "hold": Verb(Commander.hold),
    "kill": Verb(Commander.kill),
    "set_mode": Verb(Commander.set_mode),
    # navigation
    "goto": Verb(Commander.goto),
    "reposition": Verb(Commander.reposition),
    "move_relative": Verb(Commander.move_relative),
    "set_yaw": Verb(Commander.set_yaw),
    "set_speed": Verb(Commander.set_speed),
    "arrival": Verb(Commander.arrival),
    # missions
    "upload_mission": Verb(Commander.upload_mission),
    "upload_mission_file": Verb(Commander.upload_mission_file),
    "export_mission": Verb(Commander.export_mission),
    "download_mission": Verb(Commander.download_mission),
    "clear_mission": Verb(Commander.clear_mission),
    "start_mission": Verb(Commander.start_mission),
    "pause_mission": Verb(Commander.pause_mission),
    "resume_mission": Verb(Commander.resume_mission),
    "set_current_item": Verb(Commander.set_current_item),
    "mission_progress": Verb(Commander.mission_progress),
    # parameters
    "get_param": Verb(Commander.get_param),
    "set_param": Verb(Commander.set_param),
    "list_params": Verb(Commander.list_params),
    # the fleet
    "formation_goto": Verb(Commander.formation_goto),
    "fleet_takeoff": Verb(Commander.fleet_takeoff),
    "fleet_land": Verb(Commander.fleet_land),
    "fleet_return_to_launch": Verb(Commander.fleet_return_to_launch),
    "fleet_hold": Verb(Commander.fleet_hold),
    "stop_all": Verb(Commander.stop_all),
    "lock": Verb(Commander.lock),
    "unlock": Verb(Commander.unlock),
    "release": Verb(Commander.release),
}
