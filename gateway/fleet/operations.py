"""Long-running vehicle actions as tracked operations.

A takeoff, goto, landing or mission is an *operation*: the command is sent once, then a monitor task
follows the vehicle's telemetry until the action is done (altitude reached, arrived, landed and
disarmed, mission finished), failed, or superseded by a newer command. Callers (the MCP tools, REST)
*wait* on an operation with a cap; a waiter going away never touches the vehicle. One current
operation per vehicle; each is saved through the Store so its fate outlives the request that made it.

The manager also watches each vehicle's HEARTBEAT mode against what the gateway last commanded it
(`expect`, `gateway.fleet.takeover`): a mode the gateway did not send ends the operation as
``interrupted`` and hands the takeover to ``on_takeover`` (the drone is locked for agents).

No MCP or HTTP in here.
"""

from __future__ import annotations

import asyncio
import contextlib
import logging
import math
import time
import uuid
from collections.abc import Awaitable, Callable, Iterable
from dataclasses import dataclass, field
from datetime import UTC, datetime
from enum import StrEnum
from typing import Any, Protocol

from gateway.config import Settings
from gateway.errors import InvalidArgument, NotFound
from gateway.fleet import geo
from gateway.fleet.protocols import FlyingVehicle, VehicleView
from gateway.fleet.readings import (
    age_s,
    climb_rate,
    ground_speed,
    home,
    is_landed,
    is_landed_and_disarmed,
    position,
    value,
)
from gateway.fleet.safety import Lock, RunningOperation
from gateway.fleet.takeover import CAUSE_WINDOW_S, ModeExpectation, Takeover, likely_cause
from gateway.registry.records import OperationRecord
from gateway.registry.store import Store

log = logging.getLogger(__name__)

POLL_S = 0.2
"""How often a monitor looks at the telemetry cache (the cache itself is updated by streams)."""
LEFT_AUTO_GRACE_S = 2.0
"""How long a mission may be out of AUTO before the operation fails (the gateway's own pause supersedes
the operation right after switching mode)."""
SAVE_EVERY_S = 2.0
"""Progress of a running operation is written to the store at most this often."""
MISSION_END_GRACE_S = 0.8
"""How long a mission that left its mode for one it settles in (PX4 holds at the end) may take to say
it finished before the change counts as a takeover."""
TARGET_SETTLE_S = 1.5
"""How long after a goto was sent the autopilot's reported target may still be the one before it."""
TARGET_MOVED_M = 10.0
"""How far the autopilot's target may be from the goto's (at least 3 arrival tolerances) before another
ground station is taken to have moved it."""
TARGET_CONFIRM_S = 0.9
"""How long the target must stay moved (two reports at 2 Hz) before it counts as a takeover."""
FOUND_FLYING_WAIT_S = 120.0
"""After a restart: how long the gateway waits for a vehicle's first HEARTBEAT and landed state before it
gives up looking whether the vehicle is flying (its mode watch is then armed by its next command)."""


class OpStatus(StrEnum):
    running = "running"
    succeeded = "succeeded"
    failed = "failed"
    superseded = "superseded"
    interrupted = "interrupted"
    cancelled = "cancelled"


FINAL = frozenset(s for s in OpStatus if s is not OpStatus.running)


@dataclass
class Poll:
    """One look at the vehicle by a tracker."""

    progress: float
    message: str
    done: bool = False
    failed: str | None = None
    eta_s: float | None = None
    then: Callable[[], Awaitable[Any]] | None = None
    """The operation's next command, for the manager to send (under the drone's command lock, only while
    the operation still runs): the leg of a `ClimbThenGoTracker` once its climb is done."""


class Tracker(Protocol):
    """Judges an operation from the vehicle's telemetry. ``poll`` is called every POLL_S seconds."""

    kind: str

    async def poll(self, vehicle: FlyingVehicle) -> Poll: ...


def is_climbing(op: Operation, tracker: Tracker | None) -> bool:
    """Whether the operation is a takeoff still climbing: a takeoff, or an operation that took off first
    and has not reached its altitude yet (the takeoff guard holds other commands back meanwhile)."""
    return op.kind == "takeoff" or bool(getattr(tracker, "climbing", False))


