"""The Commander: the one path every command takes, whichever door it came through.

It is composed of parts, each with one job:

- `CommandPass` (`gateway.fleet.commands.command_pass`): the one pass every command on one drone takes, here
and
  nowhere else: the takeover lock, resolve the drone once, one `VehicleContext` from fresh telemetry,
  the policy judged by who asked (`Caller.via`: operators are not held by locks or the simulators-only
  switch, may kill in flight and interrupt a takeoff; agents are), the drone's command lock (the takeoff
  guard inside it), the send, the tracked operation, the audit row at send;
- `FlightVerbs`, `NavigationVerbs`, `MissionVerbs` (`gateway.fleet.commands.drone_verbs`, `navigation_verbs`,
  `mission_verbs`): each command on one drone, declared once (its arguments, checks, vehicle call and
  tracker) and run through the pass;
- `FleetVerbs` (`gateway.fleet.commands.fleet_verbs`): the fleet commands, fleet-level checks and plans
  composed of the same pass per drone, each drone's step run by `FleetStepVerbs`
  (`gateway.fleet.commands.fleet_step_verbs`);
- `OperatorVerbs`, `ZoneVerbs`, `RegistryVerbs` (`operator_verbs`, `zone_verbs`, `registry_verbs`): the
  operator's locks and stop, geofence zones and ``.plan`` files, registrations and origins;
- `OperationDesk` (`gateway.fleet.commands.command_core`): views of operations and waiting on them.

MCP tools (`gateway.mcp.tools`) and REST routes (`gateway.api`) are one call to a verb plus presenting
its result; they hold no checks of their own.

The cluster seam
----------------
Every verb can also be called by name with JSON-serialisable arguments::

    result = await commander.call("goto", caller, drone_id="alpha", lat_deg=47.39, lon_deg=8.54,
                                  alt_m=20)          # -> a JSON-serialisable dict
    final = await commander.wait(result["operation_id"], cap_s=45, on_progress=report)

``VERBS`` is filled by each verb's ``@command`` declaration; a verb's arguments are the keyword
parameters of its method after ``caller`` (validated by a pydantic model built from the signature, so a
forwarded call is checked exactly as a local one), and its result is the method's result model dumped
to JSON. Waiting is a separate step (`wait`, `wait_fleet`), so a node that does not own a drone can
forward the call to the owner (NATS request/reply) and then forward the wait, with progress, the same
way. Callbacks (progress, "still initialising" notices) are never part of a verb's arguments.
"""

from __future__ import annotations

from pydantic import BaseModel

from gateway.config import Settings
from gateway.errors import InvalidArgument
from gateway.fleet.commands.command_core import VERBS, OperationDesk
from gateway.fleet.commands.command_pass import CommandPass
from gateway.fleet.commands.drone_verbs import FlightVerbs
from gateway.fleet.commands.fleet_step_verbs import FleetStepVerbs
from gateway.fleet.commands.fleet_verbs import FleetVerbs
from gateway.fleet.commands.mission_verbs import MissionVerbs
from gateway.fleet.commands.navigation_verbs import NavigationVerbs
from gateway.fleet.commands.operator_verbs import OperatorVerbs
from gateway.fleet.commands.registry_verbs import RegistryVerbs
from gateway.fleet.commands.zone_verbs import ZoneVerbs
from gateway.fleet.operations.fleet_ops import FleetOperations
from gateway.fleet.operations.operations import OperationManager
from gateway.fleet.operations.routing import Router
from gateway.fleet.policy.caller import Caller
from gateway.fleet.policy.operator_locks import LockBook
from gateway.fleet.policy.safety import SafetyPolicy
from gateway.fleet.policy.zones import Zones
from gateway.fleet.vehicles.ids import canonical_arguments, canonical_drone_id
from gateway.fleet.vehicles.protocols import (
    FlyingVehicle,
    Notify,
    VehicleDirectory,
    VehicleRegistry,
    VehicleView,
)
from gateway.registry.store import Store
from gateway.util.json_types import JsonObject
from gateway.util.read_through import ReadThrough


