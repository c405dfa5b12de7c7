"""The mission and parameter commands on one drone: upload (items or a ground station's file),
export, start, pause, resume, clear, next item, progress; read, write and list parameters.

Each command that acts on the drone is a declaration run by the one pass
(`gateway.fleet.commands.command_pass.CommandPass.run`), as in `drone_verbs`.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Annotated

from pydantic import Field

from gateway.errors import InvalidArgument
from gateway.fleet import geo
from gateway.fleet.commands.arguments import (
    ITEM_FIELDS,
    DroneId,
    ItemIndex,
    OptionalWaypoints,
    ParamName,
    Waypoint,
    Waypoints,
)
from gateway.fleet.commands.command_core import OperationDesk, Takes, Tool, command, routed
from gateway.fleet.commands.command_pass import CommandPass, Order
from gateway.fleet.commands.drone_verbs import FlightVerbs
from gateway.fleet.commands.mission_start import resume_item, semantics_of, unchecked_text, verify_held
from gateway.fleet.commands.routes import Route
from gateway.fleet.missions import mission_files
from gateway.fleet.missions.mission import MissionItem
from gateway.fleet.operations.trackers import MissionTracker
from gateway.fleet.operations.views import (
    ActionResult,
    MissionFileView,
    MissionProgressView,
    MissionView,
    OperationView,
    ParamPage,
    ParamValue,
)
from gateway.fleet.policy.caller import Caller
from gateway.fleet.policy.mission_check import Unchecked
from gateway.fleet.policy.safety_inputs import VehicleContext
from gateway.fleet.vehicles.protocols import FlyingVehicle
from gateway.fleet.vehicles.readings import value, vehicle_context
from gateway.util.json_types import JsonObject


def mission_items(waypoints: Sequence[Waypoint]) -> list[MissionItem]:
    """A caller's waypoints as mission items (1..N); a point off the globe or a waypoint at or below
    home is refused naming its number."""
    for n, w in enumerate(waypoints, 1):
        geo.check_lat_lon(w.lat_deg, w.lon_deg)
        if w.kind in ("waypoint", "loiter_time") and w.alt_m <= 0:
            raise InvalidArgument(f"waypoint {n}: alt_m must be above 0 m above home")
    return [
        MissionItem.model_validate({ITEM_FIELDS[name]: given for name, given in w.model_dump().items()})
        for w in waypoints
    ]


class MissionVerbs:
    """Missions and parameters of one drone; pausing is the flight's safe hold."""

    def __init__(self, commands: CommandPass, desk: OperationDesk, flight: FlightVerbs) -> None:
        self.commands = commands
        self.desk = desk
        self.flight = flight

    def _upload(
        self,
        caller: Caller,
        vehicle: FlyingVehicle,
        ctx: VehicleContext,
        items: Sequence[MissionItem],
        unchecked: list[Unchecked] | None = None,
    ) -> Order:
        """The order that stores ``items`` on the drone, after the policy's mission checks (an operator's
        items the gateway cannot check are added to ``unchecked``; an agent's are refused)."""
        found = self.commands.safety.check_mission(ctx, items, caller.policy_via, semantics_of(vehicle))
        if unchecked is not None:
            unchecked.extend(found)

        async def send() -> int:
            running = self.commands.operations.running(vehicle.id)
            if running is not None and running.kind == "mission":
                raise InvalidArgument(
                    f"{vehicle.id} is flying a mission; call pause_mission before uploading another"
                )
            return await vehicle.upload_mission(items)

        return Order(send)

    @command(
        tool=Tool(
            "upload_mission",
            "mission",
            idempotent=True,
            says="{drone_id}: mission of {facts[items]} items uploaded; start it with initiate_mission or "
            "resume_mission",
            takes={"items": Takes("waypoints", Waypoints, mission_items)},
        )
    )
    @routed
    async def upload_mission(
        self, caller: Caller, drone_id: DroneId, items: list[MissionItem]
    ) -> ActionResult:
        """Upload waypoints (alt_m above home) without starting them.

        Stored on the drone as items numbered 1..N after the policy's mission checks; the tool takes
        them as `Waypoint`s (``waypoints``)."""

        def decide(vehicle: FlyingVehicle, ctx: VehicleContext) -> Order:
            return self._upload(caller, vehicle, ctx, items)

        count = len(items)
        return await self.commands.instant(
            caller, drone_id, "upload_mission", decide, f"{count} items uploaded", {"items": count}
        )

    @command
    @routed
    async def upload_mission_file(
        self, caller: Caller, drone_id: str, content: str, file_format: str | None = None
    ) -> ActionResult:
        """Store a ground station's mission file on the drone (QGC .plan or QGC WPL 110; told from the
        text when ``file_format`` is None), each item sent as the file has it, after the same policy
        checks as upload_mission (`gateway.fleet.missions.mission_files` says how the file's items are
        read)."""
        if file_format is not None and file_format not in mission_files.FORMATS:
            raise InvalidArgument(
                f"file_format {file_format!r} is not one of {', '.join(mission_files.FORMATS)}"
            )
        counted: list[int] = []
        unchecked: list[Unchecked] = []

        def decide(vehicle: FlyingVehicle, ctx: VehicleContext) -> Order:
            parsed = mission_files.parse(content, file_format)
            zero_is_here = semantics_of(vehicle).zero_position_is_here
            items = mission_files.mission_items(parsed, ctx.home, ctx.position, zero_is_here=zero_is_here)
            counted.append(len(items))
            return self._upload(caller, vehicle, ctx, items, unchecked)

        await self.commands.run(caller, drone_id, "upload_mission_file", decide)
        message = f"{counted[0]} items uploaded from the mission file"
        facts: dict[str, object] = {"items": counted[0]}
        if unchecked:
            message = f"{message}; {unchecked_text(unchecked)}"
            facts["unchecked"] = [u.text() for u in unchecked]
        return ActionResult(drone_id=drone_id, action="upload_mission_file", message=message, facts=facts)

    @command
    @routed
    async def export_mission(
        self, caller: Caller, drone_id: str, file_format: str = "plan"
    ) -> MissionFileView:
        """The drone's mission as a QGC .plan (``plan``) or QGC WPL 110 (``waypoints``) file."""
        if file_format not in mission_files.FORMATS:
            raise InvalidArgument(
                f"file_format {file_format!r} is not one of {', '.join(mission_files.FORMATS)}"
            )
        vehicle = self.commands.registry.flown(drone_id)
        vehicle.require_ready()
        raws = mission_files.raw_items(await vehicle.download_mission())
        home = vehicle_context(vehicle).home
        autopilot = vehicle.status().get("autopilot")
        content = mission_files.write(
            file_format,
            raws,
            home,
            autopilot if isinstance(autopilot, str) else None,
        )
        return MissionFileView(drone_id=drone_id, format=file_format, items=len(raws), content=content)

    @command(
        tool=Tool(
            "initiate_mission",
            "mission",
            advertise={
                "waypoints": {
                    "type": "array",
                    "items": {"type": "object"},
                    "description": "Items as upload_mission's; omit to start the drone's mission "
                    "(checked first)",
                }
            },
            takes={"items": Takes("waypoints", OptionalWaypoints, mission_items)},
        ),
        route=Route(
            "mission/start",
            "Start the mission the vehicle holds, read back and checked whole from where it is now",
            name="start_mission",
            description="The limits and zones hold the operator too; items the gateway cannot check are "
            "allowed and the\nmission is marked unchecked (in the answer, the operation's parameters and the "
            "audit row).",
            fills={"items": None, "label": "start_mission"},
        ),
    )
    @routed
    async def start_mission(
        self,
        caller: Caller,
        drone_id: DroneId,
        items: list[MissionItem] | None = None,
        label: str = "initiate_mission",
    ) -> OperationView:
        """Upload (if waypoints given) and start the mission; done when finished.

        ``items`` are uploaded first if given (an empty list is refused, never "what is stored"),
        then the drone flies the mission it holds; done when it is finished. On the ground the mission
        must begin with a takeoff item. Whatever was uploaded, the mission is read back and checked
        whole from where the drone is now (`verify_held`): another ground station may have replaced
        it, the drone moved, the zones changed."""
        if items is not None:
            if not items:
                raise InvalidArgument(
                    "waypoints is an empty list; give at least one item, or omit waypoints to start the "
                    "mission the drone holds"
                )

            def upload(vehicle: FlyingVehicle, ctx: VehicleContext) -> Order:
                return self._upload(caller, vehicle, ctx, items)

            await self.commands.run(caller, drone_id, label, upload)
        unchecked: list[Unchecked] = []

        async def decide(vehicle: FlyingVehicle, ctx: VehicleContext) -> Order:
            self.commands.safety.check_actuation(ctx, caller.policy_via)
            starts = [1] if not ctx.airborne else [1, resume_item(vehicle)]
            held, found = await verify_held(self.commands.safety, caller, vehicle, ctx, starts)
            unchecked.extend(found)
            if not ctx.in_air:
                if held[0].kind != "takeoff":
                    raise InvalidArgument(
                        f"{drone_id} is on the ground and the mission does not start with a takeoff item; "
                        "call takeoff first or make item 1 kind='takeoff'"
                    )
                self.commands.safety.check_takeoff(ctx, held[0].alt_rel_m, caller.policy_via)
            params: JsonObject = {"unchecked": [u.text() for u in found]} if found else {}
            lands = any(item.kind in ("land", "rtl") for item in held)  # it may end on the ground
            return Order(vehicle.start_mission, MissionTracker(lands=lands), params=params)

        view = (await self.commands.run(caller, drone_id, label, decide)).view()
        if unchecked:
            view = view.model_copy(update={"message": f"{view.message}; {unchecked_text(unchecked)}"})
        return view

    @command(
        tool=Tool(
            "pause_mission",
            "mission",
            idempotent=True,
            says="{drone_id} mission paused: holding position in GUIDED; resume_mission continues",
        ),
        route=Route(
            "mission/pause",
            "Pause the mission: hold where the vehicle is (GUIDED); resume continues (operator)",
            name="pause_mission",
        ),
    )
    @routed
    async def pause_mission(
        self, caller: Caller, drone_id: DroneId, label: str = "pause_mission"
    ) -> ActionResult:
        """Pause = safe hold: hover in GUIDED (not LOITER). resume_mission continues.

        The flight's safe hold (`FlightVerbs.hold`, which also declares hold_mission_position)."""
        held = await self.flight.hold(caller, drone_id, label)
        return held.model_copy(update={"message": f"{held.message} (paused as a GUIDED hold)"})

    @command(
        tool=Tool("resume_mission", "mission"),
        route=Route(
            "mission/resume", "Continue the mission from its current item (operator)", name="resume_mission"
        ),
    )
    @routed
    async def resume_mission(self, caller: Caller, drone_id: DroneId) -> OperationView:
        """Continue the mission from its current item; done when finished."""
        return await self.start_mission(caller, drone_id, None, "resume_mission")

    @command
    @routed
    async def download_mission(self, caller: Caller, drone_id: str) -> MissionView:
        vehicle = self.commands.registry.flown(drone_id)
        vehicle.require_ready()
        return MissionView(drone_id=drone_id, items=await vehicle.download_mission())

    @command(
        tool=Tool(
            "clear_mission", "mission", destructive=True, idempotent=True, says="{drone_id}: mission cleared"
        )
    )
    @routed
    async def clear_mission(self, caller: Caller, drone_id: DroneId) -> ActionResult:
        """Delete the mission stored on the drone."""

        def decide(vehicle: FlyingVehicle, ctx: VehicleContext) -> Order:
            self.commands.safety.check_actuation(ctx, caller.policy_via)

            async def send() -> None:
                running = self.commands.operations.running(drone_id)
                if running is not None and running.kind == "mission":
                    raise InvalidArgument(f"{drone_id} is flying its mission; call pause_mission first")
                await vehicle.clear_mission()

            return Order(send)

        return await self.commands.instant(caller, drone_id, "clear_mission", decide, "mission cleared")

    @command(
        tool=Tool(
            "set_current_waypoint",
            "mission",
            idempotent=True,
            says="{drone_id}: next mission item is {index}",
        )
    )
    @routed
    async def set_current_item(self, caller: Caller, drone_id: DroneId, index: ItemIndex) -> ActionResult:
        """Make mission item `index` the next target."""

        async def decide(vehicle: FlyingVehicle, ctx: VehicleContext) -> Order:
            prog = value(vehicle.telemetry.mission_progress)
            total = int(prog.total) if prog is not None else None
            if total is not None and total > 0 and index > total:
                raise InvalidArgument(
                    f"index {index} is beyond the mission's {total} items (valid: 1..{total})"
                )
            self.commands.safety.check_actuation(ctx, caller.policy_via)
            # the drone flies to item `index` next (at once in its mission mode): the held mission is
            # checked with the leg from where the drone is to that item
            await verify_held(self.commands.safety, caller, vehicle, ctx, [index])
            return Order(lambda: vehicle.set_current_mission_item(index))

        return await self.commands.instant(
            caller, drone_id, "set_current_waypoint", decide, f"next item {index}", {"index": index}
        )

    @command
    @routed
    async def mission_progress(self, caller: Caller, drone_id: str) -> MissionProgressView:
        """The item being flown (1..N), the count, and whether the mission ran to its end."""
        vehicle = self.commands.registry.flown(drone_id)
        vehicle.require_ready()
        prog = value(vehicle.telemetry.mission_progress)
        current, total = (int(prog.current), int(prog.total)) if prog is not None else (0, 0)
        finished = await vehicle.is_mission_finished()
        op = self.commands.operations.latest(drone_id)
        status = op.status.value if op is not None and op.kind == "mission" else None
        return MissionProgressView(
            drone_id=drone_id, current=current, total=total, finished=finished, operation_status=status
        )

    # ------------------------------------------------------------------------------------------------
    # parameters
    # ------------------------------------------------------------------------------------------------

    @command
    @routed
    async def get_param(self, caller: Caller, drone_id: str, name: str) -> ParamValue:
        vehicle = self.commands.registry.flown(drone_id)
        vehicle.require_ready()
        name = name.upper()
        val, kind = await vehicle.get_param(name)
        return ParamValue(drone_id=drone_id, name=name, value=val, type=kind)

    @command(tool=Tool("set_parameter", "params", idempotent=True, says="{drone_id} {name} set to {value:g}"))
    @routed
    async def set_param(
        self,
        caller: Caller,
        drone_id: DroneId,
        name: ParamName,
        value: Annotated[float, Field(allow_inf_nan=False)],
    ) -> ParamValue:
        """Write one parameter (type from the drone): speeds and altitudes within the limits, or allowlisted.

        With the drone's own type for it; agents may write only parameters a limit
        governs (within it) or the allowlist names (rules param_limit, param_not_allowed:
        `SafetyPolicy.check_param_write`)."""
        name = name.upper()

        def decide(vehicle: FlyingVehicle, ctx: VehicleContext) -> Order:
            self.commands.safety.check_param_write(
                name,
                value,
                via=caller.policy_via,
                vehicle_id=drone_id,
                protected=vehicle.protected_params,
                governed=vehicle.limit_params,
            )
            self.commands.safety.check_actuation(ctx, caller.policy_via)

            async def write() -> None:
                written.append(await vehicle.set_param(name, value))

            return Order(write)

        written: list[tuple[float | int, str]] = []  # the value as the autopilot stored it, its type
        await self.commands.run(caller, drone_id, f"set_parameter {name}", decide)
        val, kind = written[0]
        return ParamValue(drone_id=drone_id, name=name, value=val, type=kind)

    @command
    @routed
    async def list_params(
        self, caller: Caller, drone_id: str, prefix: str = "", offset: int = 0, limit: int = 100
    ) -> ParamPage:
        """One page of the parameters whose name starts with ``prefix``, sorted by name."""
        if offset < 0 or not 1 <= limit <= 500:
            raise InvalidArgument(f"offset must be >= 0 and limit 1..500; got offset={offset}, limit={limit}")
        vehicle = self.commands.registry.flown(drone_id)
        vehicle.require_ready()
        prefix = prefix.upper()
        every = await vehicle.list_params()
        names = sorted(n for n in every if n.startswith(prefix))
        page = names[offset : offset + limit]
        nxt = offset + limit if offset + limit < len(names) else None
        return ParamPage(
            drone_id=drone_id,
            prefix=prefix,
            total=len(names),
            offset=offset,
            params={n: float(every[n]) for n in page},
            next_offset=nxt,
        )
