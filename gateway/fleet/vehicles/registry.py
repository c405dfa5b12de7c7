"""The Registry: which vehicles exist (persisted through the Store) and their live Vehicle objects.

    store = await Store.open(settings.database_url)
    registry = Registry(settings, store)
    await registry.start()                      # restore registrations, connect the auto_connect ones
    v = await registry.add(VehicleSpec(id="alpha", url="tcpout://127.0.0.1:5760", expected_sysid=1))
    await v.wait_for_state("ready", within_s=60)
    await v.takeoff(10)                         # returns once accepted; poll v.telemetry for progress
    ...
    await registry.stop()                       # no mavsdk_server process remains

Each Vehicle owns one mavsdk_server sidecar (gateway.link.sidecar), its telemetry cache
(gateway.link.telemetry) and its flight recorder (gateway.fleet.missions.flightlog).
"""

from __future__ import annotations

import asyncio
import logging
from collections.abc import Awaitable, Callable, Iterable, Mapping
from typing import Protocol, Unpack

from pydantic import ValidationError

from gateway.config import Settings
from gateway.errors import InvalidArgument, UnknownVehicle
from gateway.fleet.policy.origin import Origin
from gateway.fleet.vehicles.protocols import FlyingVehicle, VehicleView, flying
from gateway.fleet.vehicles.vehicle import ConnectionState, Vehicle
from gateway.link.sidecar import Confine
from gateway.registry.records import VehicleRecord
from gateway.registry.spec import VehicleChanges, VehicleSpec, gcs_endpoint_conflict
from gateway.registry.store import Store

log = logging.getLogger("gateway.registry")

SPEC_FIELDS = set(VehicleSpec.model_fields)

StateListener = Callable[[Vehicle, ConnectionState, ConnectionState], None]


class RegisteredVehicle(VehicleView, Protocol):
    """What the registry holds: a `Vehicle` it runs, or (a cluster node) a view of a vehicle another
    node runs (`gateway.cluster.remote.RemoteVehicle`)."""

    spec: VehicleSpec

    @property
    def sidecar(self) -> object: ...

    async def connect(self) -> None: ...

    async def disconnect(self) -> None: ...


