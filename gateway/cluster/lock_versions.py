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

Two more users of these versions:

- the emergency stop's broadcast (``stop``: it ends the fleet operations other nodes coordinate) carries
  the version of the fleet lock as its node knew it when it stopped (its own stop's lock, announced just
  before) and the time it was made: a node that knows a newer change of the fleet lock (an unlock made
  after the stop) drops it, and one that applies it ends only the fleet operations started before it, so
  a stop delivered late never ends a fleet operation started after it;
- a lock kept in a node's spool while the database was down is written when the database is back only if
  no unlock newer than it is known (`superseded`): an operator who unlocked the scope through another node
  meanwhile is not overridden by the late write.
"""

from __future__ import annotations

from datetime import UTC, datetime, timedelta

from gateway.fleet.policy.geofence import FLEET
from gateway.util.json_types import JsonObject

#: broadcast kind -> the family of state it changes (a lock and its unlock share one version per scope)
FAMILIES = {"lock": "lock", "unlock": "lock", "takeover": "takeover", "release": "takeover"}
#: the field of a broadcast that holds the time its change was made, where it has one
TIME_FIELDS = {"lock": "locked_at", "takeover": "at"}
#: the broadcasts that undo a lock of their family
UNLOCKS = frozenset({"unlock", "release"})
#: the versions of the locks this node made that it remembers (to compare a kept lock's at its flush)
STAMPS_KEPT = 1000
EPOCH = datetime(1970, 1, 1, tzinfo=UTC)


def micros(at: datetime) -> int:
    """A time as whole microseconds since the epoch (the precision PostgreSQL keeps)."""
    if at.tzinfo is None:
        at = at.replace(tzinfo=UTC)
    return (at - EPOCH) // timedelta(microseconds=1)


def _time_of(kind: str, body: JsonObject) -> datetime | None:
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
        # (family, scope) -> the newest unlock (or release) this node made or applied
        self._unlocked: dict[tuple[str, str], int] = {}
        # (family, scope, the lock's time in microseconds) -> the version this node gave the lock
        self._stamped: dict[tuple[str, str, int], int] = {}

    def _note(self, kind: str, family: str, scope: str, version: int, made: datetime | None) -> None:
        if kind in UNLOCKS:
            key = (family, scope)
            self._unlocked[key] = max(self._unlocked.get(key, 0), version)
        elif made is not None:
            self._stamped[(family, scope, micros(made))] = version
            while len(self._stamped) > STAMPS_KEPT:
                del self._stamped[next(iter(self._stamped))]

    def newest(self, family: str, scope: str) -> int:
        return self._newest.get((family, scope), 0)

    def stamp(self, kind: str, body: JsonObject) -> JsonObject:
        """A broadcast this node makes, with its version (other kinds: unchanged)."""
        family = FAMILIES.get(kind)
        scope = body.get("scope")
        if family is None or not isinstance(scope, str):
            return body
        made = _time_of(kind, body) or datetime.now(UTC)
        version = max(micros(made), self.newest(family, scope) + 1)
        self._newest[(family, scope)] = version
        self._note(kind, family, scope, version, made)
        return {**body, "version": version}

    def fresh(self, kind: str, body: JsonObject) -> bool:
        """Whether a broadcast heard from another node is to be applied: newer than anything this node
        knows of its scope (then it is the newest from now on), or without a version."""
        family = FAMILIES.get(kind)
        scope, version = body.get("scope"), body.get("version")
        if family is None or not isinstance(scope, str) or not isinstance(version, int):
            return True
        if version <= self.newest(family, scope):
            return False
        self._newest[(family, scope)] = version
        self._note(kind, family, scope, version, _time_of(kind, body))
        return True

    def superseded(self, family: str, scope: str, at: datetime) -> bool:
        """Whether a lock of ``scope`` made at ``at`` (kept while the database was down) was undone since:
        an unlock (or release) newer than the lock's version is known here."""
        made = micros(at)
        version = self._stamped.get((family, scope, made), made)
        return self._unlocked.get((family, scope), 0) > version

    def stop_stamp(self, body: JsonObject) -> JsonObject:
        """The emergency stop's broadcast, with the fleet lock's version as this node knows it and the time
        the stop was made."""
        return {**body, "version": self.newest("lock", FLEET), "at": datetime.now(UTC).isoformat()}

    def stop_is_late(self, body: JsonObject) -> bool:
        """Whether a stop broadcast is older than a change of the fleet lock this node knows (an unlock
        made after it): then it is dropped. A stop without a version is applied."""
        version = body.get("version")
        return isinstance(version, int) and self.newest("lock", FLEET) > version

    def saw(self, family: str, scope: str, at: datetime) -> None:
        """A change of ``scope`` made at ``at``, read from the database: nothing older is applied later."""
        key = (family, scope)
        self._newest[key] = max(self._newest.get(key, 0), micros(at))
