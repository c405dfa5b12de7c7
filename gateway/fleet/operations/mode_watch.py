"""The mode watch: each vehicle's HEARTBEAT mode judged against what the gateway last commanded it.

`expect` records what the gateway just commanded (an operation's kind, or an instant command's modes);
while that holds, a mode the gateway did not send, or the autopilot's own target moved away from a
running goto's, is a takeover (`gateway.fleet.policy.takeover`): the drone is locked through the manager's
``on_takeover`` first, then its running operation ends as ``interrupted``. After a restart,
`watch_found_flying` arms the watch again for every vehicle found flying."""

from __future__ import annotations

import asyncio
import contextlib
import logging
import time
from collections.abc import Awaitable, Callable, Iterable
from datetime import UTC, datetime
from typing import Protocol

from gateway.fleet import geo
from gateway.fleet.operations.operation_state import Operation, OpStatus
from gateway.fleet.operations.trackers import POLL_S, GotoTracker, Tracker
from gateway.fleet.policy.operator_locks import Lock
from gateway.fleet.policy.takeover import CAUSE_WINDOW_S, ModeExpectation, Takeover, likely_cause
from gateway.fleet.vehicles.protocols import FlyingVehicle
from gateway.registry.records import OperationRecord
from gateway.registry.store import Store

log = logging.getLogger(__name__)

MISSION_END_GRACE_S = 0.8
"""How long a mission that left its mode for one it settles in (PX4 holds at the end) may take to say
it finished before the change counts as a takeover."""
TARGET_SETTLE_S = 0.5
"""How long after a goto or hold was sent a reported target away from it is not judged even when one
near it was reported (the autopilot may report the new target and then, once more, one it had queued):
well beyond the autopilot's answer to the command."""
TARGET_MOVED_M = 10.0
"""How far the autopilot's target may be from the gateway's (for a goto at least 3 arrival tolerances)
before another ground station is taken to have moved it."""
TARGET_CONFIRM_S = 0.1
"""How long the target must stay moved before it counts as a takeover: two reports in a row (the link
asks for POSITION_TARGET_GLOBAL_INT at 5 Hz), so one report cannot end an operation."""
HOLD_KINDS = frozenset({"hold"})
"""Instant commands that leave the drone at a target of the gateway's (`FlyingVehicle.commanded_target`)."""
FOUND_FLYING_WAIT_S = 120.0
"""After a restart: how long the gateway waits for a vehicle's first HEARTBEAT and landed state before it
gives up looking whether the vehicle is flying (its mode watch is then armed by its next command)."""


TakeoverHandler = Callable[[FlyingVehicle, Takeover], Awaitable[None]]


class WatchedOperations(Protocol):
    """What the mode watch needs of the operations it watches over (the `OperationManager` that owns it)."""

    @property
    def store(self) -> Store | None: ...

    @property
    def on_takeover(self) -> TakeoverHandler | None:
        """Told of every takeover before its operation ends."""
        ...

    @property
    def taken_over(self) -> Callable[[str], Lock | None]:
        """The drone's takeover lock, if it has one."""
        ...

    def command_lock(self, vehicle_id: str) -> asyncio.Lock: ...

    def latest(self, vehicle_id: str) -> Operation | None: ...

    def tracker(self, operation_id: str) -> Tracker | None: ...

    async def interrupt(self, op: Operation, message: str) -> None: ...