class Commander:
    """Every command on one drone or on the fleet, for every door. Built once by `gateway.runtime`.

    Composed, not inherited: the pass (`CommandPass`), the operation desk (views and waits), the verbs
    on one drone (flight, navigation, missions) and on the fleet; the verbs are its attributes, so a
    door calls ``commander.goto(...)`` and a name calls ``commander.call("goto", ...)``."""

    # the pass's collaborators, read of it
    settings = ReadThrough[Settings]("commands")
    registry = ReadThrough[VehicleDirectory]("commands")
    operations = ReadThrough[OperationManager]("commands")
    safety = ReadThrough[SafetyPolicy]("commands")
    locks = ReadThrough[LockBook]("commands")
    router = ReadThrough[Router | None]("commands")

    def __init__(
        self,
        settings: Settings,
        registry: VehicleDirectory,
        store: Store | None,
        operations: OperationManager,
        fleet: FleetOperations,
        safety: SafetyPolicy,
        locks: LockBook,
        router: Router | None = None,
        registrations: VehicleRegistry | None = None,
    ) -> None:
        """``router``: on a cluster node, where the drones this node does not own are run;
        ``registrations``: the registry itself, for the operator's registrations (``registry`` is what
        the verbs see of it: the agents' scopes)."""
        self.store = store
        self.fleet = fleet
        self.commands = CommandPass(settings, registry, operations, safety, locks, router)
        self.desk = desk = OperationDesk(self.commands, store)
        self.flight = flight = FlightVerbs(self.commands, desk)
        self.navigation = navigation = NavigationVerbs(self.commands, desk)
        self.missions = missions = MissionVerbs(self.commands, desk, flight)
        self.fleet_steps = fleet_steps = FleetStepVerbs(self.commands, desk, fleet)
        self.fleet_verbs = fleet_verbs = FleetVerbs(self.commands, desk, flight, fleet, fleet_steps)
        self.operator = operator = OperatorVerbs(self.commands, flight, fleet, store)
        self.zones = zones = ZoneVerbs(self.commands, Zones(safety, settings.geofence_file), missions, store)
        self.registrations = registrations_ = RegistryVerbs(self.commands, desk, registrations, store)
        #: where a verb called by name runs (`gateway.fleet.commands.command_core.command`), by class name
        self.parts: dict[str, object] = {
            type(part).__name__: part
            for part in (
                flight,
                navigation,
                missions,
                fleet_verbs,
                fleet_steps,
                operator,
                zones,
                registrations_,
            )
        }
        # the verbs as the doors call them (typed); a verb called only by name needs no line here
        # operations
        self.view = desk.view
        self.operation = desk.operation
        self.current_operation = desk.current_operation
        self.latest_operation = desk.latest_operation
        self.wait = desk.wait
        # one drone: flight
        self.arm = flight.arm
        self.disarm = flight.disarm
        self.takeoff = flight.takeoff
        self.land = flight.land
        self.return_to_launch = flight.return_to_launch
        self.hold = flight.hold
        self.kill = flight.kill
        self.kill_needs_confirmation = flight.kill_needs_confirmation
        self.set_mode = flight.set_mode
        # one drone: navigation
        self.goto = navigation.goto
        self.reposition = navigation.reposition
        self.move_relative = navigation.move_relative
        self.set_yaw = navigation.set_yaw
        self.set_speed = navigation.set_speed
        self.arrival = navigation.arrival
        self.monitor = navigation.monitor
        # one drone: missions and parameters
        self.upload_mission = missions.upload_mission
        self.upload_mission_file = missions.upload_mission_file
        self.export_mission = missions.export_mission
        self.download_mission = missions.download_mission
        self.clear_mission = missions.clear_mission
        self.start_mission = missions.start_mission
        self.pause_mission = missions.pause_mission
        self.resume_mission = missions.resume_mission
        self.set_current_item = missions.set_current_item
        self.mission_progress = missions.mission_progress
        self.get_param = missions.get_param
        self.set_param = missions.set_param
        self.list_params = missions.list_params
        # the fleet
        self.fleet_view = fleet_verbs.fleet_view
        self.fleet_operation = fleet_verbs.fleet_operation
        self.wait_fleet = fleet_verbs.wait_fleet
        self.formation_goto = fleet_verbs.formation_goto
        self.fleet_takeoff = fleet_verbs.fleet_takeoff
        self.fleet_land = fleet_verbs.fleet_land
        self.fleet_return_to_launch = fleet_verbs.fleet_return_to_launch
        self.fleet_hold = fleet_verbs.fleet_hold
        self.run_step = fleet_steps.run_step
        self.hold_step = fleet_steps.hold_step
        self.lock = operator.lock
        self.unlock = operator.unlock
        self.taken_over = operator.taken_over
        self.release = operator.release
        self.stop_all = operator.stop_all
        self.stop_one = operator.stop_one
        # zones and .plan files
        self.geofences = zones.geofences
        self.set_geofences = zones.set_geofences
        self.upload_plan = zones.upload_plan
        self.export_plan = zones.export_plan
        # registrations
        self.register_drone = registrations_.register_drone
        self.update_drone = registrations_.update_drone
        self.remove_drone = registrations_.remove_drone
        self.connect_drone = registrations_.connect_drone
        self.disconnect_drone = registrations_.disconnect_drone
        self.move_origin = registrations_.move_origin

    def vehicle(self, drone_id: str) -> VehicleView:
        """The registered drone, in whatever state (for reads); UnknownVehicle lists the known ids."""
        return self.registry.get(drone_id)

    def ready(self, drone_id: str) -> FlyingVehicle:
        """The drone flown here, if it can fly (VehicleNotReady names its state and why otherwise)."""
        vehicle = self.registry.flown(drone_id)
        vehicle.require_ready()
        return vehicle

    def canonical_id(self, drone_id: str) -> str:
        """The registered id ``drone_id`` names ignoring case (`gateway.fleet.vehicles.ids`): doors call this
        before a verb, since operations and locks are keyed by the exact id."""
        return canonical_drone_id(self.registry, drone_id)

    async def call(
        self, verb: str, caller: Caller, /, *, notify: Notify | None = None, **arguments: object
    ) -> JsonObject:
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
        result: BaseModel = await entry.method(self, caller, **parsed)
        return result.model_dump(mode="json")


__all__ = ["VERBS", "Commander"]
