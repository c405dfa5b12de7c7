"""A vehicle owned by another node, as this node sees it: the owner's telemetry snapshots.

It is a `~gateway.fleet.vehicles.protocols.VehicleView` (state, status, telemetry cache, its owner's dialect's
answers) so ``list_drones``, ``fleet_status``, formation planning and separation checks see the whole
fleet; it has no actions. The commands go to the owner before they reach a vehicle
(`gateway.cluster.forwarding`); anything that asks this node's registry to fly it
(`Registry.flown`) is told, as `OwnedElsewhere`, which node does.
"""

from __future__ import annotations

import contextlib
import time
from collections.abc import Mapping

from gateway.config import Settings
from gateway.errors import OwnedElsewhere, VehicleNotReady
from gateway.fleet.dialects import DialectReads, autopilot_number, dialect_named, flying_dialect
from gateway.fleet.dialects import limit_params as every_limit_param
from gateway.fleet.dialects import protected_params as every_protected_param
from gateway.fleet.dialects.modes import ModeChoice, require_mode
from gateway.fleet.policy.param_limits import ParamLimit
from gateway.fleet.vehicles.protocols import Notify
from gateway.fleet.vehicles.vehicle import ConnectionState
from gateway.fleet.vehicles.waits import wait_for_state
from gateway.link.contract import GroundCommand
from gateway.link.telemetry import TelemetryCache
from gateway.registry.spec import VehicleSpec
from gateway.util.json_types import JsonObject, JsonValue

from . import snapshot

__all__ = ["OwnedElsewhere", "RemoteVehicle"]  # OwnedElsewhere lives in gateway.errors


