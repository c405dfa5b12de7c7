"""The Commander's verbs on one drone: flight (arm, takeoff, land, return, hold, kill, mode),
navigation (goto, reposition, relative move, yaw, speed), missions and parameters.

Each verb resolves the drone, judges one fresh `VehicleContext` with the policy (as the caller's door
decides) and then acts under the drone's command lock: it starts a tracked operation (`_track`) or sends
an instant command (`_instant`), with the takeoff guard inside the lock for everything but the safety
actions (`CommandCore._guard_takeoff` states the rule). Only kill sends without the lock (see `kill`).
Messages name what to do next; ``label`` is how the caller names the command (its MCP tool name), used
in those messages and in the superseded operation's reason.

Every verb on one drone is ``@routed``: on a cluster node it runs on the node that owns the drone.
"""

from __future__ import annotations

import contextlib
import time
from collections.abc import Sequence
from typing import Any

from gateway.errors import InvalidArgument, NotFound, VehicleNotReady
from gateway.fleet import geo, mission_files
from gateway.fleet.caller import Caller
from gateway.fleet.command_core import NAV_KINDS, AltFrame, CommandCore, OnProgress, routed
from gateway.fleet.mission import MissionItem
from gateway.fleet.modes import ModeChoice
from gateway.fleet.operations import (
    ClimbThenGoTracker,
    GotoTracker,
    LandingTracker,
    MissionTracker,
    OpStatus,
    TakeoffTracker,
    YawTracker,
    check_positive_altitude,
)
from gateway.fleet.protocols import FlyingVehicle, Notify, VehicleView
from gateway.fleet.readings import is_airborne, is_landed_and_disarmed, position, value
from gateway.fleet.safety import Target, VehicleContext
from gateway.fleet.views import (
    ActionResult,
    ArrivalView,
    MissionFileView,
    MissionProgressView,
    MissionView,
    OperationView,
    ParamPage,
    ParamValue,
)
from gateway.registry.records import OperationRecord

TARGET_FRESH_S = 5.0
"""How old the autopilot's reported target may be to say where a drone is heading."""


