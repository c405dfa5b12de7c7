"""Long-running vehicle actions as tracked operations.

A takeoff, goto, landing or mission is an *operation*: the command is sent once, then a monitor task
follows the vehicle's telemetry until the action is done (altitude reached, arrived, landed and
disarmed, mission finished), failed, or superseded by a newer command. Callers (the MCP tools, REST)
*wait* on an operation with a cap; a waiter going away never touches the vehicle. One current
operation per vehicle; each is saved through the Store so its fate outlives the request that made it.

The manager also watches each vehicle's HEARTBEAT mode against what the gateway last commanded it
(`expect`; `gateway.fleet.operations.mode_watch`): a mode the gateway did not send ends the operation as
``interrupted`` and hands the takeover to ``on_takeover`` (the drone is locked for agents). What "done"
means for each kind of operation is its tracker's (`gateway.fleet.operations.trackers`).

No MCP or HTTP in here.
"""

from __future__ import annotations

import asyncio
import contextlib
import logging
import time
import uuid
from collections.abc import Awaitable, Callable, Iterable
from datetime import UTC, datetime

from gateway.config import Settings
from gateway.errors import InvalidArgument, NotFound
from gateway.fleet import geo
from gateway.fleet.operations.mode_watch import ModeWatch, TakeoverHandler
from gateway.fleet.operations.operation_state import Operation, OpStatus, wait_reporting
from gateway.fleet.operations.trackers import POLL_S, Poll, Tracker
from gateway.fleet.policy.operator_locks import Lock
from gateway.fleet.policy.safety_inputs import RunningOperation
from gateway.fleet.policy.takeover import ModeExpectation
from gateway.fleet.vehicles.protocols import FlyingVehicle
from gateway.fleet.vehicles.readings import age_s
from gateway.registry.records import OperationRecord
from gateway.registry.store import Store
from gateway.util.json_types import JsonMapping

log = logging.getLogger(__name__)

SAVE_EVERY_S = 2.0
"""Progress of a running operation is written to the store at most this often."""
TAKEOVER_EXPLAINS_S = 10.0
"""How long a tracker's failure waits for a takeover that explains it (`ModeWatch.explains_failure`) to
be recorded and end the operation as interrupted; after that the failure stands (a database that does
not answer must not keep an operation running for ever)."""

RESTATE_AFTER_S = 10.0
"""An operation this process follows that the database holds as running is looked at only when its last
change here is this old (its own writes, kept or in flight, come first)."""


ProgressCallback = Callable[[Operation], Awaitable[None]]


def is_climbing(op: Operation, tracker: Tracker | None) -> bool:
    """Whether the operation is a takeoff still climbing: a takeoff, or an operation that took off first
    and has not reached its altitude yet (the takeoff guard holds other commands back meanwhile)."""
    return op.kind == "takeoff" or bool(getattr(tracker, "climbing", False))


