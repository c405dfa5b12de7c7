"""Refusing a fleet command before anything is sent: every drone is looked up and checked, and one
answer names all the drones that cannot take part (`FleetRefused` when a safety rule refuses one,
`FleetUnavailable` when one cannot be reached or is not ready)."""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

from gateway.errors import GatewayError, InvalidArgument, SafetyRefusal
from gateway.fleet.vehicles.protocols import VehicleView


@dataclass(frozen=True)
class Unable:
    """Why one drone cannot take part: the safety rule (or the gateway error's code) and the message."""

    drone_id: str
    code: str
    message: str
    details: dict[str, object] = field(default_factory=dict)  # the error's details
    safety: bool = False  # refused by a safety rule (not an input or state error)

    @classmethod
    def from_error(cls, drone_id: str, exc: GatewayError) -> Unable:
        details = {k: v for k, v in exc.details.items() if k != "rule"}
        rule = exc.details.get("rule") if isinstance(exc, SafetyRefusal) else None
        return cls(drone_id, str(rule or exc.code), exc.message, details, safety=rule is not None)

    def to_dict(self) -> dict[str, object]:
        return {"drone_id": self.drone_id, "code": self.code, "message": self.message, **self.details}


def _refusal_text(action: str, unable: Sequence[Unable], total: int) -> str:
    lines = "; ".join(f"{u.drone_id}: {u.message}" for u in unable)
    return (
        f"{action} refused, nothing was sent: {len(unable)} of {total} drone(s) cannot take part "
        f"(all must, for {action}) - {lines}"
    )


class FleetRefused(SafetyRefusal):
    """A fleet command of which nothing was sent because safety rules refused some of its drones.
    ``rule`` is the drones' rule when they share one, else ``fleet_members``; each drone's rule and
    numbers are in ``drones``."""

    code = "fleet_refused"
    http_status = 403

    def __init__(self, action: str, unable: Sequence[Unable], total: int) -> None:
        rules = sorted({u.code for u in unable})
        rule = rules[0] if len(rules) == 1 else "fleet_members"
        super().__init__(
            rule, _refusal_text(action, unable, total), rules=rules, drones=[u.to_dict() for u in unable]
        )
        self.unable = list(unable)


class FleetUnavailable(GatewayError, code="fleet_unavailable", http_status=409):
    """A fleet command of which nothing was sent because some drones are unknown or not in a state to
    take part (no safety rule involved)."""

    def __init__(self, action: str, unable: Sequence[Unable], total: int) -> None:
        super().__init__(
            _refusal_text(action, unable, total),
            codes=sorted({u.code for u in unable}),
            drones=[u.to_dict() for u in unable],
        )
        self.unable = list(unable)


def refuse_fleet(action: str, unable: Sequence[Unable], total: int) -> GatewayError:
    """The error for a fleet command some drones cannot take part in: a safety refusal when any drone was
    refused by a rule, else an availability error. Either way every drone's reason is in it."""
    if any(u.safety for u in unable):
        return FleetRefused(action, unable, total)
    return FleetUnavailable(action, unable, total)


def check_drone_ids(drone_ids: Sequence[str], max_count: int = 64) -> list[str]:
    """A non-empty list of distinct ids; duplicates and oversize lists are refused, naming them."""
    ids = list(drone_ids)
    if not ids:
        raise InvalidArgument("drone_ids is empty: name at least one drone (see list_drones)")
    if len(ids) > max_count:
        raise InvalidArgument(f"drone_ids has {len(ids)} entries; at most {max_count} drones per command")
    bad = [i for i in ids if not isinstance(i, str) or not 0 < len(i) <= 64]
    if bad:
        raise InvalidArgument(f"drone ids must be 1..64 characters; got {bad[:3]!r}")
    dupes = sorted({i for i in ids if ids.count(i) > 1})
    if dupes:
        raise InvalidArgument(f"drone ids appear more than once: {dupes}")
    return ids


def collect_members(
    drone_ids: Sequence[str],
    resolve: Callable[[str], VehicleView],
    check: Callable[[VehicleView], None],
) -> tuple[dict[str, VehicleView], list[Unable]]:
    """Look every drone up (``resolve`` raises UnknownVehicle) and run ``check`` on it (raises a
    GatewayError, e.g. SafetyRefusal or VehicleNotReady, when it cannot take part). Every drone is
    checked, so one answer names all the drones that cannot take part."""
    vehicles: dict[str, VehicleView] = {}
    unable: list[Unable] = []
    for drone_id in drone_ids:
        try:
            vehicle = resolve(drone_id)
            check(vehicle)
        except GatewayError as exc:
            unable.append(Unable.from_error(drone_id, exc))
            continue
        vehicles[drone_id] = vehicle
    return vehicles, unable