class DroneVerbs(CommandCore):
    """Commands on one drone."""

    # ------------------------------------------------------------------------------------------------
    # flight: arm, disarm, takeoff, land, return, hold, kill, mode
    # ------------------------------------------------------------------------------------------------

    @routed
    async def arm(self, caller: Caller, drone_id: str, *, notify: Notify | None = None) -> ActionResult:
        """Arm; a drone still initialising is waited for, within the wait cap (see `Vehicle.arm`)."""
        vehicle = self.flown(drone_id)
        deadline = self._arming_deadline()
        await self._wait_initialised(vehicle, notify, deadline)
        self.safety.check_arm(self.context(vehicle), caller.policy_via)
        await self._instant(caller, vehicle, "arm_drone", lambda: vehicle.arm(self._left(deadline), notify))
        return ActionResult(drone_id=drone_id, action="arm", message="armed")

    @routed
    async def disarm(self, caller: Caller, drone_id: str, label: str = "disarm_drone") -> ActionResult:
        vehicle = self.ready(drone_id)
        ctx = self.context(vehicle)
        if ctx.in_air:
            raise InvalidArgument(
                f"{drone_id} is in the air; call land first (disarm only works on the ground)"
            )
        self.safety.check_actuation(ctx, caller.policy_via)
        _, sup = await self._instant(
            caller, vehicle, label, vehicle.disarm, safety_action=True, ends_operation=True
        )
        return ActionResult(
            drone_id=drone_id, action="disarm", message="disarmed", superseded_operation=sup and sup.id
        )

    @routed
    async def takeoff(
        self, caller: Caller, drone_id: str, alt_m: float, *, notify: Notify | None = None
    ) -> OperationView:
        """Arm if needed and climb to ``alt_m`` above home; done when reached."""
        vehicle = self.flown(drone_id)
        deadline = self._arming_deadline()  # initialising and arming wait together, within the cap
        await self._wait_initialised(vehicle, notify, deadline)
        self._guard_takeoff(caller, vehicle, "takeoff")
        ctx = self.context(vehicle)
        if ctx.in_air:
            raise InvalidArgument(_already_flying(drone_id, ctx.position[2] if ctx.position else None, alt_m))
        self.safety.check_takeoff(ctx, alt_m, caller.policy_via)
        return await self._track(
            caller,
            vehicle,
            TakeoffTracker(alt_m),
            lambda: vehicle.takeoff(alt_m, self._left(deadline), notify),
            {"alt_m": alt_m},
            "takeoff",
        )

    @routed
    async def land(self, caller: Caller, drone_id: str) -> OperationView:
        """Land where the drone is; done when landed and disarmed."""
        vehicle = self._for_recovery(caller, drone_id)
        if is_landed_and_disarmed(vehicle):
            raise InvalidArgument(
                f"{drone_id} is already on the ground and disarmed: nothing to do, it is landed as asked "
                "(do not take it off again unless the request says so)"
            )
        self.safety.check_actuation(self.context(vehicle), caller.policy_via)
        return await self._track(caller, vehicle, LandingTracker(kind="land"), vehicle.land, {}, "land")

    @routed
    async def return_to_launch(self, caller: Caller, drone_id: str) -> OperationView:
        """Fly home and land; done when landed and disarmed."""
        vehicle = self._for_recovery(caller, drone_id)
        ctx = self.context(vehicle)
        if not caller.is_operator:
            self._require_airborne(ctx, "return_to_launch")
        self.safety.check_actuation(ctx, caller.policy_via)
        return await self._track(
            caller,
            vehicle,
            LandingTracker(kind="return_to_launch"),
            vehicle.return_to_launch,
            {},
            "return_to_launch",
        )

    @routed
    async def hold(self, caller: Caller, drone_id: str, label: str = "hold_position") -> ActionResult:
        """GUIDED reposition to the current position (never LOITER/ALT_HOLD, which sink without RC);
        ends the drone's current operation."""
        vehicle = self._for_recovery(caller, drone_id)
        ctx = self.context(vehicle)
        if not caller.is_operator:
            self._require_airborne(ctx, label)
        self.safety.check_actuation(ctx, caller.policy_via)
        _, sup = await self._instant(
            caller, vehicle, label, vehicle.hold, safety_action=True, ends_operation=True, commands="hold"
        )
        pos = position(vehicle)
        where = f" at {pos[2]:.1f} m above home" if pos else ""
        stopped = f"; stopped {sup.kind} {sup.id}" if sup else ""
        return ActionResult(
            drone_id=drone_id,
            action=label,
            message=f"holding position{where}{stopped}",
            superseded_operation=sup and sup.id,
        )

    def kill_needs_confirmation(self, caller: Caller, drone_id: str) -> bool:
        """Whether a kill by this caller must first be confirmed by a human: an agent's kill of an
        airborne drone, when the policy allows agents to kill at all (else it is refused here, before
        anyone is asked)."""
        vehicle = self.ready(drone_id) if not caller.is_operator else self.vehicle(drone_id)
        return self.safety.check_kill(self.context(vehicle), caller.policy_via)

    @routed
    async def kill(self, caller: Caller, drone_id: str, confirmed: bool = False) -> ActionResult:
        """Cut the motors. An agent's: only with ``confirmed`` (a human said yes), and on the ground it
        only disarms. An operator's: at once, wherever the drone is.

        The one command sent without the drone's command lock: the lock is held while a command is
        sent, and a send can last long (a takeoff or mission start whose arming the autopilot refuses
        while it initialises retries for up to a minute; a mission upload takes up to 30 s). Cutting
        the motors must not wait behind that. It ends whatever operation is recorded; a command still
        being sent may complete after it (nothing can call back what is already on its way)."""
        vehicle = self._for_recovery(caller, drone_id)
        ctx = self.context(vehicle)
        self.safety.check_kill_confirmed(ctx, confirmed, caller.policy_via)
        self.safety.check_kill(ctx, caller.policy_via)  # locks and simulators-only hold on the ground too
        if caller.is_operator or ctx.airborne:
            await vehicle.kill()
            message = "motors killed in flight" if ctx.airborne else "motors killed"
        else:
            await vehicle.disarm()
            message = "on the ground: disarmed"
        sup = await self._supersede(drone_id, "kill_motors")
        self.operations.forget(drone_id)
        return ActionResult(
            drone_id=drone_id, action="kill", message=message, superseded_operation=sup and sup.id
        )

    @routed
    async def set_mode(self, caller: Caller, drone_id: str, mode: str) -> ActionResult:
        """Flight mode by a common name (HOLD, RTL, LAND, MISSION...) or the autopilot's own. HOLD is the
        gateway's safe hold."""
        vehicle = self.ready(drone_id)
        choice = vehicle.resolve_mode(mode)
        if choice.requested == "HOLD":
            return await self.hold(caller, drone_id, "set_flight_mode HOLD")
        label = f"set_flight_mode {choice.requested}"
        safety = _is_landing_mode(vehicle, choice)
        if not safety:
            self._guard_takeoff(caller, vehicle, label)
        ctx = self.context(vehicle)
        self.safety.check_mode(ctx, choice.requested, caller.policy_via)
        self.safety.check_mode(ctx, choice.native, caller.policy_via)
        _, sup = await self._instant(
            caller,
            vehicle,
            label,
            lambda: vehicle.set_flight_mode(mode),
            safety_action=safety,
            ends_operation=True,
            **_commanded(vehicle, choice),
        )
        named = (
            choice.native if choice.native == choice.requested else f"{choice.requested} ({choice.native})"
        )
        return ActionResult(
            drone_id=drone_id,
            action="set_flight_mode",
            message=f"mode {named}",
            superseded_operation=sup and sup.id,
            facts={"mode": named},
        )

    # ------------------------------------------------------------------------------------------------
    # navigation: goto, reposition, relative move, yaw, speed
    # ------------------------------------------------------------------------------------------------

    async def _fly_to(
        self,
        caller: Caller,
        drone_id: str,
        lat: float,
        lon: float,
        alt_rel: float,
        kind: str,
        label: str,
        yaw_deg: float | None = None,
    ) -> OperationView:
        geo.check_lat_lon(lat, lon)
        check_positive_altitude(alt_rel)
        vehicle = self.ready(drone_id)
        self._guard_takeoff(caller, vehicle, label)
        ctx = self.context(vehicle)
        if not (ctx.in_air and ctx.armed):
            # a target the policy refuses anyway is said before "take off first": a small model took off
            # as told, then gave up before ever hearing that the target itself was out of bounds
            self.safety.check_motion(ctx, Target(lat, lon, alt_rel), caller.policy_via)
        self._require_airborne(ctx, label)
        self.safety.check_motion(ctx, Target(lat, lon, alt_rel), caller.policy_via)
        params = {"lat_deg": lat, "lon_deg": lon, "alt_m": round(alt_rel, 2)}
        tracker = GotoTracker(lat, lon, alt_rel, self.settings.arrival_tolerance_m, kind=kind)
        return await self._track(
            caller, vehicle, tracker, lambda: vehicle.goto(lat, lon, alt_rel, yaw_deg), params, label
        )

    @routed
    async def goto(
        self,
        caller: Caller,
        drone_id: str,
        lat_deg: float,
        lon_deg: float,
        alt_m: float,
        alt_frame: AltFrame = "home",
        yaw_deg: float | None = None,
        label: str = "go_to_location",
    ) -> OperationView:
        """Fly to a position at ``alt_m`` (above home, or AMSL); done on arrival."""
        ctx = self.context(self.ready(drone_id))
        alt_rel = self._relative_alt(ctx, alt_m, alt_frame)
        yaw = None
        if yaw_deg is not None:
            geo.check_finite("yaw_deg", yaw_deg)
            yaw = yaw_deg % 360.0
        return await self._fly_to(caller, drone_id, lat_deg, lon_deg, alt_rel, "goto", label, yaw)

    @routed
    async def reposition(
        self,
        caller: Caller,
        drone_id: str,
        lat_deg: float,
        lon_deg: float,
        alt_m: float | None = None,
        alt_frame: AltFrame = "home",
    ) -> OperationView:
        """Fly to a position and hover there, at the current altitude unless ``alt_m`` is given."""
        ctx = self.context(self.ready(drone_id))
        if alt_m is None:
            if ctx.position is None:
                raise VehicleNotReady(f"no position received from {drone_id} yet")
            alt_rel = ctx.position[2]
        else:
            alt_rel = self._relative_alt(ctx, alt_m, alt_frame)
        return await self._fly_to(caller, drone_id, lat_deg, lon_deg, alt_rel, "reposition", "reposition")

    @routed
    async def move_relative(
        self,
        caller: Caller,
        drone_id: str,
        north_m: float = 0.0,
        east_m: float = 0.0,
        up_m: float | None = None,
        alt_m: float | None = None,
        *,
        notify: Notify | None = None,
    ) -> OperationView:
        """Move by metres north/east from the current position, climbing ``up_m`` (negative: down) or
        to ``alt_m`` above home. From the ground the drone takes off to that altitude first, in the same
        operation (`ClimbThenGoTracker`: the leg is sent only once the climb is done); every check of
        the takeoff and of the leg is made before anything is sent."""
        for name, metres in (("north_m", north_m), ("east_m", east_m), ("up_m", up_m), ("alt_m", alt_m)):
            if metres is not None:
                geo.check_finite(name, metres)
        if alt_m is not None and up_m not in (None, 0.0):
            raise InvalidArgument(
                f"give either up_m (a climb, here {up_m:g} m) or alt_m (an altitude above home, here "
                f"{alt_m:g} m), not both; nothing was sent"
            )
        vehicle = self.flown(drone_id)
        deadline = self._arming_deadline()
        if not is_airborne(vehicle):
            await self._wait_initialised(vehicle, notify, deadline)
        vehicle.require_ready()
        self._guard_takeoff(caller, vehicle, "move_to_relative")
        ctx = self.context(vehicle)
        pos = ctx.position
        if pos is None:
            raise VehicleNotReady(f"no position received from {drone_id} yet")
        lat, lon = geo.offset_position(pos[0], pos[1], north_m, east_m)
        if not (ctx.in_air and ctx.armed):
            return await self._climb_then_go(
                caller, vehicle, ctx, lat, lon, north_m, east_m, up_m, alt_m, deadline, notify
            )
        up = up_m or 0.0
        target = alt_m if alt_m is not None else pos[2] + up
        if alt_m is None and up < 0 and target <= 0:
            raise InvalidArgument(
                f"up_m={up:g} would take {drone_id} from {pos[2]:.1f} m to {target:.1f} m, below home: "
                f"up_m counts metres up (negative: down); to climb {-up:g} m use up_m={-up:g} (to come "
                "down to the ground, use land)"
            )
        return await self._fly_to(caller, drone_id, lat, lon, target, "move_to_relative", "move_to_relative")

    async def _climb_then_go(
        self,
        caller: Caller,
        vehicle: FlyingVehicle,
        ctx: VehicleContext,
        lat: float,
        lon: float,
        north_m: float,
        east_m: float,
        up_m: float | None,
        alt_m: float | None,
        deadline: float,
        notify: Notify | None,
    ) -> OperationView:
        """A relative move asked of a drone on the ground: take off to the altitude asked (``alt_m``, or
        ``up_m`` above the ground), then fly the leg, as one tracked operation."""
        drone_id = vehicle.id
        alt = alt_m if alt_m is not None else up_m
        if alt is None or alt <= 0:
            raise InvalidArgument(
                f"{drone_id} is on the ground; say how high to fly: move_to_relative(drone_id='{drone_id}', "
                f"north_m={north_m:g}, east_m={east_m:g}, alt_m=<metres above home>) takes off to alt_m "
                "first, then flies there; nothing was sent"
            )
        # the leg first: a target the policy refuses is said before anything flies
        self.safety.check_motion(ctx, Target(lat, lon, alt), caller.policy_via)
        self.safety.check_takeoff(ctx, alt, caller.policy_via)
        leg = GotoTracker(lat, lon, alt, self.settings.arrival_tolerance_m, kind="move_to_relative")
        tracker = ClimbThenGoTracker(TakeoffTracker(alt), leg, lambda: vehicle.goto(lat, lon, alt))
        params = {"lat_deg": lat, "lon_deg": lon, "alt_m": round(alt, 2), "takeoff_first": True}
        return await self._track(
            caller,
            vehicle,
            tracker,
            lambda: vehicle.takeoff(alt, self._left(deadline), notify),
            params,
            "move_to_relative",
        )

    @routed
    async def set_yaw(self, caller: Caller, drone_id: str, heading_deg: float) -> OperationView:
        """Turn in place to a heading (degrees from true north, clockwise); done when facing it."""
        vehicle = self.ready(drone_id)
        self._guard_takeoff(caller, vehicle, "set_yaw")
        ctx = self.context(vehicle)
        self._require_airborne(ctx, "set_yaw")
        self.safety.check_actuation(ctx, caller.policy_via)
        return await self._track(
            caller,
            vehicle,
            YawTracker(heading_deg),
            lambda: vehicle.set_yaw(heading_deg),
            {"heading_deg": heading_deg},
            "set_yaw",
        )

    @routed
    async def set_speed(self, caller: Caller, drone_id: str, speed_mps: float) -> ActionResult:
        """The horizontal speed of gotos, m/s (within the policy's limit)."""
        vehicle = self.ready(drone_id)
        self.safety.check_speed(self.context(vehicle), speed_mps, caller.policy_via)
        await self._instant(caller, vehicle, "set_max_speed", lambda: vehicle.set_max_speed(speed_mps))
        return ActionResult(
            drone_id=drone_id,
            action="set_max_speed",
            message=f"max speed {speed_mps:g} m/s",
            facts={"speed_mps": speed_mps},
        )

    @routed
    async def arrival(self, caller: Caller, drone_id: str) -> ArrivalView:
        """Whether the drone's last goto arrived, with the distance left; answers at once."""
        vehicle = self.vehicle(drone_id)
        op = self.operations.latest(drone_id)
        if op is None:
            record = await self._stored_latest(drone_id, NAV_KINDS)
            if record is not None:  # sent by the process before a restart: the truth as it is now
                d = GotoTracker(
                    record.params["lat_deg"], record.params["lon_deg"], record.params["alt_m"], 1.0
                ).distance(vehicle)
                return ArrivalView(
                    drone_id=drone_id,
                    arrived=record.status == OpStatus.succeeded.value,
                    operation_id=record.id,
                    kind=record.kind,
                    status=record.status,
                    distance_m=None if d is None else round(d[0], 1),
                    vertical_m=None if d is None else round(d[1], 1),
                    message=_restart_truth(vehicle, record),
                )
        if op is None or op.kind not in NAV_KINDS:
            flying = f"; it is flying: {_now_doing(vehicle)}" if op is None and is_airborne(vehicle) else ""
            return ArrivalView(
                drone_id=drone_id,
                arrived=False,
                operation_id=None,
                kind=None,
                status=None,
                distance_m=None,
                vertical_m=None,
                message=f"no goto sent to this drone yet{flying}",
            )
        tracker = GotoTracker(
            op.params["lat_deg"], op.params["lon_deg"], op.params["alt_m"], self.settings.arrival_tolerance_m
        )
        d = tracker.distance(vehicle)
        return ArrivalView(
            drone_id=drone_id,
            arrived=op.status is OpStatus.succeeded,
            operation_id=op.id,
            kind=op.kind,
            status=op.status.value,
            distance_m=None if d is None else round(d[0], 1),
            vertical_m=None if d is None else round(d[1], 1),
            message=op.message,
        )

    @routed
    async def monitor(
        self,
        caller: Caller,
        drone_id: str,
        land_on_arrival: bool = False,
        cap_s: float | None = None,
        *,
        on_progress: OnProgress | None = None,
    ) -> OperationView:
        """Wait (capped) for the drone's current operation; with ``land_on_arrival``, a goto that
        arrived is followed by a landing, waited for within the same cap."""
        vehicle = self.vehicle(drone_id)
        op = self.operations.latest(drone_id)
        if op is None:
            record = await self._stored_latest(drone_id)
            if record is not None:  # started by the process before a restart: the truth as it is now
                return OperationView.of_record(record, _restart_truth(vehicle, record))
            if is_airborne(vehicle):
                raise NotFound(
                    f"this gateway started nothing on {drone_id}, yet it is in the air "
                    f"({_now_doing(vehicle)}): flown by a pilot or another ground station, or by a gateway "
                    "whose records are gone"
                )
            raise NotFound(
                f"{drone_id} has no action to monitor (state: {vehicle.state}); nothing was started yet"
            )
        start = time.monotonic()
        cap = self.settings.mcp_wait_cap_s if cap_s is None else cap_s
        view = await self.wait(op.id, cap, on_progress)
        if land_on_arrival and view.kind in NAV_KINDS and view.status == "succeeded" and is_airborne(vehicle):
            self.safety.check_actuation(self.context(vehicle), caller.policy_via)
            flown = self.flown(drone_id)
            landing = await self._track(caller, flown, LandingTracker(kind="land"), flown.land, {}, "land")
            view = await self.wait(
                landing.operation_id, max(0.0, cap - (time.monotonic() - start)), on_progress
            )
        return view

    async def _stored_latest(
        self, drone_id: str, kinds: Sequence[str] | None = None
    ) -> OperationRecord | None:
        """The drone's newest operation in the database (of ``kinds``), for a process that has none of
        its own (it restarted)."""
        if self.store is None:
            return None
        for record in await self.store.list_operations(vehicle_id=drone_id, limit=20):
            if kinds is None or record.kind in kinds:
                return record
        return None

    # ------------------------------------------------------------------------------------------------
    # missions
    # ------------------------------------------------------------------------------------------------

    async def _upload(
        self, caller: Caller, vehicle: FlyingVehicle, items: Sequence[MissionItem], action: str
    ) -> int:
        ctx = self.context(vehicle)
        self.safety.check_mission(ctx, items, caller.policy_via)

        async def send() -> int:
            running = self.operations.running(vehicle.id)
            if running is not None and running.kind == "mission":
                raise InvalidArgument(
                    f"{vehicle.id} is flying a mission; call pause_mission before uploading another"
                )
            return await vehicle.upload_mission(items)

        await self._instant(caller, vehicle, action, send)
        return len(items)

    @routed
    async def upload_mission(self, caller: Caller, drone_id: str, items: list[MissionItem]) -> ActionResult:
        """Store a mission on the drone (items numbered 1..N, altitudes above home) without starting it."""
        vehicle = self.ready(drone_id)
        count = await self._upload(caller, vehicle, items, "upload_mission")
        return ActionResult(
            drone_id=drone_id,
            action="upload_mission",
            message=f"{count} items uploaded",
            facts={"items": count},
        )

    @routed
    async def upload_mission_file(
        self, caller: Caller, drone_id: str, content: str, file_format: str | None = None
    ) -> ActionResult:
        """Store a ground station's mission file on the drone (QGC .plan or QGC WPL 110; told from the
        text when ``file_format`` is None), each item sent as the file has it, after the same policy
        checks as upload_mission (`gateway.fleet.mission_files` says how the file's items are read)."""
        if file_format is not None and file_format not in mission_files.FORMATS:
            raise InvalidArgument(
                f"file_format {file_format!r} is not one of {', '.join(mission_files.FORMATS)}"
            )
        vehicle = self.ready(drone_id)
        parsed = mission_files.parse(content, file_format)
        ctx = self.context(vehicle)
        items = mission_files.mission_items(parsed, ctx.home, ctx.position)
        count = await self._upload(caller, vehicle, items, "upload_mission_file")
        return ActionResult(
            drone_id=drone_id,
            action="upload_mission_file",
            message=f"{count} items uploaded from the mission file",
            facts={"items": count},
        )

    @routed
    async def export_mission(
        self, caller: Caller, drone_id: str, file_format: str = "plan"
    ) -> MissionFileView:
        """The drone's mission as a QGC .plan (``plan``) or QGC WPL 110 (``waypoints``) file."""
        if file_format not in mission_files.FORMATS:
            raise InvalidArgument(
                f"file_format {file_format!r} is not one of {', '.join(mission_files.FORMATS)}"
            )
        vehicle = self.ready(drone_id)
        raws = mission_files.raw_items(await vehicle.download_mission())
        home = self.context(vehicle).home
        autopilot = vehicle.status().get("autopilot")
        content = mission_files.write(
            file_format,
            raws,
            home,
            autopilot if isinstance(autopilot, str) else None,
        )
        return MissionFileView(drone_id=drone_id, format=file_format, items=len(raws), content=content)

    @routed
    async def start_mission(
        self,
        caller: Caller,
        drone_id: str,
        items: list[MissionItem] | None = None,
        label: str = "initiate_mission",
    ) -> OperationView:
        """Upload ``items`` first if given, then fly the stored mission; done when it is finished. On the
        ground the mission must begin with a takeoff item."""
        vehicle = self.ready(drone_id)
        self._guard_takeoff(caller, vehicle, label)
        if items:
            await self._upload(caller, vehicle, items, label)
        ctx = self.context(vehicle)
        self.safety.check_actuation(ctx, caller.policy_via)
        if not ctx.in_air:
            stored = await vehicle.download_mission()
            if not stored:
                raise InvalidArgument(f"{drone_id} has no mission; give waypoints to initiate_mission")
            if stored[0].kind != "takeoff":
                raise InvalidArgument(
                    f"{drone_id} is on the ground and the mission does not start with a takeoff item; "
                    "call takeoff first or make item 1 kind='takeoff'"
                )
            self.safety.check_takeoff(ctx, stored[0].alt_rel_m, caller.policy_via)
        return await self._track(caller, vehicle, MissionTracker(), vehicle.start_mission, {}, label)

    @routed
    async def resume_mission(self, caller: Caller, drone_id: str) -> OperationView:
        """Continue the stored mission from its current item."""
        return await self.start_mission(caller, drone_id, None, "resume_mission")

    @routed
    async def pause_mission(
        self, caller: Caller, drone_id: str, label: str = "pause_mission"
    ) -> ActionResult:
        """Pause = the safe hold (GUIDED, not LOITER); resume_mission continues."""
        return await self.hold(caller, drone_id, label)

    @routed
    async def download_mission(self, caller: Caller, drone_id: str) -> MissionView:
        vehicle = self.ready(drone_id)
        return MissionView(drone_id=drone_id, items=await vehicle.download_mission())

    @routed
    async def clear_mission(self, caller: Caller, drone_id: str) -> ActionResult:
        vehicle = self.ready(drone_id)
        self.safety.check_actuation(self.context(vehicle), caller.policy_via)

        async def send() -> None:
            running = self.operations.running(drone_id)
            if running is not None and running.kind == "mission":
                raise InvalidArgument(f"{drone_id} is flying its mission; call pause_mission first")
            await vehicle.clear_mission()

        await self._instant(caller, vehicle, "clear_mission", send)
        return ActionResult(drone_id=drone_id, action="clear_mission", message="mission cleared")

    @routed
    async def set_current_item(self, caller: Caller, drone_id: str, index: int) -> ActionResult:
        """Make mission item ``index`` (1..N) the next target."""
        vehicle = self.ready(drone_id)
        prog = value(vehicle, "mission_progress")
        total = int(prog.total) if prog is not None else None
        if total is not None and total > 0 and index > total:
            raise InvalidArgument(f"index {index} is beyond the mission's {total} items (valid: 1..{total})")
        self._guard_takeoff(caller, vehicle, "set_current_waypoint")
        self.safety.check_actuation(self.context(vehicle), caller.policy_via)
        await self._instant(
            caller, vehicle, "set_current_waypoint", lambda: vehicle.set_current_mission_item(index)
        )
        return ActionResult(
            drone_id=drone_id,
            action="set_current_waypoint",
            message=f"next item {index}",
            facts={"index": index},
        )

    @routed
    async def mission_progress(self, caller: Caller, drone_id: str) -> MissionProgressView:
        """The item being flown (1..N), the count, and whether the mission ran to its end."""
        vehicle = self.ready(drone_id)
        prog = value(vehicle, "mission_progress")
        current, total = (int(prog.current), int(prog.total)) if prog is not None else (0, 0)
        finished = await vehicle.is_mission_finished()
        op = self.operations.latest(drone_id)
        status = op.status.value if op is not None and op.kind == "mission" else None
        return MissionProgressView(
            drone_id=drone_id, current=current, total=total, finished=finished, operation_status=status
        )

    # ------------------------------------------------------------------------------------------------
    # parameters
    # ------------------------------------------------------------------------------------------------

    @routed
    async def get_param(self, caller: Caller, drone_id: str, name: str) -> ParamValue:
        vehicle = self.ready(drone_id)
        name = name.upper()
        val, kind = await vehicle.get_param(name)
        return ParamValue(drone_id=drone_id, name=name, value=val, type=kind)

    @routed
    async def set_param(self, caller: Caller, drone_id: str, name: str, value: float) -> ParamValue:
        """Write a parameter with the drone's own type for it; agents may write only parameters a limit
        governs (within it) or the allowlist names (`SafetyPolicy.check_param_write`)."""
        vehicle = self.ready(drone_id)
        name = name.upper()
        self.safety.check_param_write(
            name,
            value,
            via=caller.policy_via,
            vehicle_id=drone_id,
            protected=vehicle.protected_params,
            governed=vehicle.limit_params,
        )
        self.safety.check_actuation(self.context(vehicle), caller.policy_via)
        (val, kind), _ = await self._instant(
            caller, vehicle, f"set_parameter {name}", lambda: vehicle.set_param(name, value)
        )
        return ParamValue(drone_id=drone_id, name=name, value=val, type=kind)

    @routed
    async def list_params(
        self, caller: Caller, drone_id: str, prefix: str = "", offset: int = 0, limit: int = 100
    ) -> ParamPage:
        """One page of the parameters whose name starts with ``prefix``, sorted by name."""
        if offset < 0 or not 1 <= limit <= 500:
            raise InvalidArgument(f"offset must be >= 0 and limit 1..500; got offset={offset}, limit={limit}")
        vehicle = self.ready(drone_id)
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


