"""One registered drone: the verbs a caller flies it with, over its link (``gateway.link.session.Link``:
sidecar, MAVSDK session, connection state, telemetry cache) and its autopilot's dialect
(``gateway.fleet.dialects``: everything that differs between ArduPilot and PX4).

The verbs are the same for every autopilot; where an autopilot does something its own way, the verb asks
the dialect. Hold is a reposition to where the vehicle is (never a mode that sinks without RC); missions
are uploaded with ``mission_raw`` in the dialect's layout and come back in user numbers 1..N; a mission
the autopilot rejects is refused with its words and never started; altitudes are metres above home,
converted to AMSL with the cached home in one place (``goto``).
"""

from __future__ import annotations

import asyncio
import contextlib
import json
import logging
import time
from collections.abc import Callable, Iterable, Mapping, Sequence
from typing import Any

from mavsdk_grpc import System
from mavsdk_grpc import mission_raw as mavsdk_mission_raw

from gateway.config import Settings
from gateway.errors import CommandFailed, InvalidArgument, VehicleNotReady
from gateway.fleet import geo, mission
from gateway.fleet.dialects import Dialect, dialect_for
from gateway.fleet.dialects import limit_params as every_limit_param
from gateway.fleet.dialects import protected_params as every_protected_param
from gateway.fleet.flightlog import FlightRecorder
from gateway.fleet.mission import MissionItem, WirePlan
from gateway.fleet.modes import ModeChoice, require_mode
from gateway.fleet.param_limits import ParamLimit
from gateway.fleet.params import Parameters
from gateway.link import refusals
from gateway.link.session import ConnectionState, Link, OnWait, Peer
from gateway.link.sidecar import Confine, Sidecar
from gateway.link.telemetry import MissionProgressValue, StatusTextValue, TelemetryCache
from gateway.registry.spec import VehicleSpec
from gateway.registry.store import Store

log = logging.getLogger("gateway.vehicle")

__all__ = ["ConnectionState", "MissionItem", "Vehicle"]

MISSION_TIMEOUT_S = 30.0
ARMABLE_WAIT_S = 60.0
MODE_CONFIRM_S = 4.0
#: closing the flight log never holds a link open longer than this (a database that hangs)
RECORDER_STOP_S = 5.0
ARM_RETRY_S = 1.0
MAV_CMD_DO_SET_MODE = 176
MISSION_STATE_COMPLETE = 5  # MISSION_CURRENT.mission_state
MAVLINK_MSG_POSITION_TARGET_GLOBAL_INT = 87
MAV_CMD_SET_MESSAGE_INTERVAL = 511
POSITION_IGNORED = 0b111  # POSITION_TARGET_TYPEMASK: x, y, z ignored (a velocity or attitude target)

StateListener = Callable[["Vehicle", ConnectionState, ConnectionState], None]