@dataclass
class Operation:
    id: str
    vehicle_id: str
    kind: str
    params: dict[str, Any]
    session_key: str | None
    created_at: datetime
    status: OpStatus = OpStatus.running
    progress: float = 0.0
    message: str = "command sent"
    #: what every later message keeps saying (e.g. that another node took the operation over)
    note: str | None = None
    eta_s: float | None = None
    updated_at: datetime | None = None
    finished_at: datetime | None = None
    started_mono: float = field(default_factory=time.monotonic)
    changed: asyncio.Event = field(default_factory=asyncio.Event, repr=False)
    done: asyncio.Event = field(default_factory=asyncio.Event, repr=False)

    @property
    def finished(self) -> bool:
        return self.status in FINAL

    def elapsed_s(self) -> float:
        return time.monotonic() - self.started_mono

    def to_dict(self) -> dict[str, Any]:
        return {
            "operation_id": self.id,
            "drone_id": self.vehicle_id,
            "kind": self.kind,
            "status": self.status.value,
            "progress": round(self.progress, 3),
            "message": self.message,
            "eta_s": None if self.eta_s is None else round(self.eta_s, 1),
            "elapsed_s": round(self.elapsed_s(), 1),
            "params": self.params,
        }


ProgressCallback = Callable[[Operation], Awaitable[None]]
TakeoverHandler = Callable[[FlyingVehicle, Takeover], Awaitable[None]]


def _now() -> datetime:
    return datetime.now(UTC)


def takeoff_tolerance_m(target_alt_m: float) -> float:
    """How close to the takeoff altitude counts as reached (ArduPilot stops a little short)."""
    return min(1.0, max(0.3, 0.05 * target_alt_m))


# ------------------------------------------------------------------------------------------------
# Trackers: what "done" means for each kind of operation
# ------------------------------------------------------------------------------------------------


@dataclass
class TakeoffTracker:
    target_alt_m: float
    kind: str = "takeoff"
    _seen_armed: bool = False

    async def poll(self, vehicle: FlyingVehicle) -> Poll:
        pos = position(vehicle)
        armed = value(vehicle, "armed")
        if armed:
            self._seen_armed = True
        elif self._seen_armed and armed is False:
            return Poll(0.0, "vehicle disarmed during takeoff", failed="vehicle disarmed during takeoff")
        if pos is None:
            return Poll(0.0, "waiting for position telemetry")
        alt = pos[2]
        remaining = self.target_alt_m - alt
        progress = max(0.0, min(1.0, alt / self.target_alt_m))
        if remaining <= takeoff_tolerance_m(self.target_alt_m):
            return Poll(1.0, f"reached {alt:.1f} m above home", done=True, eta_s=0.0)
        rate = climb_rate(vehicle)
        eta = remaining / max(rate or 0.0, 0.5) if rate and rate > 0.2 else remaining / 1.0
        return Poll(progress, f"climbing: {alt:.1f} of {self.target_alt_m:.1f} m", eta_s=eta)


@dataclass
class GotoTracker:
    """Arrived = within the horizontal tolerance and about at the target altitude."""

    lat: float
    lon: float
    alt_rel_m: float
    tolerance_m: float
    kind: str = "goto"
    _start_dist: float | None = None

    def distance(self, vehicle: VehicleView) -> tuple[float, float] | None:
        pos = position(vehicle)
        if pos is None:
            return None
        return geo.horizontal_distance_m(pos[0], pos[1], self.lat, self.lon), self.alt_rel_m - pos[2]

    async def poll(self, vehicle: FlyingVehicle) -> Poll:
        if value(vehicle, "armed") is False or is_landed(vehicle):
            return Poll(0.0, "vehicle is not flying", failed="vehicle landed or disarmed before arriving")
        d = self.distance(vehicle)
        if d is None:
            return Poll(0.0, "waiting for position telemetry")
        horiz, dz = d
        dist3 = math.hypot(horiz, dz)
        if self._start_dist is None:
            self._start_dist = max(dist3, 0.01)
        progress = max(0.0, min(1.0, 1.0 - dist3 / self._start_dist))
        if horiz <= self.tolerance_m and abs(dz) <= max(self.tolerance_m, 1.0):
            return Poll(1.0, f"arrived ({horiz:.1f} m from target)", done=True, eta_s=0.0)
        speed = ground_speed(vehicle)
        eta = dist3 / max(speed or 0.0, 1.0)
        return Poll(progress, f"{horiz:.0f} m to go, {dz:+.1f} m vertical", eta_s=eta)


@dataclass
class ClimbThenGoTracker:
    """One operation from the ground: take off to the leg's altitude, then fly the leg there. The leg's
    command (``send_leg``) is sent by the manager only once the climb is reached, so the takeoff guard's
    rule (nothing but the climb until it is done: the source paper's crash was a goto sent mid-climb)
    holds inside the operation too, and the guard refuses other commands while ``climbing``."""

    takeoff: TakeoffTracker
    leg: GotoTracker
    send_leg: Callable[[], Awaitable[Any]]
    kind: str = "move_to_relative"
    climbing: bool = True

    async def poll(self, vehicle: FlyingVehicle) -> Poll:
        if not self.climbing:
            return await self.leg.poll(vehicle)
        climb = await self.takeoff.poll(vehicle)
        if climb.failed is not None:
            return climb
        target = self.takeoff.target_alt_m
        if not climb.done:
            return Poll(0.3 * climb.progress, f"taking off first: {climb.message}", eta_s=climb.eta_s)
        self.climbing = False
        return Poll(0.3, f"took off to {target:g} m; flying the leg", then=self.send_leg)


