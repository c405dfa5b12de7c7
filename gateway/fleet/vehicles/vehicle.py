"""One registered drone: what is read of it and the actions a caller flies it with, over its link
(``gateway.link.session.Link``: sidecar, MAVSDK session, connection state, telemetry cache) and its
autopilot's dialect (``gateway.fleet.dialects``: everything that differs between ArduPilot and PX4).

`Vehicle` is a `FlyingVehicle` (`gateway.fleet.vehicles.protocols`): its read view and its actions. The
actions
are the same for every autopilot; where an autopilot does something its own way, the action asks the
dialect, and every action first asks for it (`require_dialect`): an autopilot the gateway has no dialect
for is refused in one line before anything is sent. Hold is a reposition to where the vehicle is (never
a mode that sinks without RC); altitudes are metres above home, converted to AMSL with the cached home
in one place (``goto``). Arming and mode switches live in ``vehicle_arming``, missions in
``vehicle_missions``, parameters in ``params``.
"""

from __future__ import annotations

import asyncio
import json
import logging
import time
from collections import deque
from collections.abc import Awaitable, Callable, Iterable, Mapping, Sequence

from gateway.config import Settings
from gateway.errors import CommandFailed, InvalidArgument, VehicleNotReady
from gateway.fleet import geo
from gateway.fleet.dialects import Dialect, DialectReads, dialect_for, flying_dialect
from gateway.fleet.dialects import limit_params as every_limit_param
from gateway.fleet.dialects import protected_params as every_protected_param
from gateway.fleet.dialects.modes import ModeChoice, require_mode
from gateway.fleet.missions.flightlog import FlightRecorder
from gateway.fleet.missions.mission import MissionItem
from gateway.fleet.policy.origin import Origin
from gateway.fleet.policy.param_limits import ParamLimit
from gateway.fleet.vehicles.origin_keeper import OriginKeeper
from gateway.fleet.vehicles.params import Parameters
from gateway.fleet.vehicles.protocols import FlyingVehicle
from gateway.fleet.vehicles.vehicle_arming import Arming
from gateway.fleet.vehicles.vehicle_missions import MissionControl
from gateway.fleet.vehicles.waits import (
    armed_heard_since,
    mode_heard_since,
    shown_though_unacknowledged,
    wait_for_state,
)
from gateway.link.contract import ConnectionState, GroundCommand, OnWait, Peer
from gateway.link.link_status import link_status
from gateway.link.mavsdk_system import System
from gateway.link.session import Link, LinkHooks
from gateway.link.sidecar import Confine, Sidecar
from gateway.link.telemetry import TelemetryCache
from gateway.registry.spec import VehicleSpec
from gateway.registry.store import AuditEntry, Store
from gateway.util.json_types import JsonObject
from gateway.util.read_through import ReadThrough

log = logging.getLogger("gateway.vehicle")

__all__ = ["ConnectionState", "MissionItem", "Vehicle"]