class ModeWatch:
    """The mode watch of an `OperationManager`'s vehicles (one per manager, which passes itself)."""

    def __init__(self, ops: WatchedOperations) -> None:
        self._ops = ops
        self._expected: dict[str, ModeExpectation] = {}  # what the gateway last commanded, per vehicle
        self._watches: dict[str, asyncio.Task[None]] = {}
        self._finders: dict[str, asyncio.Task[None]] = {}  # after a restart: is the vehicle flying?
        #: when an operation's latest command (its leg) was sent (the manager sets it)
        self.sent_at: dict[str, float] = {}
        #: operations whose takeover is being recorded: they end interrupted once the lock is stored
        self._taking: set[str] = set()

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
        change to a mode the gateway did not command ends the operation (`gateway.fleet.policy.takeover`)."""
        wanted = modes if modes is not None else (vehicle.commanded_modes(kind) if kind else frozenset())
        if not wanted or kind is None:
            self._expected.pop(vehicle.id, None)
            return
        settled = modes if modes is not None else vehicle.commanded_modes(kind, done=True)
        exp = ModeExpectation(kind, wanted, settled | wanted, operation_id, since=time.monotonic())
        heard = vehicle.heartbeat_mode()
        if heard is not None and heard[1] and heard[0] in wanted:
            # already flying in the command's mode (a goto while in GUIDED): the mode will not change to
            # show it, so a pilot's switch before the watch's first look is judged like any later one
            exp.seen, exp.last_mode = True, heard[0]
        if kind in HOLD_KINDS:  # the target it holds to: a move away from it is someone else's
            exp.target = vehicle.commanded_target()
        self._expected[vehicle.id] = exp
        watch = self._watches.get(vehicle.id)
        if watch is None or watch.done():
            self._watches[vehicle.id] = asyncio.create_task(self._watch(vehicle), name=f"watch-{vehicle.id}")

    def expected(self, vehicle_id: str) -> ModeExpectation | None:
        return self._expected.get(vehicle_id)

    def explains_failure(self, vehicle: FlyingVehicle, operation_id: str) -> bool:
        """Whether a takeover explains the operation's failure: one is being recorded for it, or the
        drone left the operation's modes and the watch judges that at its next look. ArduCopter's LOITER
        without RC throttle sinks and lands, and the caller must hear of the pilot's switch, not of the
        landing it caused. Only asks; the watch's own task acts (never the operation's monitor, which
        the takeover ends)."""
        if operation_id in self._taking:
            return True
        exp = self._expected.get(vehicle.id)
        heard = vehicle.heartbeat_mode()
        if exp is None or exp.operation_id != operation_id or not exp.seen or heard is None:
            return False
        return heard[0] not in exp.modes and heard[0] not in exp.settled

    def forget(self, vehicle_id: str) -> None:
        """The gateway commands nothing the mode shows (a takeover, kill): nothing more is judged."""
        self._expected.pop(vehicle_id, None)

    def let_go(self, vehicle_id: str) -> None:
        """This process no longer commands the vehicle (its cluster node gave it up): nothing more is
        judged, and its watch ends (it reads the vehicle object of the link that was stopped; a drone
        adopted again gets a new one, watched anew)."""
        self._expected.pop(vehicle_id, None)
        for tasks in (self._watches, self._finders):
            task = tasks.pop(vehicle_id, None)
            if task is not None and task is not asyncio.current_task():
                task.cancel()

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
            heard = await _heard_after_restart(vehicle)
            if heard is None:
                log.info("%s: no HEARTBEAT after the restart; its mode watch waits for a command", vehicle.id)
                return
            mode, armed = heard
            if not armed or vehicle.on_ground(fresh=False) is not False:
                return  # on the ground: its next arming and command start afresh
            if not vehicle.commanded_modes("goto"):
                return  # an autopilot the gateway has no dialect for: it commands it nothing
            if vehicle.id in self._expected or self._ops.taken_over(vehicle.id) is not None:
                return  # a command since the restart (its own watch), or a pilot has it already
            record = await self._newest_record(vehicle.id)
            if vehicle.id in self._expected:
                return
            exp = _found_expectation(vehicle, mode, record.kind if record is not None else None)
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
        store = self._ops.store
        if store is None:
            return None
        records = await store.list_operations(vehicle_id=vehicle_id, limit=1)
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
        if exp is None or self._ops.command_lock(vehicle.id).locked():
            return  # the gateway is sending a command: the mode it brings is its own
        heard = vehicle.heartbeat_mode()
        if heard is None:
            return
        mode, armed = heard
        if not armed:  # on the ground, disarmed: nothing flies; the next arming starts afresh
            exp.seen, exp.outside_since, exp.target_off_since = False, None, None
            return
        op = self._ops.latest(vehicle.id)
        mine = op if op is not None and op.id == exp.operation_id else None
        done = mine is not None and mine.status is OpStatus.succeeded
        running = mine if mine is not None and not mine.finished else None
        commanded = vehicle.ground_station_commands(exp.since)
        if commanded:  # a ground station on the relay commanded the drone: whatever the mode shows
            first = commanded[0]
            await self._taken(vehicle, exp, mode, running, command=(first.sysid, first.what))
            return
        if mode in exp.modes or (done and mode in exp.settled):
            exp.seen, exp.outside_since, exp.last_mode = True, None, mode
            moved = self._retargeted(vehicle, exp, running)
            if moved is not None and _mode_heard_since(vehicle, exp.target_off_since):
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
        """How far (m) the autopilot's own target (POSITION_TARGET_GLOBAL_INT) is from the gateway's once
        it has been off for TARGET_CONFIRM_S: another ground station or a pilot repositioned or paused
        the drone in the mode the gateway commanded (QGroundControl's Pause or "Go to location" on PX4,
        whose gotos and holds fly in Hold; a ground station's "Fly to here" or
        SET_POSITION_TARGET_GLOBAL_INT in GUIDED on ArduCopter). The gateway's target is the running
        goto's leg, else the one its hold, or its goto that arrived, left the drone at. None while the
        autopilot flies the gateway's target, or while that cannot be told."""
        tracker = self._ops.tracker(op.id) if op is not None else None
        if op is not None and tracker is not None:
            if getattr(tracker, "climbing", False):
                return None  # a climb first: its leg is not sent yet
            leg = getattr(tracker, "leg", tracker)
            if not isinstance(leg, GotoTracker):
                return None
            sent = self.sent_at.get(op.id, op.started_mono)
            if exp.target is None or exp.target != (leg.lat, leg.lon, sent):
                exp.target, exp.target_adopted, exp.target_off_since = (leg.lat, leg.lon, sent), False, None
            exp.target_near_m = max(TARGET_MOVED_M, 3 * leg.tolerance_m)
        elif op is not None or exp.target is None:
            return None  # an operation without a tracker here (another node follows it), or no target
        return self._off_target(vehicle, exp)

    @staticmethod
    def _off_target(vehicle: FlyingVehicle, exp: ModeExpectation) -> float | None:
        assert exp.target is not None
        reported = vehicle.position_target()
        if reported is None:
            return None
        goal_lat, goal_lon, sent = exp.target
        near_m = exp.target_near_m
        if not exp.target_adopted and any(
            geo.horizontal_distance_m(t_lat, t_lon, goal_lat, goal_lon) <= near_m
            for t_lat, t_lon, _ in vehicle.position_targets(sent)
        ):
            exp.target_adopted = True  # reported flying it since it was sent, even if only briefly
        lat, lon, heard_at = reported
        off = geo.horizontal_distance_m(lat, lon, goal_lat, goal_lon)
        if off <= near_m:
            exp.target_off_since = None
            if heard_at >= sent:
                exp.target_adopted = True  # it flies this target: from now on a move away is someone else's
            return None
        if heard_at < sent + TARGET_SETTLE_S or not exp.target_adopted:
            # said before the command could show in it, or not yet seen flying the gateway's target: a
            # report from before it, which a loaded link or gateway can hand over long after it was
            # said, never counts as a takeover
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
        command: tuple[int, str] | None = None,
    ) -> None:
        """A takeover: the drone is locked first (whoever hears the operation end finds it locked), then
        the running operation ends as interrupted."""
        if self._expected.get(vehicle.id) is not exp or self._ops.command_lock(vehicle.id).locked():
            return  # a command went out meanwhile
        said: str | None = None
        if command is not None:
            cause = f"ground station system {command[0]} sent {command[1]} through the gateway's relay"
        elif moved_m is not None:
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
            at=datetime.now(UTC),
            operation_id=running.id if running is not None else None,
            operation_kind=running.kind if running is not None else exp.kind,
            retargeted=moved_m is not None,
            command=command[1] if command is not None else None,
        )
        self._expected.pop(vehicle.id, None)
        log.warning("%s: %s", vehicle.id, takeover.message())
        if running is not None:
            self._taking.add(running.id)  # its monitor may see what the switch caused before the lock is in
        try:
            if self._ops.on_takeover is not None:
                try:
                    await self._ops.on_takeover(vehicle, takeover)
                except Exception:
                    log.exception("recording the takeover of %s failed", vehicle.id)
            if running is not None:
                await self._ops.interrupt(running, takeover.message())
        finally:
            if running is not None:
                self._taking.discard(running.id)

    def arrived(self, vehicle_id: str, op: Operation, tracker: Tracker) -> None:
        """``op`` succeeded at the end of its goto leg: the drone stays at that target, and a move of the
        autopilot's target away from it is someone else's, even when the goto arrived before the watch
        looked at it (its target is otherwise taken at the watch's looks while the leg runs)."""
        exp = self._expected.get(vehicle_id)
        leg = getattr(tracker, "leg", tracker)
        if exp is None or exp.operation_id != op.id or not isinstance(leg, GotoTracker):
            return
        target = (leg.lat, leg.lon, self.sent_at.get(op.id, op.started_mono))
        if exp.target != target:
            exp.target, exp.target_adopted, exp.target_off_since = target, False, None
        exp.target_near_m = max(TARGET_MOVED_M, 3 * leg.tolerance_m)

    def drop(self, operation_id: str) -> None:
        """The operation's monitor ended: forget its legs."""
        self.sent_at.pop(operation_id, None)

    async def stop(self) -> None:
        """Gateway shutdown: nothing more is judged; the watches end."""
        self._expected.clear()
        tasks = [*self._watches.values(), *self._finders.values()]
        for task in tasks:
            task.cancel()
        for task in tasks:
            with contextlib.suppress(asyncio.CancelledError, Exception):
                await task
        self._watches.clear()
        self._finders.clear()


