"""The geofence zones in force, changed a scope at a time: the fleet's (``"*"``) or one drone's.

The zones live in the safety policy's `GeofenceSet`; every change builds a complete new set first and
swaps it in only when all of it is valid (bad input changes nothing). When ``GATEWAY_GEOFENCE_FILE`` is
set, the file is rewritten (atomically) before each swap, so the zones survive a restart; without it
they last until the gateway stops (the view says ``persisted: false``).

A ``.plan``'s geofence becomes its drone's zones through the same swap
(`gateway.fleet.commands.zone_verbs`).
"""

from __future__ import annotations

import json
import logging
import os
import tempfile
from collections.abc import Sequence
from pathlib import Path
from typing import Literal

from pydantic import BaseModel, ConfigDict, Field

from gateway.errors import GatewayError, InvalidArgument
from gateway.fleet.policy.geofence import FLEET, GeofenceSet, Zone
from gateway.fleet.policy.safety import SafetyPolicy
from gateway.util.json_types import DocumentedJsonObject

log = logging.getLogger(__name__)

MAX_ZONES = 200


class ZoneFeature(BaseModel):
    """One zone as a GeoJSON Feature: ``properties`` kind (keep_in | keep_out), name, vehicle_id;
    ``geometry`` a Polygon or MultiPolygon ([lon, lat])."""

    model_config = ConfigDict(extra="allow")

    type: Literal["Feature"]
    # GeoJSON objects: checked by `Zone.from_geojson`, which names the zone and what is wrong
    properties: DocumentedJsonObject | None = None
    geometry: DocumentedJsonObject


class GeofencesView(BaseModel):
    """Every zone in force (the fleet's first, then each drone's), as a GeoJSON FeatureCollection."""

    type: Literal["FeatureCollection"] = "FeatureCollection"
    features: list[DocumentedJsonObject]  # GeoJSON Features (`feature`)
    persisted: bool = Field(description="Whether the zones are saved to GATEWAY_GEOFENCE_FILE.")


def feature(zone: Zone) -> dict[str, object]:
    """A zone as the GeoJSON Feature it was given as."""
    props: dict[str, object] = {"kind": zone.kind, "name": zone.name}
    if zone.scope != FLEET:
        props["vehicle_id"] = zone.scope
    return {"type": "Feature", "properties": props, "geometry": zone.geojson}


def zones_of(features: Sequence[ZoneFeature], scope: str) -> list[Zone]:
    """The features given for ``scope`` as zones; InvalidArgument names the first zone that is wrong."""
    if len(features) > MAX_ZONES:
        raise InvalidArgument(f"features: at most {MAX_ZONES} zones per scope; got {len(features)}")
    zones = []
    for index, given in enumerate(features):
        props = given.properties or {}
        name = props.get("name") or f"{'fleet' if scope == FLEET else scope}-zone-{index + 1}"
        owner = props.get("vehicle_id")
        if owner not in (None, scope if scope != FLEET else None):
            raise InvalidArgument(
                f"geofence '{name}' names vehicle_id {owner!r}; zones set here apply to "
                f"{'the whole fleet' if scope == FLEET else scope}: use PUT /api/v1/vehicles/{{id}}/geofences"
            )
        kind = props.get("kind")
        if not isinstance(kind, str):
            raise InvalidArgument(f"geofence '{name}' needs properties.kind: keep_in or keep_out")
        if not isinstance(name, str):
            raise InvalidArgument(f"geofence name must be a string; got {name!r}")
        zones.append(Zone.from_geojson(name, kind, given.geometry, scope))
    return zones


class Zones:
    """The zones of the safety policy, read and swapped a scope at a time (one per gateway)."""

    def __init__(self, safety: SafetyPolicy, geofence_file: str | None) -> None:
        self.safety = safety
        self.geofence_file = geofence_file

    def view(self) -> GeofencesView:
        zones = sorted(self.safety.geofences, key=lambda z: (z.scope != FLEET, z.scope, z.name))
        return GeofencesView(features=[feature(z) for z in zones], persisted=bool(self.geofence_file))

    def of(self, scope: str) -> list[Zone]:
        """The zones of one scope, as they are now."""
        return [z for z in self.safety.geofences if z.scope == scope]

    def replace(self, scope: str, zones: Sequence[Zone], who: str) -> GeofencesView:
        """Swap in a new set: the other scopes' zones kept, this scope's replaced by ``zones``; written to
        the geofence file first (a set it cannot write is not swapped in)."""
        kept = [z for z in self.safety.geofences if z.scope != scope]
        fences = GeofenceSet([*kept, *zones])  # raises on duplicate names: nothing changed yet
        try:
            self._save(fences)
        except OSError as exc:
            raise GatewayError(f"could not write GATEWAY_GEOFENCE_FILE: {exc}") from exc
        self.safety.geofences = fences
        what = "the fleet" if scope == FLEET else scope
        log.warning("operator %s set %d geofence zone(s) for %s", who, len(zones), what)
        return self.view()

    def _save(self, fences: GeofenceSet) -> None:
        if not self.geofence_file:
            return
        document = {"type": "FeatureCollection", "features": [feature(z) for z in fences]}
        target = Path(self.geofence_file)
        fd, tmp = tempfile.mkstemp(dir=target.parent, prefix=f".{target.name}.")
        try:
            with os.fdopen(fd, "w", encoding="utf-8") as handle:
                json.dump(document, handle, indent=1)
            os.replace(tmp, target)
        except BaseException:
            Path(tmp).unlink(missing_ok=True)
            raise


__all__ = ["MAX_ZONES", "GeofencesView", "ZoneFeature", "Zones", "feature", "zones_of"]