class Vehicle:
    """A registered drone. Created by the Registry; ``connect()`` starts its link."""

    def __init__(
        self,
        spec: VehicleSpec,
        settings: Settings,
        *,
        store: Store | None = None,
        peers: Callable[[], Iterable[Peer]] | None = None,
        confine: Confine | None = None,
        on_state: StateListener | None = None,
    ) -> None:
        self.settings = settings
        self.store = store
        self._on_state = on_state
        self.link = Link(
            spec,
            settings,
            dialect_for,
            peers=peers,
            confine=confine,
            on_state=self._state_changed,
            mission_progress=self._wire_progress,
            session_jobs=[("mission", self._mission_current), ("target", self._position_target)],
        )
        self.params = Parameters(spec.id, self.link.call, self.link.require_session)
        self._recorder: FlightRecorder | None = None
        self._mission_plan: WirePlan | None = None
        self._mission_state: int | None = None  # MISSION_CURRENT.mission_state (5 = COMPLETE)
        self._mission_rejection: str | None = None  # the autopilot's words when it refused the mission
        self._return_alt_name: str | None = None  # the RTL altitude parameter this vehicle has
        #: POSITION_TARGET_GLOBAL_INT: where the autopilot flies to (lat, lon, monotonic time heard)
        self._target: tuple[float, float, float] | None = None

    # --- identity, state and the link ----------------------------------------------------------------
    @property
    def id(self) -> str:
        return self.link.id

    @property
    def spec(self) -> VehicleSpec:
        return self.link.spec

    @spec.setter
    def spec(self, spec: VehicleSpec) -> None:
        self.link.spec = spec

    @property
    def dialect(self) -> Dialect:
        """The autopilot's dialect (ArduPilot's until the first HEARTBEAT says otherwise)."""
        return dialect_for(self.link.facts.autopilot)

    @property
    def telemetry(self) -> TelemetryCache:
        return self.link.telemetry

    @property
    def sidecar(self) -> Sidecar | None:
        return self.link.sidecar

    @property
    def system(self) -> System:
        return self.link.system

    @property
    def sysid(self) -> int | None:
        return self.link.sysid

    @property
    def autopilot(self) -> str | None:
        return self.link.autopilot

    @property
    def autopilot_version(self) -> str | None:
        return self.link.autopilot_version

    @property
    def is_simulator(self) -> bool:
        return self.link.is_simulator

    @property
    def sessions(self) -> int:
        return self.link.sessions

    @property
    def current_flight_id(self) -> int | None:
        """The id of the flight being recorded (armed now), None on the ground or while not connected."""
        recorder = self._recorder
        return recorder.flight.id if recorder is not None and recorder.flight is not None else None

    @property
    def last_heartbeat_age_s(self) -> float | None:
        return self.link.last_heartbeat_age_s

    @property
    def sysid_mismatch(self) -> bool:
        return self.link.sysid_mismatch

    @property
    def duplicate_sysid(self) -> list[str]:
        return self.link.duplicate_sysid

    @property
    def state(self) -> ConnectionState:
        return self.link.state

    @property
    def last_error(self) -> str | None:
        return self.link.last_error

    def initialising(self) -> str | None:
        return self.link.initialising()

    def status(self) -> dict[str, Any]:
        return self.link.status()

    def require_ready(self) -> None:
        self.link.require_ready()

    async def wait_initialised(self, within_s: float = ARMABLE_WAIT_S, notify: OnWait | None = None) -> bool:
        """Wait up to ``within_s`` for a drone still initialising, ``notify`` hearing what it waits for;
        True once ready, False when the time ran out while it still initialises and its autopilot can
        judge an arming attempt. VehicleNotReady (naming why) in any other state."""
        if await self.link.wait_ready(within_s, notify):
            return True
        if not (self.initialising() is not None and self.link.judges_arming()):
            self.require_ready()
        return False

    async def wait_for_state(self, *states: ConnectionState | str, within_s: float = 60.0) -> ConnectionState:
        return await self.link.wait_for_state(*states, within_s=within_s)

    def on_ground(self, fresh: bool = True) -> bool | None:
        """Whether the vehicle is on the ground, as its autopilot tells (its dialect decides from in_air or
        the landed state); None when no fresh telemetry says (``fresh=False``: from cached values)."""
        return self.dialect.on_ground(self.telemetry, fresh=fresh)

    def _state_changed(self, old: ConnectionState, new: ConnectionState) -> None:
        if self._on_state is not None:
            self._on_state(self, old, new)

    # --- lifecycle --------------------------------------------------------------------------------------
    async def connect(self) -> None:
        """Start the link (sidecar, session) and the flight recorder (idempotent, returns at once)."""
        await self.link.connect()  # a failed sidecar starts afresh; a running one is left alone
        if self.store is not None and self._recorder is None:
            recorder = FlightRecorder(self, self.store, self.settings)
            await recorder.start()  # a start that failed is tried again by the next connect
            self._recorder = recorder

    async def disconnect(self) -> None:
        """Stop everything of this vehicle; no mavsdk_server process remains, whatever the flight log
        could or could not write (what it could not is kept in the store's spool, or logged)."""
        try:
            if self._recorder is not None:
                recorder, self._recorder = self._recorder, None
                try:
                    await asyncio.wait_for(recorder.stop(), RECORDER_STOP_S)
                except Exception:
                    log.exception("%s: the flight log could not be closed; stopping the link anyway", self.id)
        finally:
            await self.link.disconnect()

    # --- modes ------------------------------------------------------------------------------------------
    def mode_names(self) -> list[str]:
        """The flight modes set_flight_mode takes on this drone."""
        return self.dialect.mode_names()

    def resolve_mode(self, name: str) -> ModeChoice:
        """The requested mode on this drone's autopilot; InvalidArgument listing its modes otherwise."""
        return require_mode(name, self.dialect, self.id)

    def heartbeat_mode(self) -> tuple[str, bool] | None:
        """The autopilot's own name of the mode its last HEARTBEAT shows, and whether it is armed; None
        before the first HEARTBEAT of the session or while it is stale."""
        facts = self.link.facts
        age = self.link.last_heartbeat_age_s
        if (
            facts.custom_mode is None
            or facts.autopilot is None
            or age is None
            or age > self.settings.link_lost_after_s
        ):
            return None
        return self.dialect.native_mode(facts.custom_mode), bool(facts.armed)

    def commanded_modes(self, kind: str, *, done: bool = False) -> frozenset[str]:
        """The modes an operation of ``kind`` the gateway commanded may show (the dialect's)."""
        return self.dialect.commanded_modes(kind, done=done)

    def recent_texts(self, within_s: float) -> list[str]:
        """What the autopilot said (notice or worse: what explains a failsafe, not its info chatter) in
        the last ``within_s`` seconds, oldest first."""
        return self.link.said_since(time.time() - within_s)

    async def set_flight_mode(self, name: str) -> None:
        """Switch flight mode by a common name (HOLD, RTL, LAND, MISSION, ...) or the autopilot's own;
        done once the HEARTBEAT reports the new mode. HOLD in the air is the hold action."""
        choice = self.resolve_mode(name)
        self.link.require_session()
        if choice.is_hold and self.on_ground() is False:
            await self.hold()
            return
        await self._switch_mode(choice)

    async def _switch_mode(self, choice: ModeChoice) -> None:
        facts = self.link.facts
        if facts.custom_mode == choice.custom_mode:
            return
        await self.link.command_long(MAV_CMD_DO_SET_MODE, *choice.params, what=f"set mode {choice.native}")
        loop = asyncio.get_running_loop()
        deadline = loop.time() + MODE_CONFIRM_S
        while self.link.facts.custom_mode != choice.custom_mode:
            if loop.time() > deadline:
                now = self.telemetry.fresh("flight_mode") or f"custom mode {self.link.facts.custom_mode}"
                raise CommandFailed(
                    f"set mode {choice.native} on drone '{self.id}' was accepted "
                    f"but the vehicle still reports {now}" + self.link.recent_complaint(),
                    vehicle_id=self.id,
                )
            await asyncio.sleep(0.05)

    # --- actions ----------------------------------------------------------------------------------------
    async def arm(self, within_s: float = ARMABLE_WAIT_S, notify: OnWait | None = None) -> None:
        """Arm (in the dialect's arming mode, switched to first: ArduPilot's GUIDED).

        One deadline, ``within_s`` from now, bounds the whole wait: for a drone still initialising to
        become ready (``notify`` hears what it waits for), then for the autopilot to stop refusing for
        a reason it lifts by itself ("Need Position Estimate": SYS_STATUS's pre-arm bit lags a mode
        change by up to a second), retried every ARM_RETRY_S. The arming attempt itself is the check:
        when the time runs out while the drone still initialises, one attempt gets the autopilot's own
        reason. Either way the refusal says in its words why it cannot arm yet and what to do; any
        other refusal comes back at once."""
        deadline = asyncio.get_running_loop().time() + within_s
        ready = await self.wait_initialised(within_s, notify)
        await self._arm_by(deadline, ready, notify)

    async def _arm_by(
        self, deadline: float, ready: bool, notify: OnWait | None, trust_cache: bool = True
    ) -> bool:
        """Arm unless the cached state says armed (``trust_cache``); True when an arm command was sent."""
        if trust_cache and self.telemetry.fresh("armed"):
            return False
        system = self.system
        dialect = self.dialect
        loop = asyncio.get_running_loop()
        started = time.time()
        if dialect.arming_mode is not None:
            try:
                await self._switch_mode(self.resolve_mode(dialect.arming_mode))
            except CommandFailed as exc:
                if ready:
                    raise
                said = self.link.said_since(started)
                raise self._arm_refusal(exc, said, waited=True, ready=False) from None
        while True:
            attempt_at = time.time()
            try:
                await self.link.call("arm", system.action.arm())
                return True
            except CommandFailed as exc:
                said = self.link.said_since(attempt_at)
                passing = bool(said) and all(dialect.arming_will_pass(text) for text in said)
                if not ready or not passing or loop.time() + ARM_RETRY_S > deadline:
                    raise self._arm_refusal(exc, said, waited=passing or not ready, ready=ready) from None
            log.info("%s: arming refused while initialising (%s); retrying", self.id, "; ".join(said))
            if notify is not None:
                with contextlib.suppress(Exception):  # a courtesy; the retry happens regardless
                    await notify(f"{self.id}: autopilot says {refusals.quoted(said)}; trying again")
            await asyncio.sleep(ARM_RETRY_S)

    def _arm_refusal(
        self, exc: CommandFailed, said: list[str], waited: bool, ready: bool = True
    ) -> CommandFailed | VehicleNotReady:
        """The refusal of an arming attempt: the autopilot's words and the drone's GPS (and, while it
        initialises, what the gateway still waits for); a reason it lifts by itself ("waited") also
        says what to do. A drone still initialising (not ``ready``) is refused as not ready, in the
        autopilot's words when it gave any, else in the gateway's (what it still waits for)."""
        if not said and not ready:
            try:
                self.require_ready()
            except VehicleNotReady as not_ready:
                return VehicleNotReady(
                    f"{not_ready.message}; call again in a few seconds or check fleet_status",
                    state=self.state.value,
                )
        if not said:
            return exc
        gps = self.telemetry.fresh("gps_info")
        facts = f"GPS {gps.fix_type}, {gps.num_satellites} satellites" if gps is not None else "no GPS report"
        waiting = self.initialising()
        if waiting is not None:
            facts += f"; still {waiting}"
        words = refusals.quoted(said)
        if waited:
            text = (
                f"drone '{self.id}' cannot arm yet: autopilot says {words} ({facts}); call again in a few "
                "seconds or check fleet_status"
            )
            if not ready:
                return VehicleNotReady(text, state=self.state.value)
            return CommandFailed(text, vehicle_id=self.id, result=exc.details.get("result"))
        return CommandFailed(
            f"drone '{self.id}' refused to arm: autopilot says {words} ({facts})",
            vehicle_id=self.id,
            result=exc.details.get("result"),
        )

    async def disarm(self) -> None:
        await self.link.call("disarm", self.link.require_session().action.disarm())

    async def kill(self) -> None:
        """Stop the motors at once, even in the air (the policy decides who may call this)."""
        await self.link.call("kill", self.link.require_session().action.kill())

    async def takeoff(
        self, alt_rel_m: float, within_s: float = ARMABLE_WAIT_S, notify: OnWait | None = None
    ) -> None:
        """Arm if needed (waiting for it as ``arm`` does, up to ``within_s`` in all), then take off to
        ``alt_rel_m`` metres above home. Returns once accepted."""
        geo.check_finite("takeoff altitude", alt_rel_m)
        if alt_rel_m <= 0:
            raise InvalidArgument(f"takeoff altitude must be above 0 m; got {alt_rel_m:g}")
        deadline = asyncio.get_running_loop().time() + within_s
        ready = await self.wait_initialised(within_s, notify)
        system = self.system
        if self.on_ground() is False:
            raise CommandFailed(f"drone '{self.id}' is already flying; use goto to change altitude")
        # the altitude first: between arming and the takeoff command, ArduPilot's DISARM_DELAY runs
        await self.link.call("set takeoff altitude", system.action.set_takeoff_altitude(float(alt_rel_m)))
        sent_arm = await self._arm_by(deadline, ready, notify)
        try:
            await self.link.call("takeoff", system.action.takeoff())
        except CommandFailed:
            if sent_arm or self.on_ground() is False:
                raise
            # "armed" came from the cache (the 1 Hz heartbeat), which can be a beat behind an autopilot
            # that disarmed on the ground after a landing: arm for real, then try once more
            log.info("%s: takeoff refused while the cache said armed; arming and trying again", self.id)
            await self._arm_by(deadline, ready, notify, trust_cache=False)
            await self.link.call("takeoff", system.action.takeoff())

    def home_amsl_m(self) -> float:
        home = self.telemetry.home
        if home is None:
            raise VehicleNotReady(f"drone '{self.id}' has no home position yet", state=self.state.value)
        return home.value.abs_alt_m

    async def goto(self, lat: float, lon: float, alt_rel_m: float, yaw_deg: float | None = None) -> None:
        """Fly to lat/lon at ``alt_rel_m`` above home (converted to AMSL with the cached home)."""
        geo.check_lat_lon(lat, lon)
        geo.check_finite("altitude", alt_rel_m)
        if yaw_deg is not None:
            geo.check_finite("yaw", yaw_deg)
        self.require_ready()
        amsl = geo.relative_to_amsl(float(alt_rel_m), self.home_amsl_m())
        yaw = float("nan") if yaw_deg is None else float(yaw_deg) % 360.0
        await self.link.call("goto", self.system.action.goto_location(float(lat), float(lon), amsl, yaw))

    async def hold(self) -> None:
        """Hold position: a reposition to where the vehicle is now (never LOITER/ALT_HOLD, in which a
        copter without RC throttle descends). On the ground there is nothing to hold."""
        system = self.link.require_session()
        if self.on_ground() is not False:
            return
        pos = self.telemetry.fresh("position")
        if pos is None:
            raise CommandFailed(f"cannot hold drone '{self.id}': no current position", vehicle_id=self.id)
        await self.link.call(
            "hold", system.action.goto_location(pos.lat_deg, pos.lon_deg, pos.abs_alt_m, float("nan"))
        )

    async def land(self) -> None:
        await self.link.call("land", self.link.require_session().action.land())

    async def return_to_launch(self) -> None:
        await self.link.call("return to launch", self.link.require_session().action.return_to_launch())

    async def set_yaw(self, heading_deg: float) -> None:
        """Turn to a heading (degrees from true north) in place."""
        geo.check_finite("heading", heading_deg)
        self.require_ready()
        await self.dialect.set_yaw(self.link, float(heading_deg) % 360.0)

    async def set_max_speed(self, mps: float) -> None:
        geo.check_finite("speed", mps)
        if mps <= 0:
            raise InvalidArgument(f"speed must be above 0 m/s; got {mps:g}")
        await self.link.call("set speed", self.link.require_session().action.set_current_speed(float(mps)))

    # --- missions ---------------------------------------------------------------------------------------
    def _wire_progress(self, current: int, total: int) -> MissionProgressValue:
        """MAVSDK's mission progress (wire seq, wire count) in user numbers. "Finished" comes from
        MISSION_CURRENT's mission_state COMPLETE: MAVSDK's progress never reaches current == total
        against ArduPilot, whose MISSION_CURRENT.total leaves out home."""
        finished = self._mission_state == MISSION_STATE_COMPLETE
        return self.dialect.mission_progress(
            current, total, self._mission_plan, finished, from_mission_current=False
        )

    async def _mission_current(self, system: System) -> None:
        """MISSION_CURRENT (requested at 1 Hz): current seq and the mission state."""
        async for msg in system.mavlink_direct.message("MISSION_CURRENT"):
            fields = json.loads(msg.fields_json)
            state = int(fields.get("mission_state", 0))
            if state != self._mission_state:
                self._mission_state = state
                progress = self.dialect.mission_progress(
                    int(fields.get("seq", 0)),
                    int(fields.get("total", 0)),
                    self._mission_plan,
                    state == MISSION_STATE_COMPLETE,
                    from_mission_current=True,
                )
                self.telemetry.put("mission_progress", progress)

    def position_target(self) -> tuple[float, float, float] | None:
        """Where the autopilot says it flies to (POSITION_TARGET_GLOBAL_INT): latitude, longitude and
        when it said so (monotonic); None when it has not said (or not for this session)."""
        return self._target

    async def _position_target(self, system: System) -> None:
        """POSITION_TARGET_GLOBAL_INT, asked for at 2 Hz (ArduPilot streams it only with EXT_STAT; PX4
        streams it anyway): the target a goto's takeover watch compares with the gateway's own."""
        self._target = None
        while self.link.facts.autopilot is None:  # noqa: ASYNC110 - set by the HEARTBEAT loop
            await asyncio.sleep(0.2)
        with contextlib.suppress(CommandFailed):
            await self.link.command_long(
                MAV_CMD_SET_MESSAGE_INTERVAL, MAVLINK_MSG_POSITION_TARGET_GLOBAL_INT, 5e5, what="rate"
            )
        async for msg in system.mavlink_direct.message("POSITION_TARGET_GLOBAL_INT"):
            fields = json.loads(msg.fields_json)
            if int(fields.get("type_mask", 0)) & POSITION_IGNORED == POSITION_IGNORED:
                continue  # no position in it
            lat, lon = int(fields.get("lat_int", 0)) / 1e7, int(fields.get("lon_int", 0)) / 1e7
            if lat or lon:
                self._target = (lat, lon, time.monotonic())

    async def upload_mission(self, items: Sequence[MissionItem | dict[str, Any]]) -> int:
        """Upload user items 1..N in the dialect's layout (ArduPilot: home at seq 0, hidden). Returns N.

        Raises CommandFailed with the autopilot's words when it refuses the mission, in the MISSION_ACK
        (ArduPilot: e.g. NO_SPACE and "Only N items are supported") or (PX4) in the text of its
        feasibility check. After a refused (or failed) upload the drone holds the mission it had, or
        one it rejected: either way not the caller's, so `start_mission` refuses until an upload
        succeeds or the mission is cleared."""
        if not isinstance(items, list | tuple) or not items:
            raise InvalidArgument("a mission needs at least one item")
        if len(items) > mission.MAX_ITEMS:
            raise InvalidArgument(f"a mission holds at most {mission.MAX_ITEMS} items; got {len(items)}")
        parsed: list[MissionItem] = []
        for k, item in enumerate(items, start=1):
            try:
                parsed.append(item if isinstance(item, MissionItem) else MissionItem.model_validate(item))
            except Exception as exc:
                raise InvalidArgument(f"mission item {k}: {exc}") from None
        system = self.link.require_session()
        home = self.telemetry.home
        dialect = self.dialect
        plan = dialect.encode_mission(
            parsed, (home.value.lat_deg, home.value.lon_deg, home.value.abs_alt_m) if home else None
        )
        raw = [
            mavsdk_mission_raw.MissionItem(
                w.seq, w.frame, w.command, 1 if w.seq == 0 else 0, 1,
                w.param1, w.param2, w.param3, w.param4, w.x, w.y, w.z, 0,
            )
            for w in plan.items
        ]  # fmt: skip
        self._mission_plan = None  # whatever was on board is being replaced
        self._mission_state = None
        try:
            rejection = await self._upload_checked(system, raw, dialect)
        except CommandFailed as exc:
            self._mission_rejection = exc.message
            raise
        self._mission_plan = plan
        self._mission_rejection = rejection
        if rejection is not None:
            raise CommandFailed(
                f"drone '{self.id}' rejected the mission ({len(parsed)} items): {rejection}. "
                "It will not be started; change the items and upload again.",
                vehicle_id=self.id,
                result="MISSION_REJECTED",
            )
        return len(parsed)

    async def _upload_checked(
        self, system: System, raw: list[mavsdk_mission_raw.MissionItem], dialect: Dialect
    ) -> str | None:
        """Upload; return the autopilot's rejection text if its feasibility check refused the mission
        after accepting the transfer (PX4). A MISSION_ACK error raises CommandFailed."""
        heard: list[str] = []
        verdict = asyncio.Event()

        def listen(item: StatusTextValue) -> None:
            text = item.text.strip()
            if dialect.mission_rejection(text):
                heard.append(text)
                verdict.set()

        self.telemetry.on_status_text(listen)
        try:
            # a MISSION_ACK error raises CommandFailed with the result and what the autopilot said
            await self.link.call("upload mission", system.mission_raw.upload_mission(raw), MISSION_TIMEOUT_S)
            if dialect.mission_verdict_s > 0:
                with contextlib.suppress(TimeoutError):
                    await asyncio.wait_for(verdict.wait(), dialect.mission_verdict_s)
        finally:
            self.telemetry.remove_status_listener(listen)
        return heard[0] if heard else None

    async def download_mission(self) -> list[MissionItem]:
        """The vehicle's mission as user items 1..N."""
        system = self.link.require_session()
        raw = await self.link.call(
            "download mission", system.mission_raw.download_mission(), MISSION_TIMEOUT_S
        )
        items, plan = self.dialect.decode_mission(list(raw))
        self._mission_plan = plan
        return items

    async def clear_mission(self) -> None:
        await self.link.call(
            "clear mission", self.link.require_session().mission_raw.clear_mission(), MISSION_TIMEOUT_S
        )
        self._mission_plan = WirePlan(items=[], user_to_wire=[])
        self._mission_state = None
        self._mission_rejection = None

    async def start_mission(self) -> None:
        """Run the uploaded mission: in the air, switch to it (AUTO / MISSION); on the ground, the
        dialect's way of arming and starting it. A mission the autopilot rejected is never started."""
        self.require_ready()
        system = self.system
        if self._mission_rejection is not None:
            raise CommandFailed(
                f"drone '{self.id}' rejected the last mission uploaded to it ({self._mission_rejection}); "
                "it starts none until it accepts one: upload a corrected mission first",
                vehicle_id=self.id,
                result="MISSION_REJECTED",
            )
        if self._mission_plan is None:
            await self.download_mission()
        if self._mission_plan is None or not self._mission_plan.user_to_wire:
            raise CommandFailed(
                f"drone '{self.id}' has no mission to start; upload one first", vehicle_id=self.id
            )
        self._mission_state = None  # a COMPLETE from an earlier run is not this run's
        if self.on_ground() is False:
            await self.link.call("start mission", system.mission_raw.start_mission())
            return
        await self.dialect.start_mission_on_ground(self.link, self.arm)

    async def set_current_mission_item(self, user_index: int) -> None:
        if not isinstance(user_index, int) or isinstance(user_index, bool):
            raise InvalidArgument(f"mission item index must be an integer; got {user_index!r}")
        system = self.link.require_session()
        if self._mission_plan is None:
            await self.download_mission()
        plan = self._mission_plan
        count = len(plan.user_to_wire) if plan else 0
        if plan is None or not 1 <= user_index <= count:
            raise InvalidArgument(f"mission item index must be 1..{count}; got {user_index}")
        await self.link.call(
            "set current mission item", system.mission_raw.set_current_mission_item(plan.wire_seq(user_index))
        )

    async def is_mission_finished(self) -> bool:
        if self._mission_state == MISSION_STATE_COMPLETE:
            return True
        finished = await self.link.call(
            "mission finished", self.link.require_session().mission_raw.is_mission_finished()
        )
        return bool(finished)

    # --- parameters (gateway.fleet.params) ---------------------------------------------------------------
    def return_altitude_param(self) -> tuple[str, float]:
        """The parameter that sets the altitude RTL flies home at, and its units per metre (ArduPilot
        4.7: RTL_ALT_M in metres, before: RTL_ALT in centimetres; PX4: RTL_RETURN_ALT in metres)."""
        candidates = self.dialect.return_altitude_params
        return next((c for c in candidates if c[0] == self._return_alt_name), candidates[0])

    async def set_return_altitude(self, alt_m: float) -> tuple[str, float | int]:
        """Set the altitude RTL climbs to before flying home (metres above home) in the parameter and
        units this autopilot has; returns (parameter, value written)."""
        geo.check_finite("return altitude", alt_m)
        candidates = self.dialect.return_altitude_params
        if self._return_alt_name is not None:  # the one this vehicle is known to have first
            candidates = tuple(sorted(candidates, key=lambda c: c[0] != self._return_alt_name))
        for name, per_metre in candidates:
            value = alt_m * per_metre
            try:
                stored, _kind = await self.set_param(
                    name, round(value) if per_metre >= 100 else round(value, 2)
                )
            except CommandFailed as exc:
                if exc.details.get("result") == "UNKNOWN_PARAMETER" and (name, per_metre) != candidates[-1]:
                    continue
                raise
            self._return_alt_name = name
            return name, stored
        raise AssertionError("unreachable: the last candidate raises")

    @property
    def protected_params(self) -> tuple[str, ...]:
        """Patterns of parameters agents may not write on this drone's autopilot (every dialect's while
        the autopilot is not known yet)."""
        if self.link.facts.autopilot is None:
            return every_protected_param()
        return self.dialect.protected_params

    @property
    def limit_params(self) -> Mapping[str, ParamLimit]:
        """The parameters governed by a policy limit on this drone's autopilot (every dialect's while
        the autopilot is not known yet)."""
        if self.link.facts.autopilot is None:
            return every_limit_param()
        return self.dialect.limit_params

    async def get_param(self, name: str) -> tuple[float | int, str]:
        """Value and type ('int' | 'float'); tries the other ArduPilot name if the parameter was renamed."""
        return await self.params.get(name)

    async def set_param(self, name: str, value: float | int) -> tuple[float | int, str]:
        """Write a parameter with the vehicle's own type for it; returns (stored value, type)."""
        return await self.params.set(name, value)

    async def list_params(self, max_age_s: float | None = None) -> dict[str, float | int]:
        """All parameters, fetched once and cached; ``max_age_s`` forces a refetch of an older copy."""
        return await self.params.all(max_age_s)

    @property
    def params_fetched_age_s(self) -> float | None:
        return self.params.list_age_s