def _mode_heard_since(vehicle: FlyingVehicle, moved_at: float | None) -> bool:
    """Whether a HEARTBEAT heard after the autopilot's target moved still shows the gateway's mode. A
    switch to another mode (RETURN, LAND) moves the target too, and its 5 Hz report may come before the
    1 Hz HEARTBEAT that shows the new mode: the takeover is then the mode change, named as such."""
    heard_at = vehicle.heartbeat_heard_at()
    return heard_at is not None and moved_at is not None and heard_at >= moved_at


async def _heard_after_restart(vehicle: FlyingVehicle) -> tuple[str, bool] | None:
    """The vehicle's HEARTBEAT mode and armed state once they are known (and, armed, whether it is on the
    ground); None when they are not within FOUND_FLYING_WAIT_S."""
    deadline = time.monotonic() + FOUND_FLYING_WAIT_S
    while (heard := vehicle.heartbeat_mode()) is None or (
        heard[1] and vehicle.on_ground(fresh=False) is None
    ):
        if time.monotonic() > deadline:
            return None
        await asyncio.sleep(POLL_S)
    return heard


def _found_expectation(vehicle: FlyingVehicle, mode: str, kind: str | None) -> ModeExpectation:
    """What the watch expects of a vehicle found flying in ``mode`` after a restart: the modes of its last
    stored operation (``kind``) when it flies one of them, else the mode it was found in."""
    modes = (vehicle.commanded_modes(kind) | vehicle.commanded_modes(kind, done=True)) if kind else None
    now = time.monotonic()
    if kind is not None and modes and mode in modes:
        return ModeExpectation(kind, modes, modes, seen=True, last_mode=mode, since=now)
    found = frozenset({mode})
    return ModeExpectation(f"found flying in {mode}", found, found, seen=True, last_mode=mode, since=now)