class RemoteVehicle:
    """A registered vehicle whose sidecar runs on another node (or on none, between owners)."""

    remote = True
    sidecar = None

    def __init__(self, spec: VehicleSpec, settings: Settings) -> None:
        self.spec = spec
        self.settings = settings
        self.telemetry = TelemetryCache(stale_after_s=settings.link_lost_after_s)
        self.telemetry.live = False
        self._status: JsonObject = {}  # the owner's Vehicle.status(), as JSON
        self._received_at: float | None = None
        self.owner: str | None = None  # node id from the lease table (None: nobody holds a live lease)
        self.epoch: int = 0
        self.operation: JsonObject | None = None  # the owner's current operation, as it published it
        self._seq = -1

    # --- identity and state ------------------------------------------------------------------------
    @property
    def id(self) -> str:
        return self.spec.id

    def set_owner(self, node_id: str | None, epoch: int = 0) -> None:
        if node_id != self.owner:
            self._seq = -1
        self.owner = node_id
        self.epoch = max(self.epoch, epoch) if node_id is not None else self.epoch

    def apply(self, body: snapshot.Snapshot) -> bool:
        """Take a snapshot in; False when it is older than one already applied (a previous owner)."""
        epoch, seq = _count(body.get("epoch")), _count(body.get("seq"))
        if epoch < self.epoch or (
            epoch == self.epoch and body.get("node") == self.owner and seq <= self._seq
        ):
            return False
        self.epoch, self._seq = epoch, seq
        self.owner = str(body.get("node") or self.owner)
        snapshot.apply(self.telemetry, body)
        status = body.get("status")
        self._status = status if isinstance(status, dict) else {}
        op = body.get("operation")
        self.operation = op if isinstance(op, dict) else None
        self._received_at = time.monotonic()
        return True

    @property
    def snapshot_age_s(self) -> float | None:
        return None if self._received_at is None else time.monotonic() - self._received_at

    def _fresh(self) -> bool:
        age = self.snapshot_age_s
        return age is not None and age <= self.settings.link_lost_after_s

    @property
    def state(self) -> ConnectionState:
        if self.owner is None:
            return ConnectionState.REGISTERED
        if not self._fresh():
            return ConnectionState.LINK_LOST if self._received_at is not None else ConnectionState.CONNECTING
        try:
            return ConnectionState(str(self._status.get("state", "connecting")))
        except ValueError:
            return ConnectionState.CONNECTING

    @property
    def last_error(self) -> str | None:
        if self.owner is None:
            return "no node owns this drone right now (waiting for a node to take its lease)"
        if not self._fresh():
            age = self.snapshot_age_s
            heard = "never" if age is None else f"{age:.0f} s ago"
            return f"no telemetry from its owner node {self.owner} (last snapshot {heard})"
        return self._text("last_error")

    def _text(self, key: str) -> str | None:
        value = self._status.get(key)
        return value if isinstance(value, str) else None

    @property
    def sysid(self) -> int | None:
        value = self._status.get("sysid")
        return value if isinstance(value, int) else None

    @property
    def autopilot(self) -> str | None:
        return self._text("autopilot")

    @property
    def autopilot_version(self) -> str | None:
        return self._text("autopilot_version")

    @property
    def current_flight_id(self) -> int | None:
        """None: the owner node records the flight (it appears in /api/v1/flights once stored)."""
        return None

    @property
    def is_simulator(self) -> bool:
        return bool(self._status.get("is_simulator"))

    @property
    def sysid_mismatch(self) -> bool:
        return bool(self._status.get("sysid_mismatch"))

    @property
    def last_heartbeat_age_s(self) -> float | None:
        age = self._status.get("last_heartbeat_age_s")
        extra = self.snapshot_age_s or 0.0
        return float(age) + extra if isinstance(age, int | float) else None

    def initialising(self) -> str | None:
        if self.state != ConnectionState.CONNECTED:
            return None
        return self._text("initialising")

    def status(self) -> JsonObject:
        state = self.state
        base: JsonObject = dict(self._status)
        base.update(
            {
                "id": self.id,
                "name": self.spec.name,
                "url": self.spec.url,
                "tags": list(self.spec.tags),
                "state": state.value,
                "last_error": self.last_error,
                "last_heartbeat_age_s": None
                if self.last_heartbeat_age_s is None
                else round(self.last_heartbeat_age_s, 3),
                "owner_node": self.owner,
                "lease_epoch": self.epoch,
                "snapshot_age_s": None if self.snapshot_age_s is None else round(self.snapshot_age_s, 3),
            }
        )
        raw = base.get("sidecar")
        owners: JsonObject = raw if isinstance(raw, dict) else {}
        base["sidecar"] = {  # it runs on the owner: no process or port of it here
            "state": "remote",
            "pid": None,
            "grpc_port": None,
            "restarts": _count(owners.get("restarts")),
            "owner_state": owners.get("state"),
        }
        return base

    def require_ready(self) -> None:
        state = self.state
        if state == ConnectionState.READY:
            return
        why = self.last_error or self.initialising() or "not ready"
        raise VehicleNotReady(f"drone '{self.id}' is {state.value}: {why}", state=state.value)

    async def wait_for_state(self, *states: ConnectionState | str, within_s: float = 60.0) -> ConnectionState:
        return await wait_for_state(self, *states, within_s=within_s)

    async def wait_initialised(self, within_s: float = 60.0, notify: Notify | None = None) -> bool:
        """Wait, as its owner publishes it, for a drone still initialising; then require_ready (whether
        an arming attempt may be made anyway is for the owner to judge)."""
        waiting = self.initialising()
        if self.state == ConnectionState.CONNECTED and waiting is not None:
            if notify is not None:
                with contextlib.suppress(Exception):
                    await notify(f"{self.id}: {waiting}")
            try:
                await self.wait_for_state(ConnectionState.READY, within_s=within_s)
            except VehicleNotReady:
                pass
        self.require_ready()
        return True

    # --- lifecycle: the owner's business ------------------------------------------------------------
    async def connect(self) -> None:
        """Nothing to start here: the owning node runs the sidecar."""

    async def disconnect(self) -> None:
        """Nothing to stop here: the owning node runs the sidecar."""

    # --- what its owner's dialect says (the commands go to the owner: gateway.cluster.forwarding) ----
    @property
    def dialect(self) -> DialectReads:
        """The autopilot's dialect, by the autopilot the owner reports (ArduPilot's until it says)."""
        return dialect_named(self.autopilot)

    def resolve_mode(self, name: str) -> ModeChoice:
        return require_mode(name, self.dialect, self.id)

    def on_ground(self, fresh: bool = True) -> bool | None:
        return self.dialect.on_ground(self.telemetry, fresh=fresh)

    def heartbeat_mode(self) -> tuple[str, bool] | None:
        return None  # its owner watches the mode (and tells the cluster of a takeover)

    def heartbeat_heard_at(self) -> float | None:
        return None  # its owner watches the mode

    def position_target(self) -> tuple[float, float, float] | None:
        return None  # its owner compares it (and tells the cluster of a takeover)

    def position_targets(self, since: float) -> list[tuple[float, float, float]]:
        return []  # its owner compares them

    def commanded_target(self) -> tuple[float, float, float] | None:
        return None  # its owner sent it

    def ground_station_commands(self, since: float) -> list[GroundCommand]:
        return []  # its owner relays them

    def commanded_modes(self, kind: str, *, done: bool = False) -> frozenset[str]:
        return self.dialect.commanded_modes(kind, done=done)

    def recent_texts(self, within_s: float) -> list[str]:
        return []

    def return_altitude_param(self) -> tuple[str, float]:
        # which of them the vehicle has, its owner knows; no dialect for its autopilot: NoDialect
        return flying_dialect(autopilot_number(self.autopilot), self.id).return_altitude_params[0]

    @property
    def protected_params(self) -> tuple[str, ...]:
        return every_protected_param() if self.autopilot is None else self.dialect.protected_params

    @property
    def origin(self) -> tuple[float, float, float] | None:
        return None  # kept by the node that flies it, where every command is decided

    def flown_here(self) -> None:
        """Another node flies it: a view only (`VehicleView.flown_here`)."""
        return None

    @property
    def limit_params(self) -> Mapping[str, ParamLimit]:
        return every_limit_param() if self.autopilot is None else self.dialect.limit_params


def _count(value: JsonValue) -> int:
    """A whole number of a snapshot (an epoch, a sequence number, restarts); 0 when missing."""
    return int(value) if isinstance(value, int | float) else 0