@dataclass
class YawTracker:
    heading_deg: float
    kind: str = "set_yaw"
    tolerance_deg: float = 5.0

    async def poll(self, vehicle: FlyingVehicle) -> Poll:
        heading = value(vehicle, "heading_deg")
        if heading is None:
            return Poll(0.0, "waiting for heading telemetry")
        err = abs((float(heading) - self.heading_deg + 180.0) % 360.0 - 180.0)
        if err <= self.tolerance_deg:
            return Poll(1.0, f"heading {float(heading):.0f} deg", done=True, eta_s=0.0)
        return Poll(max(0.0, 1.0 - err / 180.0), f"turning: {err:.0f} deg to go", eta_s=err / 30.0)


@dataclass
class LandingTracker:
    """Land and RTL: done once landed and disarmed (ArduPilot disarms itself after touchdown)."""

    kind: str = "land"
    _start: tuple[float, float] | None = None  # (altitude, horizontal distance to home) at start

    async def poll(self, vehicle: FlyingVehicle) -> Poll:
        if is_landed_and_disarmed(vehicle):
            return Poll(1.0, "landed and disarmed", done=True, eta_s=0.0)
        pos = position(vehicle)
        if pos is None:
            return Poll(0.0, "waiting for position telemetry")
        alt = max(pos[2], 0.0)
        horiz = 0.0
        h = home(vehicle)
        if self.kind == "return_to_launch" and h is not None:
            horiz = geo.horizontal_distance_m(pos[0], pos[1], h[0], h[1])
        if self._start is None:
            self._start = (max(alt, 0.1), horiz)
        total = self._start[0] + self._start[1]
        progress = max(0.0, min(0.99, 1.0 - (alt + horiz) / max(total, 0.1)))
        speed = ground_speed(vehicle) or 0.0
        eta = horiz / max(speed, 1.0) + alt / 1.0
        if is_landed(vehicle):
            return Poll(0.99, "on the ground, waiting for disarm", eta_s=3.0)
        where = f"{horiz:.0f} m from home, " if self.kind == "return_to_launch" else ""
        return Poll(progress, f"{where}{alt:.1f} m above home", eta_s=eta)


@dataclass
class MissionTracker:
    """Done when the autopilot says the mission is finished (asked at most once a second)."""

    kind: str = "mission"
    _asked_at: float = 0.0
    _seen_auto: bool = False
    _left_auto_at: float | None = None

    async def poll(self, vehicle: FlyingVehicle) -> Poll:
        prog = value(vehicle, "mission_progress")
        current, total = (int(prog.current), int(prog.total)) if prog is not None else (0, 0)
        left = self._left_auto(vehicle)
        if left is not None:
            return Poll(
                0.0,
                left,
                failed=f"{left} at item {current} of {total}; the mission is no longer being flown",
            )
        now = time.monotonic()
        if now - self._asked_at >= 1.0:
            self._asked_at = now
            if await vehicle.is_mission_finished():
                return Poll(1.0, f"mission finished ({total} items)", done=True, eta_s=0.0)
        progress = max(0.0, min(0.99, (current - 1) / total)) if total else 0.0
        return Poll(progress, f"item {current} of {total}")

    def _left_auto(self, vehicle: FlyingVehicle) -> str | None:
        """The autopilot itself left AUTO (a failsafe, a pilot, another ground station) for longer than
        LEFT_AUTO_GRACE_S. The gateway's own pause/hold supersedes the operation before that."""
        mode = value(vehicle, "flight_mode")
        if mode is None:
            return None
        if str(mode).upper() in ("AUTO", "MISSION", "AUTO.MISSION"):
            self._seen_auto, self._left_auto_at = True, None
            return None
        if not self._seen_auto:
            return None
        now = time.monotonic()
        if self._left_auto_at is None:
            self._left_auto_at = now
        if now - self._left_auto_at < LEFT_AUTO_GRACE_S:
            return None
        return f"the autopilot switched from AUTO to {mode} (failsafe, pilot or another ground station)"


# ------------------------------------------------------------------------------------------------
# The manager
# ------------------------------------------------------------------------------------------------


