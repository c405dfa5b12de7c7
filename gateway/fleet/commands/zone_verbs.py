"""The operator's geofence zones and a ground station's ``.plan``, whose geofence becomes its drone's
zones.

`set_geofences` replaces one scope's zones (the fleet's, ``"*"``, or one drone's) through the zones
service (`gateway.fleet.policy.zones`: all valid or nothing changes). `upload_plan` stores a mission file
on the drone: a ``.plan``'s geofence first becomes the drone's zones (the same swap), the mission items
are then checked against them (`MissionVerbs.upload_mission_file`), and if they are refused the zones are
put back as they were; the plan's circles and rally points are kept beside the mission and written back
by `export_plan`. Only operators change zones.
"""

from __future__ import annotations

from gateway.fleet.commands.command_core import command, operator_only
from gateway.fleet.commands.command_pass import CommandPass
from gateway.fleet.commands.mission_verbs import MissionVerbs
from gateway.fleet.missions import plan_extras
from gateway.fleet.missions.plan_extras import FenceZone, PlanExtras
from gateway.fleet.operations.views import ActionResult, MissionFileView
from gateway.fleet.policy.caller import Caller
from gateway.fleet.policy.geofence import FLEET, Zone
from gateway.fleet.policy.zones import GeofencesView, ZoneFeature, Zones, zones_of


class ZoneVerbs:
    """Geofence zones, and the ``.plan`` files that carry them."""

    def __init__(self, commands: CommandPass, zones: Zones, missions: MissionVerbs) -> None:
        self.commands = commands
        self.zones = zones
        self.missions = missions
        #: per drone, the geofence circles and rally points of its last .plan (this process only)
        self._plans: dict[str, PlanExtras] = {}

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
        said = self._keep(drone_id, extras)
        return result.model_copy(
            update={"message": f"{result.message}; {said}", "facts": {**result.facts, "plan": said}}
        )

    def _keep(self, drone_id: str, extras: PlanExtras) -> str:
        """Keep the plan's fence and rally points (each only when it has some); what became of them."""
        previous = self._plans.get(drone_id, PlanExtras())
        self._plans[drone_id] = PlanExtras(
            extras.fence if extras.fence else previous.fence, extras.rally if extras.rally else previous.rally
        )
        said = []
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
        kept = self._plans.get(drone_id, PlanExtras())
        circles = {z.name: z.circle for z in kept.fence if z.circle is not None}
        fence = [FenceZone(z.name, z.kind, z.geojson, circles.get(z.name)) for z in self.zones.of(drone_id)]
        return view.model_copy(update={"content": plan_extras.with_extras(view.content, fence, kept.rally)})