ARMABLE_WAIT_S = 60.0
#: closing the flight log never holds a link open longer than this (a database that hangs)
RECORDER_STOP_S = 5.0
POSITION_IGNORED = 0b111  # POSITION_TARGET_TYPEMASK: x, y, z ignored (a velocity or attitude target)
#: an unacknowledged goto or hold counts as run once the autopilot reports a target this near the sent one
TARGET_REPORTED_M = 2.0

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
        hooks = LinkHooks(
            dialect_for,
            peers=peers,
            confine=confine,
            on_state=self._state_changed,
            mission_progress=lambda current, total: self.missions.wire_progress(current, total),
            session_jobs=[
                ("mission", lambda system: self.missions.follow(system)),
                ("target", self._position_target),
                ("params", self._parameter_list),
            ],
            on_relay_refused=self._relay_refused,
        )
        self.link = Link(spec, settings, hooks)
        self.missions = MissionControl(self.link, self)
        self.arming = Arming(self.link, self)
        self.params = Parameters(spec.id, self.link.call, self.link.require_session)
        self._recorder: FlightRecorder | None = None
        self.origins = OriginKeeper(spec.id, self.link.telemetry, store)
        self._return_alt_name: str | None = None  # the RTL altitude parameter this vehicle has
        #: POSITION_TARGET_GLOBAL_INT: where the autopilot flies to (lat, lon, monotonic time heard)
        self._target: tuple[float, float, float] | None = None
        # the last reports (5 Hz: about 3 s), so a takeover watch that ticks late still sees a target
        # the autopilot flew only briefly before another ground station replaced it
        self._targets: deque[tuple[float, float, float]] = deque(maxlen=16)
        #: the last position target the gateway sent (goto, hold): lat, lon, monotonic time sent
        self._commanded: tuple[float, float, float] | None = None

    async def _parameter_list(self, _system: System) -> None:
        """A session's job: the autopilot's parameter list, fetched once per vehicle as its first session
        starts (an unknown name is then refused from it at once); nothing more to do after."""
        await self.params.prefetch()
        await asyncio.Event().wait()

    # --- identity, state and the link ----------------------------------------------------------------
    async def move_origin(self, lat: object, lon: object, alt_amsl_m: object, by: str) -> Origin:
        return await self.origins.move(lat, lon, alt_amsl_m, by)

    @property
    def origin(self) -> tuple[float, float, float] | None:
        """Where the distance limit and the zones count from (`gateway.fleet.policy.origin`)."""
        found = self.origins.current()
        return None if found is None else found.point

    def flown_here(self) -> FlyingVehicle:
        """This node flies it (`VehicleView.flown_here`)."""
        return self

    @property
    def dialect(self) -> DialectReads:
        """What is read through the autopilot's dialect (ArduPilot's until the first HEARTBEAT says
        otherwise; `Unsupported`'s for an autopilot the gateway has no dialect for)."""
        return dialect_for(self.link.facts.autopilot)

    def require_dialect(self) -> Dialect:
        """The dialect commands to this drone are sent through; NoDialect (saying which autopilot and
        what to do) when the gateway has none for its autopilot. Every action asks it first."""
        return flying_dialect(self.link.facts.autopilot, self.id)

    # read of the link as it is
    id = ReadThrough[str]("link")
    spec = ReadThrough[VehicleSpec]("link", writable=True)
    telemetry = ReadThrough[TelemetryCache]("link")
    sidecar = ReadThrough[Sidecar | None]("link")
    system = ReadThrough[System]("link")
    sysid = ReadThrough[int | None]("link")
    autopilot = ReadThrough[str | None]("link")
    autopilot_version = ReadThrough[str | None]("link")
    is_simulator = ReadThrough[bool]("link")
    sessions = ReadThrough[int]("link")
    last_heartbeat_age_s = ReadThrough[float | None]("link")
    sysid_mismatch = ReadThrough[bool]("link")
    duplicate_sysid = ReadThrough[list[str]]("link")
    state = ReadThrough[ConnectionState]("link")
    last_error = ReadThrough[str | None]("link")

    @property
    def current_flight_id(self) -> int | None:
        """The id of the flight being recorded (armed now), None on the ground or while not connected."""
        recorder = self._recorder
        return recorder.flight.id if recorder is not None and recorder.flight is not None else None

    def initialising(self) -> str | None:
        return self.link.initialising()

    def status(self) -> JsonObject:
        return link_status(self.link)

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
        return await wait_for_state(self, *states, within_s=within_s)

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
        self.link.want()  # connecting from this call on, not once the stored origin has been read
        try:
            await self.origins.start()  # the stored origin is known before the first home arrives
        except BaseException:
            self.link.unwant()
            raise
        await self.link.connect()  # a failed sidecar starts afresh; a running one is left alone
        if self.store is not None and self._recorder is None:
            recorder = FlightRecorder(self.link, self.heartbeat_state, self.store, self.settings)
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
            await self.origins.stop()
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

    def heartbeat_heard_at(self) -> float | None:
        return self.link.facts.last_heartbeat

    def heartbeat_state(self) -> tuple[int, int] | None:
        """(MAV_TYPE, custom mode) of the autopilot's last HEARTBEAT (the flight recorder keeps them for
        the .tlog); None before the first HEARTBEAT of the session or while it is stale."""
        facts = self.link.facts
        age = self.link.last_heartbeat_age_s
        if facts.custom_mode is None or facts.mav_type is None or age is None:
            return None
        if age > self.settings.link_lost_after_s:
            return None
        return facts.mav_type, facts.custom_mode

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
        self.require_dialect()
        choice = self.resolve_mode(name)
        self.link.require_session()
        if choice.is_hold and self.on_ground() is False:
            await self.hold()
            return
        await self.arming.switch_mode(choice)

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
        self.require_dialect()
        deadline = asyncio.get_running_loop().time() + within_s
        ready = await self.wait_initialised(within_s, notify)
        await self.arming.arm_by(deadline, ready, notify)

    async def disarm(self) -> None:
        await self._act("disarm", lambda system: system.action.disarm(), shown=self._disarmed_since)

    async def kill(self) -> None:
        """Stop the motors at once, even in the air (the policy decides who may call this)."""
        await self._act("kill", lambda system: system.action.kill(), shown=self._disarmed_since)

    async def _act(
        self,
        what: str,
        order: Callable[[System], Awaitable[None]],
        kind: str | None = None,
        shown: Callable[[float], bool] | None = None,
    ) -> None:
        """One MAVSDK action the autopilot runs as it is (``order`` picks it of the session), sent once
        the dialect check passed. An unacknowledged action counts as run once the autopilot shows its
        effect within `waits.UNACKED_WAIT_S` (a starved autopilot's ACKs come after MAVSDK's retries, as
        with the takeoff): ``shown(sent)`` says whether it does in what it reported since ``sent``
        (monotonic); ``kind``: the operation whose modes (the dialect's `commanded_modes`) show it."""
        dialect = self.require_dialect()
        modes = dialect.commanded_modes(kind) if kind else frozenset()
        if shown is None and modes:
            shown = lambda _sent: self.telemetry.fresh("flight_mode") in modes  # noqa: E731
        sent = time.monotonic()
        try:
            await self.link.call(what, order(self.link.require_session()))
        except CommandFailed as exc:
            if shown is None or not await shown_though_unacknowledged(exc, lambda: shown(sent)):
                raise
            log.warning("%s: %s unacknowledged, but the autopilot shows it (mode %s, %s): accepted",
                        self.id, what, self.telemetry.fresh("flight_mode"),
                        "armed" if self.telemetry.fresh("armed") else "disarmed")  # fmt: skip

    def _taking_off_since(self, sent: float, mode_before: str | None) -> bool:
        """What a takeoff the autopilot runs shows: in the air, or (still on the ground, PX4) switched
        since ``sent`` to a takeoff mode it was not in (ArduPilot takes off in GUIDED, its mode already)."""
        modes = self.require_dialect().commanded_modes("takeoff")
        return self.on_ground() is False or mode_heard_since(self.telemetry, sent, modes, mode_before)

    def _disarmed_since(self, sent: float) -> bool:
        return armed_heard_since(self.telemetry, sent, armed=False)

    def _target_reported(self, lat: float, lon: float) -> Callable[[float], bool]:
        """Whether the autopilot reported flying to ``lat``/``lon`` (POSITION_TARGET_GLOBAL_INT) since a
        time: what a goto or hold it ran shows."""

        def shown(sent: float) -> bool:
            return any(
                geo.horizontal_distance_m(t_lat, t_lon, lat, lon) <= TARGET_REPORTED_M
                for t_lat, t_lon, _ in self.position_targets(sent)
            )

        return shown

    async def takeoff(
        self, alt_rel_m: float, within_s: float = ARMABLE_WAIT_S, notify: OnWait | None = None
    ) -> None:
        """Arm if needed (waiting for it as ``arm`` does, up to ``within_s`` in all), then take off to
        ``alt_rel_m`` metres above home. Returns once accepted."""
        self.require_dialect()
        geo.check_finite("takeoff altitude", alt_rel_m)
        if alt_rel_m <= 0:
            raise InvalidArgument(f"takeoff altitude must be above 0 m; got {alt_rel_m:g}")
        deadline = asyncio.get_running_loop().time() + within_s
        ready = await self.wait_initialised(within_s, notify)
        system = self.system
        if self.on_ground() is False:
            raise CommandFailed(f"drone '{self.id}' is already flying; use goto to change altitude")
        # the altitude first: between arming and the takeoff command, ArduPilot's DISARM_DELAY runs;
        # MAVSDK sets it as a parameter (after the list the session fetches, if that still runs)
        await self.params.not_fetching()
        await self.link.call("set takeoff altitude", system.action.set_takeoff_altitude(float(alt_rel_m)))
        sent_arm = await self.arming.arm_by(deadline, ready, notify)
        mode_before, sent = self.telemetry.fresh("flight_mode"), time.monotonic()
        try:
            await self.link.call("takeoff", system.action.takeoff())
        except CommandFailed as exc:
            if await shown_though_unacknowledged(exc, lambda: self._taking_off_since(sent, mode_before)):
                # the autopilot took off and its ACK was lost or late past MAVSDK's retries (PX4 SIH
                # starved of CPU logged the takeoff 4 times, or showed AUTO.TAKEOFF still on the ground)
                log.warning("%s: takeoff unacknowledged, but the autopilot shows it (mode %s, %s): accepted",
                            self.id, self.telemetry.fresh("flight_mode"),
                            "on the ground" if self.on_ground() else "in the air")  # fmt: skip
                return
            if sent_arm or self.on_ground() is False:
                raise
            # "armed" came from the cache (the 1 Hz heartbeat), which can be a beat behind an autopilot
            # that disarmed on the ground after a landing: arm for real, then try once more
            log.info("%s: takeoff refused while the cache said armed; arming and trying again", self.id)
            await self.arming.arm_by(deadline, ready, notify, trust_cache=False)
            await self.link.call("takeoff", system.action.takeoff())

    def home_amsl_m(self) -> float:
        home = self.telemetry.home
        if home is None:
            raise VehicleNotReady(f"drone '{self.id}' has no home position yet", state=self.state.value)
        return home.value.abs_alt_m

    async def goto(self, lat: float, lon: float, alt_rel_m: float, yaw_deg: float | None = None) -> None:
        """Fly to lat/lon at ``alt_rel_m`` above home (converted to AMSL with the cached home)."""
        self.require_dialect()
        geo.check_lat_lon(lat, lon)
        geo.check_finite("altitude", alt_rel_m)
        if yaw_deg is not None:
            geo.check_finite("yaw", yaw_deg)
        self.require_ready()
        amsl = geo.relative_to_amsl(float(alt_rel_m), self.home_amsl_m())
        yaw = float("nan") if yaw_deg is None else float(yaw_deg) % 360.0
        self._commanded = (float(lat), float(lon), time.monotonic())
        await self._act(
            "goto",
            lambda system: system.action.goto_location(float(lat), float(lon), amsl, yaw),
            shown=self._target_reported(float(lat), float(lon)),
        )

    async def hold(self) -> None:
        """Hold position: a reposition to where the vehicle is now (never LOITER/ALT_HOLD, in which a
        copter without RC throttle descends). On the ground there is nothing to hold."""
        self.require_dialect()
        self.link.require_session()
        if self.on_ground() is not False:
            self._commanded = None  # nothing sent: no target of the gateway's to hold to
            return
        pos = self.telemetry.fresh("position")
        if pos is None:
            raise CommandFailed(f"cannot hold drone '{self.id}': no current position", vehicle_id=self.id)
        self._commanded = (pos.lat_deg, pos.lon_deg, time.monotonic())
        await self._act(
            "hold",
            lambda system: system.action.goto_location(pos.lat_deg, pos.lon_deg, pos.abs_alt_m, float("nan")),
            shown=self._target_reported(pos.lat_deg, pos.lon_deg),
        )

    async def land(self) -> None:
        await self._act("land", lambda system: system.action.land(), kind="land")

    async def return_to_launch(self) -> None:
        await self._act(
            "return to launch", lambda system: system.action.return_to_launch(), kind="return_to_launch"
        )

    async def set_yaw(self, heading_deg: float) -> None:
        """Turn to a heading (degrees from true north) in place."""
        dialect = self.require_dialect()
        geo.check_finite("heading", heading_deg)
        self.require_ready()
        await dialect.set_yaw(self.link, float(heading_deg) % 360.0)

    async def set_max_speed(self, mps: float) -> None:
        self.require_dialect()
        geo.check_finite("speed", mps)
        if mps <= 0:
            raise InvalidArgument(f"speed must be above 0 m/s; got {mps:g}")
        await self.link.call("set speed", self.link.require_session().action.set_current_speed(float(mps)))

    # --- where the autopilot flies to ---------------------------------------------------------------------
    def position_target(self) -> tuple[float, float, float] | None:
        """Where the autopilot says it flies to (POSITION_TARGET_GLOBAL_INT): latitude, longitude and
        when it said so (monotonic); None when it has not said (or not for this session)."""
        return self._target

    def position_targets(self, since: float) -> list[tuple[float, float, float]]:
        return [t for t in self._targets if t[2] >= since]

    def ground_station_commands(self, since: float) -> list[GroundCommand]:
        relay = self.link.relay
        return [] if relay is None else relay.commands_since(since)

    def _relay_refused(self, url: str, reason: str) -> None:
        """A ground station endpoint whose peer is no ground station was stopped by the relay: audited
        (its status shows the reason)."""
        if self.store is None:
            return
        try:
            self.store.queue_audit(
                AuditEntry(
                    principal="relay",
                    source="gateway",
                    vehicle_id=self.id,
                    action="gcs_endpoint_refused",
                    arguments={"endpoint": url},
                    outcome="refused",
                    error=reason,
                )
            )
        except RuntimeError:  # the store is closed: the gateway is stopping
            log.warning("%s: %s (not audited: the store is closed)", self.id, reason)

    def commanded_target(self) -> tuple[float, float, float] | None:
        """The last position target the gateway sent (a goto or a hold): latitude, longitude and when it
        was sent (monotonic, just before); None when the last hold sent nothing (on the ground)."""
        return self._commanded

    async def _position_target(self, system: System) -> None:
        """POSITION_TARGET_GLOBAL_INT (the link asks for it at 5 Hz with the other rates): the target a
        goto's takeover watch compares with the gateway's own."""
        self._target = None
        self._targets.clear()
        async for msg in system.mavlink_direct.message("POSITION_TARGET_GLOBAL_INT"):
            fields = json.loads(msg.fields_json)
            if int(fields.get("type_mask", 0)) & POSITION_IGNORED == POSITION_IGNORED:
                continue  # no position in it
            lat, lon = int(fields.get("lat_int", 0)) / 1e7, int(fields.get("lon_int", 0)) / 1e7
            if lat or lon:
                self._target = (lat, lon, time.monotonic())
                self._targets.append(self._target)

    # --- missions (gateway.fleet.vehicles.vehicle_missions) -------------------------------------------------
    async def upload_mission(self, items: Sequence[MissionItem | dict[str, object]]) -> int:
        return await self.missions.upload(items)

    async def download_mission(self) -> list[MissionItem]:
        return await self.missions.download()

    async def clear_mission(self) -> None:
        await self.missions.clear()

    async def start_mission(self) -> None:
        await self.missions.start()

    async def set_current_mission_item(self, user_index: int) -> None:
        await self.missions.set_current(user_index)

    async def is_mission_finished(self) -> bool:
        return await self.missions.is_finished()

    # --- parameters (gateway.fleet.vehicles.params) ---------------------------------------------------------
    def return_altitude_param(self) -> tuple[str, float]:
        """The parameter that sets the altitude RTL flies home at, and its units per metre (ArduPilot
        4.7: RTL_ALT_M in metres, before: RTL_ALT in centimetres; PX4: RTL_RETURN_ALT in metres)."""
        candidates = self.require_dialect().return_altitude_params
        return next((c for c in candidates if c[0] == self._return_alt_name), candidates[0])

    async def set_return_altitude(self, alt_m: float) -> tuple[str, float | int]:
        """Set the altitude RTL climbs to before flying home (metres above home) in the parameter and
        units this autopilot has; returns (parameter, value written)."""
        candidates = self.require_dialect().return_altitude_params
        geo.check_finite("return altitude", alt_m)
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
        self.require_dialect()
        return await self.params.get(name)

    async def set_param(self, name: str, value: float | int) -> tuple[float | int, str]:
        """Write a parameter with the vehicle's own type for it; returns (stored value, type)."""
        self.require_dialect()
        return await self.params.set(name, value)

    async def list_params(self, max_age_s: float | None = None) -> dict[str, float | int]:
        """All parameters, fetched once and cached; ``max_age_s`` forces a refetch of an older copy."""
        self.require_dialect()
        return await self.params.all(max_age_s)

    @property
    def params_fetched_age_s(self) -> float | None:
        return self.params.list_age_s