class Registry:
    """Owns one Vehicle (and through it one sidecar) per registered drone."""

    def __init__(
        self,
        settings: Settings,
        store: Store,
        *,
        confine: Confine | None = None,
        remote_factory: Callable[[VehicleSpec], RegisteredVehicle] | None = None,
    ) -> None:
        """``remote_factory`` makes this the registry of a cluster node: every vehicle starts as a view of
        a vehicle owned elsewhere, and the node's lease keeper calls :meth:`adopt` / :meth:`release`."""
        self.settings = settings
        self.store = store
        self._confine = confine
        self._remote_factory = remote_factory
        self._vehicles: dict[str, RegisteredVehicle] = {}
        self._listeners: list[StateListener] = []
        self._changed_hooks: list[Callable[[], Awaitable[None]]] = []
        self._lock = asyncio.Lock()
        self._started = False

    # --- lifecycle --------------------------------------------------------------------------------------
    async def start(self) -> None:
        """Restore every registered vehicle; connect those with auto_connect."""
        async with self._lock:
            if self._started:
                return
            self._started = True
            for record in await self.store.list_vehicles():
                try:
                    spec = VehicleSpec.model_validate(record.model_dump(include=SPEC_FIELDS))
                except ValidationError as exc:  # a row edited by hand must not keep the others down
                    log.error("not restoring vehicle %r: invalid registration: %s", record.id, exc)
                    continue
                if self.clustered:
                    self._vehicles[spec.id] = self._remote(spec)
                    continue
                vehicle = self._make(spec)
                if record.auto_connect:
                    await vehicle.connect()
            log.info("registry started with %d vehicle(s)", len(self._vehicles))

    @property
    def clustered(self) -> bool:
        return self._remote_factory is not None

    async def stop(self) -> None:
        """Disconnect every vehicle; no mavsdk_server process remains afterwards."""
        async with self._lock:
            vehicles = list(self._vehicles.values())
            results = await asyncio.gather(*(v.disconnect() for v in vehicles), return_exceptions=True)
            for vehicle, result in zip(vehicles, results, strict=True):
                if isinstance(result, BaseException):
                    log.error("stopping %s failed: %r", vehicle.id, result)
            self._vehicles.clear()
            self._started = False

    # --- registrations ----------------------------------------------------------------------------------
    async def add(self, spec: VehicleSpec | Mapping[str, object], connect: bool = True) -> RegisteredVehicle:
        """Register (persist) a vehicle and, by default, connect it. Raises DuplicateVehicle."""
        spec = _validate_spec(spec)
        async with self._lock:
            self._refuse_crossed_links(spec)
            await self.store.add_vehicle(spec, auto_connect=connect)
            vehicle: RegisteredVehicle
            if self.clustered:  # the node whose lease keeper takes it runs its sidecar
                vehicle = self._vehicles[spec.id] = self._remote(spec)
            else:
                vehicle = self._make(spec)
        if connect and not self.clustered:
            await vehicle.connect()
        await self._registrations_changed()
        return vehicle

    async def update(self, vehicle_id: str, **changes: Unpack[VehicleChanges]) -> RegisteredVehicle:
        """Change name, tags, expected_sysid, url, gcs_endpoints or auto_connect; a new URL or new ground
        station endpoints reconnect the vehicle."""
        old = self.get(vehicle_id)
        link = {k: v for k, v in changes.items() if k in ("url", "gcs_endpoints")}
        if link:
            self._refuse_crossed_links(_validate_spec({**old.spec.model_dump(), **link}))
        record = await self.store.update_vehicle(vehicle_id, **changes)
        spec = VehicleSpec.model_validate(record.model_dump(include=SPEC_FIELDS))
        was_connected = old.sidecar is not None
        if not isinstance(old, Vehicle):
            old.spec = spec  # its owner reconnects it if the URL changed (sync)
        elif _link_changed(old.spec, spec) and was_connected:
            await old.disconnect()
            old.spec = spec
            await old.connect()
        else:
            old.spec = spec
        await self._registrations_changed()
        return old

    def _refuse_crossed_links(self, spec: VehicleSpec) -> None:
        """A ground station endpoint that is another registered drone's link or the gateway's own port
        is refused before anything is stored (InvalidArgument naming both)."""
        others = [v.spec for v in self._vehicles.values() if v.id != spec.id]
        conflict = gcs_endpoint_conflict(spec, others, self.settings.port)
        if conflict is not None:
            raise InvalidArgument(conflict)

    async def remove(self, vehicle_id: str) -> None:
        vehicle = self.get(vehicle_id)
        await vehicle.disconnect()
        await self.store.remove_vehicle(vehicle_id)
        self._vehicles.pop(vehicle_id, None)
        await self._registrations_changed()

    def get(self, vehicle_id: str) -> RegisteredVehicle:
        vehicle = self._vehicles.get(vehicle_id) if isinstance(vehicle_id, str) else None
        if vehicle is None:
            raise UnknownVehicle(str(vehicle_id)[:64], list(self._vehicles))
        return vehicle

    def flown(self, vehicle_id: str) -> FlyingVehicle:
        """The vehicle, to send it commands: a `Vehicle` this node flies whose autopilot the gateway has
        a dialect for. OwnedElsewhere for a drone another cluster node flies (this node shows it),
        NoDialect for an autopilot without a dialect (`Vehicle.require_dialect`)."""
        vehicle = self.get(vehicle_id)
        if isinstance(vehicle, Vehicle):
            vehicle.require_dialect()
        return flying(vehicle)

    async def move_origin(
        self, vehicle_id: str, lat: object, lon: object, alt_amsl_m: object, by: str
    ) -> Origin:
        """An operator's new origin for the vehicle (`gateway.fleet.policy.origin`), kept by the node that
        flies it."""
        vehicle = self.get(vehicle_id)
        if not isinstance(vehicle, Vehicle):
            flying(vehicle)  # OwnedElsewhere, naming the node that flies it
            raise AssertionError("unreachable: a remote vehicle is not flown here")
        return await vehicle.move_origin(lat, lon, alt_amsl_m, by)

    def all(self) -> list[RegisteredVehicle]:
        return [self._vehicles[k] for k in sorted(self._vehicles)]

    async def connect(self, vehicle_id: str) -> RegisteredVehicle:
        """Connect (and keep connecting at every start). On a cluster node the owner connects it."""
        return await self._switch(vehicle_id, connected=True)

    async def disconnect(self, vehicle_id: str) -> RegisteredVehicle:
        """Disconnect (and no longer connect at start)."""
        return await self._switch(vehicle_id, connected=False)

    async def _switch(self, vehicle_id: str, *, connected: bool) -> RegisteredVehicle:
        vehicle = self.get(vehicle_id)
        await (vehicle.connect() if connected else vehicle.disconnect())
        await self.store.update_vehicle(vehicle_id, auto_connect=connected)
        await self._registrations_changed()
        return vehicle

    # --- cluster: which vehicles this node runs ------------------------------------------------------
    def find(self, vehicle_id: str) -> RegisteredVehicle | None:
        """The vehicle, or None (no error) when it is not registered."""
        return self._vehicles.get(vehicle_id)

    def is_local(self, vehicle_id: str) -> bool:
        return isinstance(self._vehicles.get(vehicle_id), Vehicle)

    def local(self) -> list[Vehicle]:
        """The vehicles whose sidecar runs in this process."""
        return [v for v in self.all() if isinstance(v, Vehicle)]

    async def adopt(self, vehicle_id: str) -> Vehicle:
        """This node now owns the vehicle: replace its remote view by a connected local Vehicle."""
        async with self._lock:
            current = self.get(vehicle_id)
            if isinstance(current, Vehicle):
                return current
            vehicle = self._make(current.spec)
        await vehicle.connect()
        return vehicle

    async def release(self, vehicle_id: str) -> RegisteredVehicle | None:
        """This node no longer owns the vehicle: stop its sidecar, keep a remote view of it."""
        async with self._lock:
            current = self._vehicles.get(vehicle_id)
            if current is None or not isinstance(current, Vehicle):
                return current
            assert self._remote_factory is not None, "release() is for cluster nodes"
            self._vehicles[vehicle_id] = remote = self._remote(current.spec)
        try:
            await current.disconnect()
        except Exception:
            log.exception("stopping %s after its lease ended failed", vehicle_id)
        return remote

    async def sync(self, records: Iterable[VehicleRecord]) -> list[str]:
        """Match the registrations in the database (changed on another node); returns the ids of local
        vehicles whose URL changed (reconnected)."""
        specs = {}
        for record in records:
            try:
                specs[record.id] = VehicleSpec.model_validate(record.model_dump(include=SPEC_FIELDS))
            except ValidationError:
                continue
        changed = []
        for vid in [v for v in self._vehicles if v not in specs]:
            gone = self._vehicles.pop(vid)
            if isinstance(gone, Vehicle):
                await gone.disconnect()
        for vid, spec in specs.items():
            current = self._vehicles.get(vid)
            if current is None:
                self._vehicles[vid] = self._remote(spec)
            elif current.spec != spec:
                url_changed = _link_changed(current.spec, spec)
                current.spec = spec
                if url_changed and isinstance(current, Vehicle) and current.sidecar is not None:
                    await current.disconnect()
                    await current.connect()
                    changed.append(vid)
        return changed

    def on_registrations_changed(self, hook: Callable[[], Awaitable[None]]) -> None:
        """``await hook()`` after a registration was added, changed or removed through this registry."""
        self._changed_hooks.append(hook)

    async def _registrations_changed(self) -> None:
        for hook in list(self._changed_hooks):
            try:
                await hook()
            except Exception:
                log.exception("registration hook failed")

    def on_state_change(self, listener: StateListener) -> None:
        """``listener(vehicle, old, new)`` on every connection state change (e.g. MCP resource updates)."""
        self._listeners.append(listener)

    # --- internals --------------------------------------------------------------------------------------
    def _remote(self, spec: VehicleSpec) -> RegisteredVehicle:
        assert self._remote_factory is not None
        return self._remote_factory(spec)

    def _make(self, spec: VehicleSpec) -> Vehicle:
        vehicle = Vehicle(
            spec,
            self.settings,
            store=self.store,
            peers=self.local,  # duplicate system ids: among the vehicles whose links run here
            confine=self._confine,
            on_state=self._state_changed,
        )
        self._vehicles[spec.id] = vehicle
        return vehicle

    def _state_changed(self, vehicle: Vehicle, old: ConnectionState, new: ConnectionState) -> None:
        for listener in list(self._listeners):
            try:
                listener(vehicle, old, new)
            except Exception:
                log.exception("state listener failed")


def _validate_spec(spec: VehicleSpec | Mapping[str, object]) -> VehicleSpec:
    try:
        return VehicleSpec.model_validate(spec.model_dump() if isinstance(spec, VehicleSpec) else spec)
    except ValidationError as exc:
        problems = "; ".join(f"{'.'.join(map(str, e['loc'])) or 'spec'}: {e['msg']}" for e in exc.errors())
        raise InvalidArgument(f"invalid vehicle registration: {problems}") from None


def _link_changed(old: VehicleSpec, new: VehicleSpec) -> bool:
    """The drone's link must be opened again: another URL, or other ground station endpoints."""
    return (old.url, old.gcs_endpoints) != (new.url, new.gcs_endpoints)