def _now() -> datetime:
    return datetime.now(UTC)


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
        self._followed_on: dict[str, FlyingVehicle] = {}  # the link each running operation is followed over
        #: operations whose tracker failed while a takeover explained it: since when (monotonic)
        self._explained: dict[str, float] = {}
        self._last_saved: dict[str, float] = {}
        self._locks: dict[str, asyncio.Lock] = {}
        self.mode_watch = ModeWatch(self)
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
        send: Callable[[], Awaitable[object]],
        params: JsonMapping,
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
                params=dict(params),
                session_key=session_key,
                created_at=_now(),
            )
            return await self._track(vehicle, op, tracker)

    # -- what the gateway commanded, and takeovers (`gateway.fleet.operations.mode_watch`) -------------------
    def expected(self, vehicle_id: str) -> ModeExpectation | None:
        return self.mode_watch.expected(vehicle_id)

    def forget(self, vehicle_id: str) -> None:
        """The gateway commands nothing the mode shows (a takeover, kill): nothing more is judged."""
        self.mode_watch.forget(vehicle_id)

    def watch_found_flying(self, vehicles: Iterable[FlyingVehicle]) -> None:
        """After a restart: every vehicle found flying gets its mode watch again (`ModeWatch`)."""
        self.mode_watch.watch_found_flying(vehicles)

    def tracker(self, operation_id: str) -> Tracker | None:
        """The tracker of a running operation."""
        return self._trackers.get(operation_id)

    def knows(self, operation_id: str) -> bool:
        """Whether this process follows (or followed to its end) the operation ``operation_id``."""
        return operation_id in self._ops

    async def settle_running_row(self, operation_id: str, holder: FlyingVehicle) -> bool:
        """The database holds ``operation_id``, which this process follows, as running; ``holder`` is the
        drone as this node holds it now. Ended here: its end is written again (that write never reached
        the database). Followed over another link than ``holder`` (one the node stopped): let go, and
        True, to be picked up again over ``holder``. Nothing follows it any more (its monitor is gone):
        ended as failed. So a row nobody updates never stays running."""
        op = self._ops.get(operation_id)
        if op is None or (_now() - (op.updated_at or op.created_at)).total_seconds() < RESTATE_AFTER_S:
            return False
        followed_on = self._followed_on.get(operation_id)
        if op.finished:
            log.warning("operation %s ended here (%s) but is running in the database: written again",
                        op.id, op.status.value)  # fmt: skip
            await self._save(op, force=True)
        elif followed_on is not None and followed_on is not holder:
            log.warning("operation %s is followed over a link %s no longer has: picked up again", op.id,
                        op.vehicle_id)  # fmt: skip
            stopped = self._forget(op)
            if stopped is not None:  # its end (untracking) before the operation is followed again
                with contextlib.suppress(asyncio.CancelledError, Exception):
                    await stopped
            return True
        elif operation_id not in self._monitors:
            await self._finish(op, OpStatus.failed, "monitoring stopped: nothing follows this operation")
        return False

    def _forget(self, op: Operation) -> asyncio.Task[None] | None:
        """Stop following ``op`` without writing anything; its monitor, cancelled, if it had one."""
        self._ops.pop(op.id, None)
        self._last_saved.pop(op.id, None)
        task = self._untrack(op.id)
        if task is not None:
            task.cancel()
        if self._current.get(op.vehicle_id) is op:
            self._current.pop(op.vehicle_id)
        return task

    def let_go(self, vehicle_id: str) -> list[str]:
        """This process no longer commands the vehicle (a cluster node gave it up: it fenced itself, or
        lost its lease): its operations on it are no longer followed here, and nothing more is written
        about them. The node that takes the drone over (this one again, or another) follows the running
        ones under the same ids from the database, or closes them there. A monitor left running would
        follow the stopped link for ever ("connection interrupted"), keep the operation running in this
        process (a takeoff refusing every later one), and end it later over what the next owner
        recorded. The ids of the running ones."""
        running = []
        for op in [op for op in self._ops.values() if op.vehicle_id == vehicle_id]:
            self._forget(op)
            if not op.finished:
                running.append(op.id)
        self._current.pop(vehicle_id, None)
        self.mode_watch.let_go(vehicle_id)
        return running

    async def interrupt(self, op: Operation, message: str) -> None:
        """End ``op`` as interrupted (a takeover)."""
        await self._finish(op, OpStatus.interrupted, message)

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

        async def report(changed: Operation) -> None:
            if on_progress is None:
                return
            try:
                await on_progress(changed)
            except Exception:  # a client that cannot take progress still gets its answer
                log.debug("progress report for %s failed", changed.id, exc_info=True)

        return await wait_reporting(op, cap, lambda o: (o.progress, o.message), report)

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
        tasks = list(self._monitors.values())
        for task in tasks:
            task.cancel()
        await self.mode_watch.stop()
        for task in tasks:
            with contextlib.suppress(asyncio.CancelledError, Exception):
                await task
        self._monitors.clear()

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
        return await self._track(vehicle, op, tracker)

    async def _track(self, vehicle: FlyingVehicle, op: Operation, tracker: Tracker) -> Operation:
        """Make ``op`` the drone's operation (superseding the one it replaces), save it and follow it with
        its tracker."""
        previous = self.running(vehicle.id)
        if previous is not None:
            await self._finish(previous, OpStatus.superseded, f"superseded by {op.kind} {op.id}")
        self._ops[op.id] = op
        self._current[vehicle.id] = op
        self._trackers[op.id] = tracker
        self._followed_on[op.id] = vehicle
        self.mode_watch.expect(vehicle, op.kind, op.id, _climb_modes(vehicle, op.kind, tracker))
        await self._save(op, force=True)
        self._monitors[op.id] = asyncio.create_task(
            self._monitor(vehicle, op, tracker), name=f"op-{op.kind}-{op.id}"
        )
        return op

    # -- internals -------------------------------------------------------------------------------
    async def _monitor(self, vehicle: FlyingVehicle, op: Operation, tracker: Tracker) -> None:
        stale_after = float(getattr(self.settings, "link_lost_after_s", 3.0))
        interrupted = False
        try:
            while not op.finished:
                pos_age = age_s(vehicle, "position")
                interruption = _interruption(vehicle)
                if interruption is not None and not interrupted:
                    op.interruptions.append(_interruption_cause(vehicle))
                interrupted = interruption is not None
                if interruption is not None:
                    self._update(op, op.progress, interruption, op.eta_s)
                elif pos_age is not None and pos_age > stale_after:
                    self._update(op, op.progress, f"no telemetry for {pos_age:.0f} s (link lost?)", op.eta_s)
                else:
                    poll = await self._poll(vehicle, op, tracker)
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
                        self.mode_watch.arrived(vehicle.id, op, tracker)
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
        finally:  # unless the operation is followed again meanwhile, by a monitor of its own
            if self._monitors.get(op.id) in (None, asyncio.current_task()):
                self._untrack(op.id)

    def _untrack(self, op_id: str) -> asyncio.Task[None] | None:
        """Forget what follows the operation: its tracker, its mode watch, its monitor (returned)."""
        self._trackers.pop(op_id, None)
        self._followed_on.pop(op_id, None)
        self._explained.pop(op_id, None)
        self.mode_watch.drop(op_id)
        return self._monitors.pop(op_id, None)

    async def _poll(self, vehicle: FlyingVehicle, op: Operation, tracker: Tracker) -> Poll:
        """The tracker's look; a failure a takeover explains is left to the takeover for up to
        TAKEOVER_EXPLAINS_S (it ends the operation as interrupted once its lock is stored)."""
        poll = await tracker.poll(vehicle)
        if poll.failed is None or op.finished or not self.mode_watch.explains_failure(vehicle, op.id):
            return poll
        since = self._explained.setdefault(op.id, time.monotonic())
        if time.monotonic() - since > TAKEOVER_EXPLAINS_S:
            return poll
        return Poll(op.progress, op.message, eta_s=op.eta_s)

    async def _send_next(
        self, vehicle: FlyingVehicle, op: Operation, send: Callable[[], Awaitable[object]]
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
            self.mode_watch.sent_at[op.id] = time.monotonic()
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
        op.message = _noted(op, message + _interrupted_meanwhile(op))
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


def _interruption_cause(vehicle: FlyingVehicle) -> str:
    """One interruption in a few words: the state and the link's last error."""
    try:
        error = vehicle.status().get("last_error")
    except Exception:
        error = None
    return f"{vehicle.state}: {error}" if error else str(vehicle.state)


def _interrupted_meanwhile(op: Operation) -> str:
    """What the final answer adds when the gateway lost the drone while the operation ran (the drone
    flew on alone; e.g. the sidecar restarted): how often and why, so a long answer is explained."""
    if not op.interruptions:
        return ""
    times = len(op.interruptions)
    count = "once" if times == 1 else "twice" if times == 2 else f"{times} times"
    return (
        f" (the connection was interrupted {count} while it ran: {'; '.join(op.interruptions)}; "
        "the drone flew on and tracking resumed)"
    )


def check_positive_altitude(alt_rel_m: float) -> None:
    geo.check_finite("alt_m", alt_rel_m)
    if alt_rel_m <= 0:
        raise InvalidArgument(
            f"alt_m {alt_rel_m:g} is not above home; give a flying altitude > 0 m above home "
            "(use land to come down)"
        )
