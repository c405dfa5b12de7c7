"""The operator's geofence zones and a ground station's ``.plan``, whose geofence becomes its drone's
zones.

`set_geofences` replaces one scope's zones (the fleet's, ``"*"``, or one drone's) through the zones
service (`gateway.fleet.policy.zones`: all valid or nothing changes). `upload_plan` stores a mission file
on the drone: a ``.plan``'s geofence first becomes the drone's zones (the same swap), the mission items
are then checked against them (`MissionVerbs.upload_mission_file`), and if they are refused the zones are
put back as they were; the plan's circles and rally points are kept in the store (with the drone, so a
restart or another node keeps them) and written back by `export_plan`. Only operators change zones.
"""

from __future__ import annotations

import logging

from sqlalchemy.exc import SQLAlchemyError

from gateway.fleet.commands.command_core import command
from gateway.fleet.commands.command_pass import CommandPass
from gateway.fleet.commands.mission_verbs import MissionVerbs
from gateway.fleet.commands.verb_rules import operator_only
from gateway.fleet.missions import plan_extras
from gateway.fleet.missions.plan_extras import FenceZone, PlanExtras
from gateway.fleet.operations.views import ActionResult, MissionFileView
from gateway.fleet.policy.caller import Caller
from gateway.fleet.policy.geofence import FLEET, Zone
from gateway.fleet.policy.zones import GeofencesView, ZoneFeature, Zones, zones_of
from gateway.registry.store import Store
from gateway.registry.store_plans import KeptPlanExtras

log = logging.getLogger(__name__)


class ZoneVerbs:
    """Geofence zones, and the ``.plan`` files that carry them."""

    def __init__(
        self, commands: CommandPass, zones: Zones, missions: MissionVerbs, store: Store | None
    ) -> None:
        """``store``: where each drone's last .plan extras are kept (None: in this process only)."""
        self.commands = commands
        self.zones = zones
        self.missions = missions
        self.store = store
        self._unstored: dict[str, KeptPlanExtras] = {}

    async def _kept(self, drone_id: str) -> KeptPlanExtras:
        if self.store is None:
            return self._unstored.get(drone_id, KeptPlanExtras())
        return await self.store.get_plan_extras(drone_id) or KeptPlanExtras()

    async def _store(self, drone_id: str, kept: KeptPlanExtras, who: str) -> None:
        if self.store is None:
            self._unstored[drone_id] = kept
        else:
            await self.store.save_plan_extras(drone_id, kept, who)

    def geofences(self) -> GeofencesView:
        """Every zone in force (a read)."""
        return self.zones.view()

    @command
    async def set_geofences(self, caller: Caller, scope: str, features: list[ZoneFeature]) -> GeofencesView:
        """Replace the zones of ``scope`` (a drone id, or ``"*"`` for the fleet) by ``features`` (none:
        remove them); every zone is checked before any is swapped in."""
        operator_only(caller, "change geofences")
        if scope != FLEET:
            self.commands.registry.get(scope)  # UnknownVehicle names the known ids
        return self.zones.replace(scope, zones_of(features, scope), caller.principal)

    @command
    async def upload_plan(
        self, caller: Caller, drone_id: str, content: str, file_format: str | None = None
    ) -> ActionResult:
        """Store a mission file on the drone (QGC .plan or WPL 110; told from the text when
        ``file_format`` is None). A .plan's geofence replaces the drone's zones before its items are
        checked, and is put back if they are refused; its rally points are kept for `export_plan`."""
        operator_only(caller, "upload a mission file (its geofence replaces the drone's zones)")
        self.commands.registry.get(drone_id)  # UnknownVehicle before any zone is touched
        extras = PlanExtras()
        if file_format == "plan" or (file_format is None and content.lstrip().startswith("{")):
            content, extras = plan_extras.split_plan(content, prefix=f"{drone_id}-plan")
        zones = [Zone.from_geojson(z.name, z.kind, z.geometry, drone_id) for z in extras.fence]
        before = self.zones.of(drone_id)
        if zones:
            self.zones.replace(drone_id, zones, caller.principal)
        try:
            result = await self.missions.upload_mission_file(caller, drone_id, content, file_format)
        except BaseException:
            if zones:
                self.zones.replace(drone_id, before, caller.principal)
            raise
        if not extras:
            return result
        said = await self._keep(drone_id, extras, caller.principal)
        return result.model_copy(
            update={"message": f"{result.message}; {said}", "facts": {**result.facts, "plan": said}}
        )

    async def _keep(self, drone_id: str, extras: PlanExtras, who: str) -> str:
        """Keep the plan's fence circles and rally points (each only when it has some) in the store; what
        became of them."""
        said = []
        try:
            previous = await self._kept(drone_id)
            circles = {z.name: z.circle for z in extras.fence if z.circle is not None}
            kept = KeptPlanExtras(
                extras.rally if extras.rally else previous.rally,
                circles if extras.fence else previous.circles,
            )
            await self._store(drone_id, kept, who)
        except (SQLAlchemyError, OSError) as exc:
            log.error("%s: the .plan's rally points and circles could not be stored: %s", drone_id, exc)
            said.append(
                f"the plan's rally points and geofence circles could not be stored ({type(exc).__name__}): "
                "an exported .plan will not carry them"
            )
        if extras.fence:
            said.append(
                f"the plan's geofence ({len(extras.fence)} zones) is now the drone's geofences, replacing "
                "its own (the gateway's policy holds it; the autopilot's own fence is not written)"
            )
        if extras.rally:
            said.append(
                f"{len(extras.rally)} rally points kept by the gateway and written back in the exported "
                ".plan; not uploaded to the autopilot (the gateway has no rally upload), so its RTL returns "
                "home"
            )
        return "; ".join(said)

    @command
    async def export_plan(self, caller: Caller, drone_id: str, file_format: str = "plan") -> MissionFileView:
        """The drone's mission as a file (`MissionVerbs.export_mission`); a .plan also carries the
        drone's zones as its geofence and the rally points kept from its last .plan (a read)."""
        view = await self.missions.export_mission(caller, drone_id, file_format)
        if file_format != "plan":
            return view
        kept = await self._kept(drone_id)
        fence = [
            FenceZone(z.name, z.kind, z.geojson, kept.circles.get(z.name)) for z in self.zones.of(drone_id)
        ]
        return view.model_copy(update={"content": plan_extras.with_extras(view.content, fence, kept.rally)})
