"""Errors shared by the fleet logic, REST and MCP layers.

Each error has a stable machine-readable ``code`` and a message written for the person (or model)
who has to act on it. REST maps them to JSON error bodies, MCP to tool errors.
"""

from __future__ import annotations

from gateway.util.text import printable


class GatewayError(Exception):
    code = "gateway_error"
    http_status = 500

    def __init_subclass__(cls, *, code: str = "", http_status: int = 0, **kwargs: object) -> None:
        """A subclass names its code and HTTP status in its header: ``class X(GatewayError, code="x",
        http_status=409)``; one that names neither keeps its parent's."""
        super().__init_subclass__(**kwargs)
        cls.code = code or cls.code
        cls.http_status = http_status or cls.http_status

    def __init__(self, message: str, **details: object) -> None:
        super().__init__(message)
        self.message = message
        self.details = details

    def to_dict(self) -> dict[str, object]:
        body: dict[str, object] = {"code": self.code, "message": self.message}
        if self.details:
            body["details"] = self.details
        return body


class InvalidArgument(GatewayError, code="invalid_argument", http_status=422): ...


class StateConflict(InvalidArgument, code="state_conflict", http_status=409):
    """The request is well formed, but the drone's state makes it moot (a land for a drone already landed
    and disarmed): REST answers 409 Conflict; MCP reports it as an invalid argument, as before."""


class UnknownVehicle(GatewayError, code="unknown_vehicle", http_status=404):
    def __init__(self, vehicle_id: str, known: list[str]) -> None:
        known_text = ", ".join(sorted(known)) if known else "none registered"
        shown = printable(str(vehicle_id), 64)
        super().__init__(f"unknown drone id '{shown}'; known ids: {known_text}", known=sorted(known))


class DuplicateVehicle(GatewayError, code="duplicate_vehicle", http_status=409): ...


class NotFound(GatewayError, code="not_found", http_status=404): ...


class VehicleNotReady(GatewayError, code="vehicle_not_ready", http_status=409): ...


class CommandFailed(GatewayError, code="command_failed", http_status=502):
    """The autopilot (or mavsdk_server) rejected or failed a command."""


class NoDialect(GatewayError, code="no_dialect", http_status=409):
    """The drone's autopilot (as its HEARTBEAT names it) has no dialect in this gateway: it is shown,
    never commanded."""


class OwnedElsewhere(GatewayError, code="owned_elsewhere", http_status=409):
    """Cluster: another node flies the drone; this node shows it but cannot command it."""

    @classmethod
    def of(cls, vehicle_id: str, owner_node: str | None) -> OwnedElsewhere:
        where = f"cluster node {owner_node}" if owner_node else "no cluster node right now"
        return cls(
            f"drone '{vehicle_id}' is owned by {where}; this node answers reads for it but cannot "
            "command it: use the node that owns it (GET /api/v1/cluster lists the nodes and their drones)",
            vehicle_id=vehicle_id,
            owner_node=owner_node,
        )


class SafetyRefusal(GatewayError, code="safety_refusal", http_status=403):
    """A safety rule refused the request; ``rule`` names it."""

    def __init__(self, rule: str, message: str, **details: object) -> None:
        super().__init__(message, rule=rule, **details)
        self.rule = rule


class NoOwner(GatewayError, code="no_owner", http_status=503):
    """Cluster: no node holds the drone's lease right now (its node was lost and a takeover is under
    way, or no live node may own it)."""


class OwnerLost(NoOwner, code="owner_lost", http_status=503):
    """Cluster: the node running a forwarded call lost the drone's lease while the caller waited (it was
    lost, or fenced itself); the call had been accepted there, so it may have run."""


class OwnerFenced(GatewayError, code="owner_fenced", http_status=503):
    """Cluster: the node running a forwarded call fenced itself (it could not renew its leases) or lost
    the drone's lease while it ran: the call was not finished there, and that node does not command the
    drone any further (the drone flies its last command on its own)."""


class NotRun(GatewayError, code="not_run", http_status=503):
    """Cluster: a forwarded call was not run: the bus is unreachable from this node, or the owner did not
    accept it before its deadline (the owner refuses it if it arrives later), or it was sent for a lease
    epoch the owner no longer holds."""


class StopPending(GatewayError, code="stop_pending", http_status=202):
    """Cluster: an operator's stop no owner acknowledged in time and that the drone's own link did not
    take yet: the node that took it keeps trying (its message says how, and for how long)."""


class OwnerTimeout(GatewayError, code="owner_timeout", http_status=504):
    """Cluster: the node owning the drone did not answer in time; the call may or may not have run."""
