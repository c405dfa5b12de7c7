"""Operator locks and takeover locks: who may not command which drone, and why.

A `LockBook` is owned by the REST layer (it persists `to_records()` and restores with `from_records()`);
everything else, agents included, reaches only its read-only `LockView` (`ReadOnlyLocks`)."""

from __future__ import annotations

import re
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from datetime import UTC, datetime
from typing import Protocol

from gateway.errors import InvalidArgument
from gateway.fleet.policy.geofence import FLEET
from gateway.util.json_types import JsonObject

_SCOPE_RE = re.compile(r"^(\*|[a-z0-9-]{1,32})$")
MAX_REASON_CHARS = 500


@dataclass(frozen=True)
class Lock:
    scope: str  # vehicle id, or "*" for the whole fleet
    reason: str
    by: str
    locked_at: datetime

    def to_record(self) -> JsonObject:
        return {
            "scope": self.scope,
            "reason": self.reason,
            "by": self.by,
            "locked_at": self.locked_at.isoformat(),
        }


class LockView(Protocol):
    """What the MCP side may see of the locks: reading only."""

    def reason_for(self, vehicle_id: str) -> str | None: ...

    def takeover_for(self, vehicle_id: str) -> Lock | None: ...

    def locks_for(self, vehicle_id: str) -> list[Lock]: ...

    def all(self) -> list[Lock]: ...


class LockBook:
    """Operator locks on vehicles or the whole fleet ("*"). Owned by the REST layer, which persists
    `to_records()` and restores with `from_records()`; hand `view()` to everything else."""

    def __init__(self) -> None:
        self._locks: dict[str, Lock] = {}
        # vehicle id -> its takeover lock (gateway.fleet.policy.takeover)
        self._takeovers: dict[str, Lock] = {}

    def lock(self, scope: str, reason: str, by: str, at: datetime | None = None) -> Lock:
        """Lock a vehicle (or "*": the fleet). Locking again replaces the reason and who."""
        if not isinstance(scope, str) or not _SCOPE_RE.match(scope):
            raise InvalidArgument(
                f"lock scope must be a vehicle id ([a-z0-9-]{{1,32}}) or '*'; got {scope!r}"
            )
        if not isinstance(reason, str) or not reason.strip():
            raise InvalidArgument("a lock needs a reason (shown to agents and operators)")
        if len(reason) > MAX_REASON_CHARS:
            raise InvalidArgument(f"lock reason is {len(reason)} characters; the limit is {MAX_REASON_CHARS}")
        if not isinstance(by, str) or not by.strip():
            raise InvalidArgument("a lock needs the name of who set it")
        lock = Lock(scope, reason.strip(), by.strip(), at or datetime.now(UTC))
        self._locks[scope] = lock
        return lock

    def unlock(self, scope: str) -> Lock | None:
        """Remove a lock; returns it, or None when that scope was not locked (idempotent)."""
        return self._locks.pop(scope, None)

    def get(self, scope: str) -> Lock | None:
        return self._locks.get(scope)

    # Takeover locks: set by the gateway when a pilot, another ground station or a failsafe changed a
    # drone's mode (`gateway.fleet.policy.takeover`); agents are refused until an operator releases the drone.
    # Kept apart from the operator's locks: unlocking one never lifts the other.
    def take_over(
        self, vehicle_id: str, reason: str, at: datetime | None = None, by: str = "autopilot"
    ) -> Lock:
        lock = Lock(vehicle_id, reason.strip()[:MAX_REASON_CHARS], by, at or datetime.now(UTC))
        self._takeovers[vehicle_id] = lock
        return lock

    def release(self, vehicle_id: str) -> Lock | None:
        """Lift a drone's takeover lock; returns it, or None when there was none (idempotent)."""
        return self._takeovers.pop(vehicle_id, None)

    def takeover_for(self, vehicle_id: str) -> Lock | None:
        return self._takeovers.get(vehicle_id)

    def takeovers(self) -> list[Lock]:
        return sorted(self._takeovers.values(), key=lambda lk: lk.scope)

    def locks_for(self, vehicle_id: str) -> list[Lock]:
        return [lk for key in (FLEET, vehicle_id) if (lk := self._locks.get(key)) is not None]

    def reason_for(self, vehicle_id: str) -> str | None:
        """Why this vehicle is locked (its takeover first, then the fleet lock), or None when it is not."""
        parts = []
        taken = self._takeovers.get(vehicle_id)
        if taken is not None:
            parts.append(f"drone {vehicle_id} was {taken.reason}; an operator must release it")
        for lk in self.locks_for(vehicle_id):
            what = "the fleet is locked" if lk.scope == FLEET else f"drone {vehicle_id} is locked"
            parts.append(f"{what} by {lk.by}: {lk.reason}")
        return "; ".join(parts) or None

    def all(self) -> list[Lock]:
        return sorted(self._locks.values(), key=lambda lk: (lk.scope != FLEET, lk.scope))

    def view(self) -> ReadOnlyLocks:
        return ReadOnlyLocks(self)

    def to_records(self) -> list[JsonObject]:
        return [lk.to_record() for lk in self.all()]

    @classmethod
    def from_records(cls, records: Iterable[Mapping[str, object]]) -> LockBook:
        book = cls()
        for rec in records:
            try:
                at = rec["locked_at"]
                when = at if isinstance(at, datetime) else datetime.fromisoformat(str(at))
                book.lock(str(rec["scope"]), str(rec["reason"]), str(rec["by"]), at=when)
            except KeyError as exc:
                raise InvalidArgument(f"lock record lacks {exc.args[0]!r}: {dict(rec)!r}") from None
            except ValueError as exc:
                raise InvalidArgument(f"lock record has a bad locked_at: {exc}") from None
        return book


def taken_over_text(vehicle_id: str, lock: Lock) -> str:
    """An agent's refusal on a taken-over drone: what happened, and what an operator must do."""
    return (
        f"drone {vehicle_id} was {lock.reason}. A pilot or ground station has control; the gateway sends "
        f"this drone nothing until an operator releases it (REST DELETE /api/v1/vehicles/{vehicle_id}/"
        f"takeover, `fleet-gateway drones release {vehicle_id}`, or the console). Do not retry; read-only "
        "tools still work"
    )


class ReadOnlyLocks:
    """A `LockView` over a `LockBook`: no lock or unlock here, by construction."""

    __slots__ = ("_all", "_locks_for", "_reason_for", "_takeover_for")

    def __init__(self, book: LockBook) -> None:
        # Bound methods only: the view keeps no attribute through which the book could be reached
        # by ordinary attribute access.
        self._reason_for = book.reason_for
        self._locks_for = book.locks_for
        self._all = book.all
        self._takeover_for = book.takeover_for

    def reason_for(self, vehicle_id: str) -> str | None:
        return self._reason_for(vehicle_id)

    def locks_for(self, vehicle_id: str) -> list[Lock]:
        return self._locks_for(vehicle_id)

    def all(self) -> list[Lock]:
        return self._all()

    def takeover_for(self, vehicle_id: str) -> Lock | None:
        return self._takeover_for(vehicle_id)
