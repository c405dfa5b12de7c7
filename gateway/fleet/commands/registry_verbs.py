"""The operator's registrations: add, change, remove, connect and disconnect drones, and move a drone's
origin (where its distance limit and zones count from, `gateway.fleet.policy.origin`).

Each is a declared verb (callable by name; REST and the CLI, through REST, call it) over the registry
the runtime built (`VehicleRegistry`): it persists the change and starts or stops the sidecar. Only
operators change registrations. A registration's verb answers with the registration as stored.
"""

from __future__ import annotations

from collections.abc import Mapping

from pydantic import TypeAdapter, ValidationError

from gateway.errors import GatewayError, InvalidArgument, UnknownVehicle
from gateway.fleet.commands.command_core import OperationDesk, command, routed
from gateway.fleet.commands.command_pass import CommandPass
from gateway.fleet.commands.routes import OriginIn, Route
from gateway.fleet.commands.verb_rules import operator_only
from gateway.fleet.policy.caller import Caller
from gateway.fleet.policy.origin import OriginView, origin_view
from gateway.fleet.vehicles.protocols import VehicleRegistry
from gateway.fleet.vehicles.readings import home
from gateway.registry.records import VehicleRecord
from gateway.registry.spec import VehicleChanges, VehicleSpec
from gateway.registry.store import Store

#: what a registration's change may name (`VehicleRegistry.update`)
CHANGEABLE = ("url", "name", "tags", "expected_sysid", "node_tag", "gcs_endpoints", "auto_connect")


_CHANGES = TypeAdapter(VehicleChanges)


def _typed_changes(changes: Mapping[str, object]) -> VehicleChanges:
    """``changes`` (names already checked against `CHANGEABLE`) with their values' types checked."""
    try:
        return _CHANGES.validate_python(dict(changes))
    except ValidationError as exc:
        first = exc.errors()[0]
        where = ".".join(str(part) for part in first["loc"])
        raise InvalidArgument(f"changes.{where}: {first['msg']} (given {first.get('input')!r})") from None


class RegistryVerbs:
    """Registrations and origins; ``registrations`` is the registry itself (the other parts see it
    through the agents' scopes), None where the Commander runs without one (nothing can be registered)."""

    def __init__(
        self,
        commands: CommandPass,
        desk: OperationDesk,
        registrations: VehicleRegistry | None,
        store: Store | None,
    ) -> None:
        self.commands = commands
        self.desk = desk
        self._registrations = registrations
        self._store = store

    def _registry(self) -> VehicleRegistry:
        if self._registrations is None:
            raise GatewayError("this gateway runs without a registry of its own: nothing can be registered")
        return self._registrations

    async def _record(self, drone_id: str) -> VehicleRecord:
        """The stored registration; UnknownVehicle names the registered ids."""
        if self._store is None:
            raise GatewayError("this gateway runs without a database: registrations are not kept")
        record = await self._store.get_vehicle(drone_id)
        if record is None:
            raise UnknownVehicle(drone_id[:64], [v.id for v in await self._store.list_vehicles()])
        return record

    @command
    async def register_drone(self, caller: Caller, spec: VehicleSpec, connect: bool = True) -> VehicleRecord:
        """Register (store) a drone and, with ``connect``, start its sidecar now and at every start."""
        operator_only(caller, "register drones")
        await self._registry().add(spec, connect=connect)
        return await self._record(spec.id)

    @command
    async def update_drone(
        self, caller: Caller, drone_id: str, changes: Mapping[str, object]
    ) -> VehicleRecord:
        """Change a registration (``changes``: some of `CHANGEABLE`; a new URL or new ground station
        endpoints reconnect a connected drone)."""
        operator_only(caller, "change registrations")
        if not changes:
            raise InvalidArgument(f"nothing to update: give at least one of {', '.join(CHANGEABLE)}")
        unknown = sorted(set(changes) - set(CHANGEABLE))
        if unknown:
            raise InvalidArgument(
                f"changes: {', '.join(unknown)} cannot be changed; changeable: {', '.join(CHANGEABLE)}"
            )
        typed = _typed_changes(changes)
        await self._record(drone_id)
        await self._registry().update(drone_id, **typed)
        return await self._record(drone_id)

    @command
    async def remove_drone(self, caller: Caller, drone_id: str) -> VehicleRecord:
        """Remove a registration (its sidecar stopped first); the answer is the registration removed."""
        operator_only(caller, "remove drones")
        record = await self._record(drone_id)
        await self._registry().remove(drone_id)
        return record

    @command
    async def connect_drone(self, caller: Caller, drone_id: str) -> VehicleRecord:
        """Start the drone's sidecar (now and at every start)."""
        operator_only(caller, "connect drones")
        return await self._switched(drone_id, connected=True)

    @command
    async def disconnect_drone(self, caller: Caller, drone_id: str) -> VehicleRecord:
        """Stop the drone's sidecar (and no longer connect it at start)."""
        operator_only(caller, "disconnect drones")
        return await self._switched(drone_id, connected=False)

    async def _switched(self, drone_id: str, *, connected: bool) -> VehicleRecord:
        """The registration after a registered drone was connected or disconnected."""
        await self._record(drone_id)
        registry = self._registry()
        await (registry.connect(drone_id) if connected else registry.disconnect(drone_id))
        return await self._record(drone_id)

    @command(
        route=Route(
            "origin", "Move a drone's origin (operator)", method="PUT", name="put_origin", body=OriginIn
        )
    )
    @routed
    async def move_origin(
        self, caller: Caller, drone_id: str, lat: float, lon: float, alt_amsl_m: float
    ) -> OriginView:
        """Move the point the drone's distance limit and zones count from (checked, stored; on the node
        that flies it)."""
        operator_only(caller, "move a drone's origin")
        moved = await self._registry().move_origin(drone_id, lat, lon, alt_amsl_m, caller.principal)
        return origin_view(drone_id, moved, home(self.commands.registry.get(drone_id)))
