"""Versions of the lock broadcasts, so that a late one is dropped.

An operator's lock or unlock, and a takeover lock or its release, are applied at once on the node that
makes them and broadcast to the others (``fleet.event.<kind>``). NATS does not bound when a broadcast
arrives: one published while the bus was down at its node is sent when that node reconnects, which can
be after an operator unlocked the fleet through another node. Applied then, that old lock would lock the
fleet again, and a node would hold it (it is not in the database any more).

Each such broadcast therefore carries a version, and a node applies a broadcast only when it is newer
than everything it knows of that lock's scope; anything else is dropped. A version is a time in
microseconds, made monotonic per scope on each node (a hybrid clock): a lock's own time (``locked_at``,
the time its database row keeps), an unlock's or a release's time of making, and never less than one
above the newest version this node has seen of the scope, on the bus or in the database (a stored lock's
``locked_at``). So an unlock made after its node saw the lock, by broadcast or in the database, is newer
than it, whatever the clocks; between changes no node saw of each other, the nodes' clocks decide (they
must agree within half a second for the accept time already, docs/cluster.md).

A broadcast without a version (a node of an earlier release) is applied as before.
"""

from __future__ import annotations

from datetime import UTC, datetime, timedelta
from typing import Any

#: broadcast kind -> the family of state it changes (a lock and its unlock share one version per scope)
FAMILIES = {"lock": "lock", "unlock": "lock", "takeover": "takeover", "release": "takeover"}
#: the field of a broadcast that holds the time its change was made, where it has one
TIME_FIELDS = {"lock": "locked_at", "takeover": "at"}
EPOCH = datetime(1970, 1, 1, tzinfo=UTC)


def micros(at: datetime) -> int:
    """A time as whole microseconds since the epoch (the precision PostgreSQL keeps)."""
    if at.tzinfo is None:
        at = at.replace(tzinfo=UTC)
    return (at - EPOCH) // timedelta(microseconds=1)


def _time_of(kind: str, body: dict[str, Any]) -> datetime | None:
    value = body.get(TIME_FIELDS.get(kind, ""))
    if isinstance(value, datetime):
        return value
    if isinstance(value, str):
        try:
            return datetime.fromisoformat(value)
        except ValueError:
            return None
    return None


class LockVersions:
    """The newest version this node knows of each lock scope and takeover scope."""

    def __init__(self) -> None:
        self._newest: dict[tuple[str, str], int] = {}

    def newest(self, family: str, scope: str) -> int:
        return self._newest.get((family, scope), 0)

    def stamp(self, kind: str, body: dict[str, Any]) -> dict[str, Any]:
        """A broadcast this node makes, with its version (other kinds: unchanged)."""
        family = FAMILIES.get(kind)
        scope = body.get("scope")
        if family is None or not isinstance(scope, str):
            return body
        made = _time_of(kind, body) or datetime.now(UTC)
        version = max(micros(made), self.newest(family, scope) + 1)
        self._newest[(family, scope)] = version
        return {**body, "version": version}

    def fresh(self, kind: str, body: dict[str, Any]) -> bool:
        """Whether a broadcast heard from another node is to be applied: newer than anything this node
        knows of its scope (then it is the newest from now on), or without a version."""
        family = FAMILIES.get(kind)
        scope, version = body.get("scope"), body.get("version")
        if family is None or not isinstance(scope, str) or not isinstance(version, int):
            return True
        if version <= self.newest(family, scope):
            return False
        self._newest[(family, scope)] = version
        return True

    def saw(self, family: str, scope: str, at: datetime) -> None:
        """A change of ``scope`` made at ``at``, read from the database: nothing older is applied later."""
        key = (family, scope)
        self._newest[key] = max(self._newest.get(key, 0), micros(at))