class OperationManager:
    """One current operation per vehicle; monitors run independently of whoever waits on them."""

    def __init__(self, settings: Settings, store: Store | None = None) -> None:
        """``store`` None keeps operations in memory only (unit tests of the trackers)."""
        self.settings = settings
        self.store = store
        self._ops: dict[str, Operation] = {}
        self._current: dict[str, Operation] = {}  # latest operation per vehicle (may be finished)
        self._monitors: dict[str, asyncio.Task[None]] = {}
        self._trackers: dict[str, Tracker] = {}  # of the running operations
        self._last_saved: dict[str, float] = {}
        self._locks: dict[str, asyncio.Lock] = {}
        self._expected: dict[str, ModeExpectation] = {}  # what the gateway last commanded, per vehicle
        self._watches: dict[str, asyncio.Task[None]] = {}
        self._finders: dict[str, asyncio.Task[None]] = {}  # after a restart: is the vehicle flying?
        self._sent_at: dict[str, float] = {}  # when an operation's latest command (its leg) was sent
        # the leg (its send time) whose target the autopilot has been seen flying to, per operation
        self._adopted: dict[str, float] = {}
        #: told of every takeover before its operation ends (the runtime locks the drone)
        self.on_takeover: TakeoverHandler | None = None
        #: the drone's takeover lock, if it has one (the runtime reads the LockBook)
        self.taken_over: Callable[[str], Lock | None] = lambda _vehicle_id: None

    # -- queries -------------------------------------------------------------------------------
    def get(self, operation_id: str) -> Operation:
        try:
            return self._ops[operation_id]
        except KeyError:
            raise NotFound(f"no operation with id '{operation_id}'") from None

    def latest(self, vehicle_id: str) -> Operation | None:
        """The vehicle's most recent operation, running or finished."""
        return self._current.get(vehicle_id)

    def running(self, vehicle_id: str) -> Operation | None:
        op = self._current.get(vehicle_id)
        return op if op is not None and not op.finished else None

    def takeoff_in_progress(self, vehicle_id: str) -> Operation | None:
        """The running takeoff that has not yet reached its altitude, if any (also an operation that
        takes off first, while it climbs)."""
        op = self.running(vehicle_id)
        return op if op is not None and is_climbing(op, self._trackers.get(op.id)) else None

    def running_facts(self, vehicle_id: str, kind: str | None = None) -> RunningOperation | None:
        """The vehicle's running operation (of ``kind``, if given) as the safety policy sees it; an
        operation that takes off first is a ``takeoff`` while it climbs."""
        op = self.running(vehicle_id)
        if op is None:
            return None
        op_kind = "takeoff" if is_climbing(op, self._trackers.get(op.id)) else op.kind
        if kind is not None and op_kind != kind:
            return None
        target = op.params.get("alt_m")
        return RunningOperation(
            op.id, op_kind, op.message, float(target) if isinstance(target, int | float) else None
        )

    # -- commands --------------------------------------------------------------------------------
    def command_lock(self, vehicle_id: str) -> asyncio.Lock:
        """The drone's command lock: every command to one drone is sent under it, one at a time (`start`
        here, the Commander's instant commands too). It is held while a command is checked and *sent*
        (usually well under a second; at most as long as the send takes, e.g. a takeoff whose arming
        the autopilot refuses while it initialises), never while an operation runs."""
        return self._locks.setdefault(vehicle_id, asyncio.Lock())

    async def start(
        self,
        vehicle: FlyingVehicle,
        tracker: Tracker,
        send: Callable[[], Awaitable[Any]],
        params: dict[str, Any],
        session_key: str | None = None,
        precheck: Callable[[], None] | None = None,
    ) -> Operation:
        """Send the command (``send``); if the vehicle accepts it, track it as the vehicle's operation.

        Commands on one vehicle are serialised; ``precheck`` runs inside that critical section, so a
        check such as "no takeoff in progress" also sees a takeoff whose command is still being sent
        (LLM hosts issue parallel tool calls). A command that fails raises and leaves the current
        operation as it was: the vehicle is still doing it. On success the previous one is superseded.
        """
        async with self.command_lock(vehicle.id):
            if precheck is not None:
                precheck()
            await send()
            op = Operation(
                id=uuid.uuid4().hex[:12],
                vehicle_id=vehicle.id,
                kind=tracker.kind,
                params=params,
                session_key=session_key,
                created_at=_now(),
            )
            previous = self.running(vehicle.id)
            if previous is not None:
                await self._finish(previous, OpStatus.superseded, f"superseded by {op.kind} {op.id}")
            self._ops[op.id] = op
            self._current[vehicle.id] = op
            self._trackers[op.id] = tracker
            self.expect(vehicle, op.kind, op.id, _climb_modes(vehicle, op.kind, tracker))
            await self._save(op, force=True)
            self._monitors[op.id] = asyncio.create_task(
                self._monitor(vehicle, op, tracker), name=f"op-{op.kind}-{op.id}"
            )
            return op

    # -- what the gateway commanded, and takeovers -------------------------------------------------
    def expect(
        self,
        vehicle: FlyingVehicle,
        kind: str | None,
        operation_id: str | None = None,
        modes: frozenset[str] | None = None,
    ) -> None:
        """Record what the gateway just commanded ``vehicle`` (called under its command lock, after the
        command was accepted): an operation of ``kind``, or an instant command whose ``modes`` are
        given (a mode change); None: nothing the mode can be judged by (kill, disarm). From then on a
        change to a mode the gateway did not command ends the operation (`gateway.fleet.takeover`)."""
        wanted = modes if modes is not None else (vehicle.commanded_modes(kind) if kind else frozenset())
        if not wanted or kind is None:
            self._expected.pop(vehicle.id, None)
            return
        settled = modes if modes is not None else vehicle.commanded_modes(kind, done=True)
        self._expected[vehicle.id] = ModeExpectation(kind, wanted, settled | wanted, operation_id)
        watch = self._watches.get(vehicle.id)
        if watch is None or watch.done():
            self._watches[vehicle.id] = asyncio.create_task(self._watch(vehicle), name=f"watch-{vehicle.id}")

    def expected(self, vehicle_id: str) -> ModeExpectation | None:
        return self._expected.get(vehicle_id)

    def forget(self, vehicle_id: str) -> None:
        """The gateway commands nothing the mode shows (a takeover, kill): nothing more is judged."""
        self._expected.pop(vehicle_id, None)

    def watch_found_flying(self, vehicles: Iterable[FlyingVehicle]) -> None:
        """After a restart: every vehicle found armed in the air gets its mode watch again, so a pilot's
        later switch is a takeover as before. It is judged by what the gateway last commanded it (its
        newest stored operation) while the vehicle is in one of that command's modes; in any other mode
        (the process died before it commanded one, or someone switched meanwhile) by the mode it was
        found in. Each vehicle is looked at once its HEARTBEAT and landed state are known."""
        for vehicle in vehicles:
            task = self._finders.get(vehicle.id)
            if task is None or task.done():
                self._finders[vehicle.id] = asyncio.create_task(
                    self._found_flying(vehicle), name=f"found-flying-{vehicle.id}"
                )

    async def _found_flying(self, vehicle: FlyingVehicle) -> None:
        try:
            deadline = time.monotonic() + FOUND_FLYING_WAIT_S
            while (heard := vehicle.heartbeat_mode()) is None or (
                heard[1] and vehicle.on_ground(fresh=False) is None
            ):
                if time.monotonic() > deadline:
                    log.info(
                        "%s: no HEARTBEAT after the restart; its mode watch waits for a command", vehicle.id
                    )
                    return
                await asyncio.sleep(POLL_S)
            mode, armed = heard
            if not armed or vehicle.on_ground(fresh=False) is not False:
                return  # on the ground: its next arming and command start afresh
            if not vehicle.commanded_modes("goto"):
                return  # an autopilot the gateway has no dialect for: it commands it nothing
            if vehicle.id in self._expected or self.taken_over(vehicle.id) is not None:
                return  # a command since the restart (its own watch), or a pilot has it already
            record = await self._newest_record(vehicle.id)
            kind = record.kind if record is not None else None
            modes = (
                (vehicle.commanded_modes(kind) | vehicle.commanded_modes(kind, done=True)) if kind else None
            )
            if vehicle.id in self._expected:
                return
            if kind is not None and modes and mode in modes:
                exp = ModeExpectation(kind, modes, modes, seen=True, last_mode=mode)
            else:
                found = frozenset({mode})
                exp = ModeExpectation(f"found flying in {mode}", found, found, seen=True, last_mode=mode)
            self._expected[vehicle.id] = exp
            log.info(
                "%s: found flying in %s after the restart; its mode watch is on (%s)",
                vehicle.id,
                mode,
                exp.kind,
            )
            watch = self._watches.get(vehicle.id)
            if watch is None or watch.done():
                self._watches[vehicle.id] = asyncio.create_task(
                    self._watch(vehicle), name=f"watch-{vehicle.id}"
                )
        except asyncio.CancelledError:
            raise
        except Exception:  # a restart must go on whatever one vehicle's look does
            log.exception("looking whether %s is flying after the restart failed", vehicle.id)
        finally:
            if self._finders.get(vehicle.id) is asyncio.current_task():
                self._finders.pop(vehicle.id, None)

    async def _newest_record(self, vehicle_id: str) -> OperationRecord | None:
        if self.store is None:
            return None
        records = await self.store.list_operations(vehicle_id=vehicle_id, limit=1)
        return records[0] if records else None

    async def _watch(self, vehicle: FlyingVehicle) -> None:
        """Judge the vehicle's HEARTBEAT mode every POLL_S while the gateway expects something of it."""
        while vehicle.id in self._expected:
            await asyncio.sleep(POLL_S)
            try:
                await self._judge_mode(vehicle)
            except asyncio.CancelledError:
                raise
            except Exception:  # the watch must never die silently
                log.exception("mode watch of %s failed", vehicle.id)
        self._watches.pop(vehicle.id, None)

    async def _judge_mode(self, vehicle: FlyingVehicle) -> None:
        exp = self._expected.get(vehicle.id)
        if exp is None or self.command_lock(vehicle.id).locked():
            return  # the gateway is sending a command: the mode it brings is its own
        heard = vehicle.heartbeat_mode()
        if heard is None:
            return
        mode, armed = heard
        if not armed:  # on the ground, disarmed: nothing flies; the next arming starts afresh
            exp.seen, exp.outside_since, exp.target_off_since = False, None, None
            return
        op = self._current.get(vehicle.id)
        mine = op if op is not None and op.id == exp.operation_id else None
        done = mine is not None and mine.status is OpStatus.succeeded
        running = mine if mine is not None and not mine.finished else None
        if mode in exp.modes or (done and mode in exp.settled):
            exp.seen, exp.outside_since, exp.last_mode = True, None, mode
            moved = self._retargeted(vehicle, exp, running)
            if moved is not None:
                await self._taken(vehicle, exp, mode, running, moved)
            return
        if not exp.seen:
            return  # the command's own mode has not shown yet
        if exp.kind == "mission" and mode in exp.settled:  # the mission may just have ended
            now = time.monotonic()
            exp.outside_since = exp.outside_since or now
            if await vehicle.is_mission_finished():
                exp.modes, exp.last_mode = exp.settled, mode  # it ended: where it settles is commanded
                return  # (a tracked mission's tracker ends it as succeeded)
            if now - exp.outside_since < MISSION_END_GRACE_S:
                return
        await self._taken(vehicle, exp, mode, running)

    def _retargeted(self, vehicle: FlyingVehicle, exp: ModeExpectation, op: Operation | None) -> float | None:
        """How far (m) the autopilot's own target (POSITION_TARGET_GLOBAL_INT) is from the running goto's
        once it has been off for TARGET_CONFIRM_S: another ground station repositioned or paused the
        drone in the mode the gateway commanded (QGroundControl's Pause or "Go to location" on PX4,
        whose gotos fly in Hold; Mission Planner's "Fly to here" in GUIDED). None while it is not."""
        tracker = self._trackers.get(op.id) if op is not None else None
        if op is None or tracker is None or getattr(tracker, "climbing", False):
            return None
        leg = getattr(tracker, "leg", tracker)
        target = vehicle.position_target()
        if not isinstance(leg, GotoTracker) or target is None:
            return None
        lat, lon, heard_at = target
        sent = self._sent_at.get(op.id, op.started_mono)
        off = geo.horizontal_distance_m(lat, lon, leg.lat, leg.lon)
        if off <= max(TARGET_MOVED_M, 3 * leg.tolerance_m):
            exp.target_off_since = None
            if heard_at >= sent:
                self._adopted[op.id] = sent  # it flies this leg: from now on a move away is someone else's
            return None
        if heard_at < sent + TARGET_SETTLE_S:
            exp.target_off_since = None  # said before the command could show in it
            return None
        if self._adopted.get(op.id) != sent:
            # not yet seen flying this leg's target: a report from before it, which a loaded link or
            # gateway can hand over long after it was said, never counts as a takeover
            exp.target_off_since = None
            return None
        if exp.target_off_since is None:
            exp.target_off_since = heard_at
        return off if heard_at - exp.target_off_since >= TARGET_CONFIRM_S else None

    async def _taken(
        self,
        vehicle: FlyingVehicle,
        exp: ModeExpectation,
        mode: str,
        running: Operation | None,
        moved_m: float | None = None,
    ) -> None:
        """A takeover: the drone is locked first (whoever hears the operation end finds it locked), then
        the running operation ends as interrupted."""
        if self._expected.get(vehicle.id) is not exp or self.command_lock(vehicle.id).locked():
            return  # a command went out meanwhile
        said: str | None = None
        if moved_m is not None:
            cause = (
                f"another ground station repositioned or paused it (its target is {moved_m:.0f} m from the "
                "gateway's)"
            )
        else:
            cause, said = likely_cause(mode, vehicle.recent_texts(CAUSE_WINDOW_S))
        takeover = Takeover(
            vehicle_id=vehicle.id,
            from_mode=exp.last_mode or "?",
            to_mode=mode,
            cause=cause,
            said=said,
            at=_now(),
            operation_id=running.id if running is not None else None,
            operation_kind=running.kind if running is not None else exp.kind,
            retargeted=moved_m is not None,
        )
        self._expected.pop(vehicle.id, None)
        log.warning("%s: %s", vehicle.id, takeover.message())
        if self.on_takeover is not None:
            try:
                await self.on_takeover(vehicle, takeover)
            except Exception:
                log.exception("recording the takeover of %s failed", vehicle.id)
        if running is not None:
            await self._finish(running, OpStatus.interrupted, takeover.message())

    async def supersede(self, vehicle_id: str, by: str) -> Operation | None:
        """A non-tracked command (hold, mode change, kill, disarm) replaced the current operation."""
        op = self.running(vehicle_id)
        if op is not None:
            await self._finish(op, OpStatus.superseded, f"superseded by {by}")
        return op

    async def wait(
        self,
        op: Operation,
        cap_s: float | None = None,
        on_progress: ProgressCallback | None = None,
    ) -> Operation:
        """Wait until ``op`` is finished or ``cap_s`` passed; report progress on each change.

        Cancelling the waiter only ends the wait: the monitor (and the vehicle) carry on.
        """
        cap = self.settings.mcp_wait_cap_s if cap_s is None else cap_s
        deadline = time.monotonic() + max(0.0, cap)
        last_reported: tuple[float, str] | None = None
        while not op.finished:
            remaining = deadline - time.monotonic()
            if remaining <= 0:
                break
            op.changed.clear()
            with contextlib.suppress(TimeoutError):
                await asyncio.wait_for(op.changed.wait(), timeout=min(remaining, 1.0))
            if on_progress is not None and (op.progress, op.message) != last_reported:
                last_reported = (op.progress, op.message)
                try:
                    await on_progress(op)
                except Exception:  # a client that cannot take progress still gets its answer
                    log.debug("progress report for %s failed", op.id, exc_info=True)
        return op

    async def recover(self) -> int:
        """At start: operations a previous gateway process left 'running' are recorded as interrupted
        (their monitors died with it). Returns how many were found."""
        store = self.store
        if store is None:
            return 0
        stale = [
            r for r in await store.list_operations(status="running", limit=1000) if r.id not in self._ops
        ]
        for record in stale:
            now = _now()
            await store.save_operation(
                record.model_copy(
                    update={
                        "status": OpStatus.interrupted.value,
                        "message": "the gateway restarted while this operation was running",
                        "updated_at": now,
                        "finished_at": now,
                    }
                )
            )
        return len(stale)

    async def stop(self) -> None:
        """Gateway shutdown: monitors end, running operations are recorded as interrupted."""
        for op in list(self._ops.values()):
            if not op.finished:
                await self._finish(
                    op, OpStatus.interrupted, "gateway stopped while the operation was running"
                )
        self._expected.clear()
        tasks = [*self._monitors.values(), *self._watches.values(), *self._finders.values()]
        for task in tasks:
            task.cancel()
        for task in tasks:
            with contextlib.suppress(asyncio.CancelledError, Exception):
                await task
        self._monitors.clear()
        self._watches.clear()
        self._finders.clear()

    async def resume(
        self, record: OperationRecord, vehicle: FlyingVehicle, tracker: Tracker, message: str
    ) -> Operation:
        """Follow an operation another process started (a cluster node that was lost): same id, kind and
        params, tracked again from the vehicle's telemetry here."""
        op = Operation(
            id=record.id,
            vehicle_id=record.vehicle_id,
            kind=record.kind,
            params=dict(record.params or {}),
            session_key=record.session_key,
            created_at=record.created_at,
            progress=float(record.progress or 0.0),
            message=message,
            note=message,
            updated_at=_now(),
        )
        previous = self.running(vehicle.id)
        if previous is not None:
            await self._finish(previous, OpStatus.superseded, f"superseded by {op.kind} {op.id}")
        self._ops[op.id] = op
        self._current[vehicle.id] = op
        self._trackers[op.id] = tracker
        self.expect(vehicle, op.kind, op.id, _climb_modes(vehicle, op.kind, tracker))
        await self._save(op, force=True)
        self._monitors[op.id] = asyncio.create_task(
            self._monitor(vehicle, op, tracker), name=f"op-{op.kind}-{op.id}"
        )
        return op

    # -- internals -------------------------------------------------------------------------------
    async def _monitor(self, vehicle: FlyingVehicle, op: Operation, tracker: Tracker) -> None:
        stale_after = float(getattr(self.settings, "link_lost_after_s", 3.0))
        try:
            while not op.finished:
                pos_age = age_s(vehicle, "position")
                interruption = _interruption(vehicle)
                if interruption is not None:
                    self._update(op, op.progress, interruption, op.eta_s)
                elif pos_age is not None and pos_age > stale_after:
                    self._update(op, op.progress, f"no telemetry for {pos_age:.0f} s (link lost?)", op.eta_s)
                else:
                    poll = await tracker.poll(vehicle)
                    if op.finished:
                        break
                    if poll.failed:
                        await self._finish(op, OpStatus.failed, poll.failed)
                        break
                    if poll.then is not None and not await self._send_next(vehicle, op, poll.then):
                        break
                    if poll.done:
                        op.progress = 1.0
                        op.eta_s = 0.0
                        await self._finish(op, OpStatus.succeeded, poll.message)
                        break
                    self._update(op, poll.progress, poll.message, poll.eta_s)
                    await self._save(op)
                await asyncio.sleep(POLL_S)
        except asyncio.CancelledError:
            raise
        except Exception as exc:  # a monitor must never die silently
            log.exception("monitor of operation %s failed", op.id)
            await self._finish(op, OpStatus.failed, f"monitoring failed: {exc}")
        finally:
            self._monitors.pop(op.id, None)
            self._trackers.pop(op.id, None)
            self._sent_at.pop(op.id, None)
            self._adopted.pop(op.id, None)

    async def _send_next(
        self, vehicle: FlyingVehicle, op: Operation, send: Callable[[], Awaitable[Any]]
    ) -> bool:
        """Send the operation's next command under the drone's command lock, unless another command
        ended the operation meanwhile; False when it is not (any more) to be followed."""
        async with self.command_lock(vehicle.id):
            if op.finished:
                return False
            try:
                await send()
            except Exception as exc:
                message = getattr(exc, "message", None) or str(exc) or type(exc).__name__
                await self._finish(op, OpStatus.failed, f"the next leg was not accepted: {message}")
                return False
            self._sent_at[op.id] = time.monotonic()
        return True

    def _update(self, op: Operation, progress: float, message: str, eta_s: float | None) -> None:
        message = _noted(op, message)
        if (progress, message) != (op.progress, op.message):
            op.progress = max(op.progress, progress) if op.kind != "set_yaw" else progress
            op.message = message
            op.eta_s = eta_s
            op.updated_at = _now()
            op.changed.set()

    async def _finish(self, op: Operation, status: OpStatus, message: str) -> None:
        if op.finished:
            return
        op.status = status
        op.message = _noted(op, message)
        op.finished_at = op.updated_at = _now()
        if status is not OpStatus.succeeded:
            op.eta_s = None
        op.changed.set()
        op.done.set()
        task = self._monitors.get(op.id)
        if task is not None and task is not asyncio.current_task():
            task.cancel()
        await self._save(op, force=True)

    async def _save(self, op: Operation, force: bool = False) -> None:
        store = self.store
        if store is None:
            return
        now = time.monotonic()
        if not force and now - self._last_saved.get(op.id, 0.0) < SAVE_EVERY_S:
            return
        self._last_saved[op.id] = now
        try:
            await store.save_operation(
                OperationRecord(
                    id=op.id,
                    vehicle_id=op.vehicle_id,
                    kind=op.kind,
                    params=op.params,
                    status=op.status.value,
                    progress=max(0.0, min(1.0, op.progress)),
                    message=op.message,
                    session_key=op.session_key,
                    created_at=op.created_at,
                    updated_at=op.updated_at or op.created_at,
                    finished_at=op.finished_at,
                )
            )
        except Exception:
            log.exception("could not save operation %s", op.id)


