"""Drone ids as people and models write them: 'Alpha' and 'ALPHA' name the drone registered as alpha.

Operations, command locks, scopes and audit rows are keyed by the id string, so an id is made canonical
where a call enters (the MCP tool wrapper, `Commander.call`, the REST command routes), never inside the
registry lookup: two spellings of one drone must never reach the fleet layer as two keys."""

from __future__ import annotations

from collections.abc import Mapping

from gateway.fleet.vehicles.protocols import VehicleDirectory


def canonical_drone_id(directory: VehicleDirectory, drone_id: str) -> str:
    """The registered id that ``drone_id`` names ignoring case; unchanged when it names none (the lookup
    then says which ids exist) or several that differ only in case (then only the exact one matches)."""
    ids = [v.id for v in directory.all()]
    if drone_id in ids:
        return drone_id
    folded = drone_id.casefold()
    matches = [i for i in ids if i.casefold() == folded]
    return matches[0] if len(matches) == 1 else drone_id


def canonical_arguments(directory: VehicleDirectory, arguments: Mapping[str, object]) -> dict[str, object]:
    """A verb's or a tool's arguments with ``drone_id`` and each of ``drone_ids`` made canonical."""
    out = dict(arguments)
    drone_id = out.get("drone_id")
    if isinstance(drone_id, str):
        out["drone_id"] = canonical_drone_id(directory, drone_id)
    drone_ids = out.get("drone_ids")
    if isinstance(drone_ids, list):
        out["drone_ids"] = [canonical_drone_id(directory, d) if isinstance(d, str) else d for d in drone_ids]
    return out