def _commanded(vehicle: VehicleView, choice: ModeChoice) -> dict[str, Any]:
    """What a mode change commands, for the takeover watch: the mission, return, landing or takeoff
    mode is judged as that operation is (the autopilot's own next modes included: PX4 holds after a
    mission), any other mode as itself."""
    for common, kind in (
        ("MISSION", "mission"),
        ("RTL", "return_to_launch"),
        ("LAND", "land"),
        ("TAKEOFF", "takeoff"),
    ):
        with contextlib.suppress(InvalidArgument):
            if vehicle.resolve_mode(common).native == choice.native:
                return {"commands": kind}
    return {"commands": f"set_flight_mode {choice.native}", "modes": frozenset({choice.native})}


def _now_doing(vehicle: VehicleView) -> str:
    """What the drone does now, from its telemetry: mode, airborne, altitude."""
    mode = value(vehicle, "flight_mode") or "unknown"
    pos = position(vehicle)
    where = f" at {pos[2]:.1f} m above home" if pos is not None else ""
    state = "in the air" if is_airborne(vehicle) else "on the ground"
    heard, prog = vehicle.heartbeat_mode(), value(vehicle, "mission_progress")
    if heard is not None and heard[0] in vehicle.commanded_modes("mission") and prog is not None:
        where += f", flying mission item {int(prog.current)} of {int(prog.total)}"  # MISSION_CURRENT
    target = vehicle.position_target()  # POSITION_TARGET_GLOBAL_INT
    if target is not None and pos is not None and time.monotonic() - target[2] < TARGET_FRESH_S:
        far = geo.horizontal_distance_m(pos[0], pos[1], target[0], target[1])
        where += (
            f", heading for the autopilot's target {far:.0f} m away ({target[0]:.6f}, {target[1]:.6f})"
            if far > 3.0
            else ", holding at the autopilot's target"
        )
    return f"mode {mode}, {state}{where}"