def _climb_modes(vehicle: FlyingVehicle, kind: str, tracker: Tracker) -> frozenset[str] | None:
    """The modes of an operation that takes off first: its takeoff's and its own (PX4 climbs in
    AUTO.TAKEOFF, then holds and flies the leg in AUTO.LOITER); None for any other operation (its kind
    says)."""
    if not getattr(tracker, "climbing", False):
        return None
    return vehicle.commanded_modes("takeoff") | vehicle.commanded_modes(kind)


def _noted(op: Operation, message: str) -> str:
    """``message`` followed by the operation's note, so a tracker's progress or result never hides it
    (a client monitoring a taken-over operation learns what happened to it)."""
    if not op.note or op.note in message:
        return message
    return f"{message}; {op.note}"


def _interruption(vehicle: FlyingVehicle) -> str | None:
    """Why the gateway cannot follow the vehicle right now (sidecar restarting, link lost), or None."""
    name = str(vehicle.state)
    if not name or name == "ready":
        return None
    why = ""
    try:
        error = vehicle.status().get("last_error")
        why = f" ({error})" if error else ""
    except Exception:  # a status problem must not end the monitor
        pass
    return (
        f"connection interrupted: {vehicle.id} is {name}{why}; the drone keeps flying its last command "
        "on its own, and tracking resumes when it is ready again"
    )


def check_positive_altitude(alt_rel_m: float) -> None:
    geo.check_finite("alt_m", alt_rel_m)
    if alt_rel_m <= 0:
        raise InvalidArgument(
            f"alt_m {alt_rel_m:g} is not above home; give a flying altitude > 0 m above home "
            "(use land to come down)"
        )