def _restart_truth(vehicle: VehicleView, record: OperationRecord) -> str:
    """A stored operation and the drone now, for a caller of a process that did not run it: e.g. "the
    gateway restarted while this operation was running; now: mode GUIDED, in the air at 12.0 m above
    home, 180 m from the goto's target"."""
    said = record.message or record.status
    if "restarted" not in said and "gateway stopped" not in said:  # it ended before this process
        said = f"{said} (before the gateway restarted)"
    target = ""
    params = record.params or {}
    pos = position(vehicle)
    if (
        pos is not None
        and isinstance(params.get("lat_deg"), int | float)
        and isinstance(params.get("lon_deg"), int | float)
    ):
        far = geo.horizontal_distance_m(pos[0], pos[1], float(params["lat_deg"]), float(params["lon_deg"]))
        target = f", {far:.0f} m from the {record.kind}'s target"
    return f"{said}; now: {_now_doing(vehicle)}{target}"


def _is_landing_mode(vehicle: VehicleView, choice: ModeChoice) -> bool:
    """Whether ``choice`` is the drone's LAND or RTL mode, by whichever name it was asked for: a safety
    action, never refused by the takeoff guard."""
    for name in ("LAND", "RTL"):
        with contextlib.suppress(InvalidArgument):
            if vehicle.resolve_mode(name).native == choice.native:
                return True
    return False


def _already_flying(drone_id: str, alt_m: float | None, wanted_m: float) -> str:
    """The refusal of a takeoff in the air, naming the call that changes altitude, with its numbers
    (a small model read "use go_to_location to change altitude" and flew to latitude 0, longitude 0)."""
    if alt_m is None:
        return (
            f"{drone_id} is already flying; to change altitude use "
            f"move_to_relative(drone_id='{drone_id}', north_m=0, east_m=0, up_m=<metres up, negative down>)"
        )
    change = wanted_m - alt_m
    if abs(change) < 1.0:
        return f"{drone_id} already flies at {alt_m:.0f} m, the altitude asked for: nothing to do"
    verb = "climb" if change > 0 else "descend"
    return (
        f"{drone_id} already flies at {alt_m:.0f} m; to {verb} to {wanted_m:g} m use "
        f"move_to_relative(drone_id='{drone_id}', north_m=0, east_m=0, up_m={change:.0f})"
    )
