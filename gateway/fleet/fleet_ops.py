"""Fleet operations: one action on several drones, run as a group of per-drone operations.

A fleet operation (formation move, fleet takeoff, landing, return to launch) is a list of *phases*; a
phase gives some drones one step each (a command and a tracker, i.e. a per-drone `Operation` of the
`OperationManager`). Within a phase every command goes out concurrently (``asyncio.gather``), so
dispatching to N drones takes about as long as dispatching to one. A phase ends when every drone's step
has ended; only then does the next phase start. That barrier is what the formation planner's
separation guarantee rests on (`gateway.fleet.formation`: every drone finishes phase k before any
starts phase k+1).

Failure handling is explicit and per drone. A phase marked ``abort_on_failure`` (the formation's
phases) stops the fleet operation when one of its steps fails, is superseded or overruns its time: the
drones still moving in that phase are held where they are (a point of their planned segment, so the
planned separation still holds) and no later phase starts. Other phases (takeoff, landing, RTL) let
each drone finish on its own.

No MCP or HTTP in here: the MCP tools and any other caller wait on a `FleetOperation` with a cap.
"""

from __future__ import annotations

import asyncio
import contextlib
import logging
import math
import time
import uuid
from collections.abc import Awaitable, Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from datetime import UTC, datetime
from typing import TYPE_CHECKING, Any

from gateway.errors import GatewayError, InvalidArgument, NotFound, SafetyRefusal
from gateway.fleet import geo
from gateway.fleet.caller import Caller
from gateway.fleet.operations import (
    GotoTracker,
    LandingTracker,
    Operation,
    OperationManager,
    OpStatus,
    TakeoffTracker,
    Tracker,
)
from gateway.fleet.protocols import VehicleView, flying
from gateway.fleet.routing import Router

if TYPE_CHECKING:
    from gateway.fleet.formation import FormationPlan

Send = Callable[[], Awaitable[None]]
"""Sends one command to a drone (returns once the drone accepted it)."""

log = logging.getLogger(__name__)

POLL_S = 0.2
"""How often a running fleet operation looks at its drones' operations."""
MAX_FINISHED_KEPT = 50
"""Finished fleet operations kept in memory (for monitor_fleet and fleet://formation)."""
FLEET_CALLER = Caller(via="cluster", principal="fleet")
"""The caller of a fleet operation started without one (judged as an agent)."""
FOLLOW_WAIT_S = 30.0
"""A step run on another node is followed by waits of this length, one after the other."""


def _now() -> datetime:
    return datetime.now(UTC)


# ------------------------------------------------------------------------------------------------
# what a fleet operation is made of
# ------------------------------------------------------------------------------------------------


@dataclass
class Step:
    """One drone's part of a phase: send a command, then track it as the drone's current operation.
    ``spec`` describes it as JSON (see `build_step`), so the node owning the drone can run it there."""

    vehicle: VehicleView
    tracker: Tracker
    send: Send
    params: dict[str, Any]
    timeout_s: float | None = None  # the step fails if not finished by then (the vehicle keeps going)
    precheck: Callable[[], None] | None = None  # run inside the vehicle's command lock, just before send
    spec: dict[str, Any] = field(default_factory=dict)


@dataclass
class Phase:
    name: str
    steps: dict[str, Step]
    abort_on_failure: bool = False  # a failed step ends the fleet operation and holds the others


@dataclass
class Member:
    """One drone of a fleet operation: its latest outcome and, for formations, its slot."""

    drone_id: str
    status: str = "waiting"  # waiting | running | succeeded | failed | superseded | held | not_sent
    message: str = "waiting for its phase"
    operation_id: str | None = None
    sent_after_s: float | None = None  # since the fleet operation started: its latest command went out
    accepted_after_s: float | None = None  # ... and was accepted by the vehicle
    slot: dict[str, Any] | None = None

    def to_dict(self) -> dict[str, Any]:
        out: dict[str, Any] = {
            "drone_id": self.drone_id,
            "status": self.status,
            "message": self.message,
            "operation_id": self.operation_id,
            "sent_after_s": self.sent_after_s,
            "accepted_after_s": self.accepted_after_s,
        }
        if self.slot is not None:
            out.update(self.slot)
        return out


FINAL_FLEET = frozenset({"succeeded", "partial", "failed", "aborted", "superseded", "interrupted"})


@dataclass
class FleetOperation:
    """A group of per-drone operations run in phases. Status: running, then succeeded (every drone),
    partial (some drones), failed (none), aborted (a formation stopped after a failure), superseded or
    interrupted."""

    id: str
    kind: str
    drone_ids: list[str]
    params: dict[str, Any]
    members: dict[str, Member]
    phase_names: list[str]
    session_key: str | None = None
    plan: dict[str, Any] | None = None
    notes: list[str] = field(default_factory=list)
    caller: Caller = FLEET_CALLER  # who asked: a step run on another node is judged as theirs
    status: str = "running"
    message: str = "starting"
    phase: int = 0  # 1-based index of the phase running (0: not started)
    dispatch_s: list[float] = field(default_factory=list)  # per phase: first command sent -> all accepted
    created_at: datetime = field(default_factory=_now)
    started_mono: float = field(default_factory=time.monotonic)
    finished_mono: float | None = None
    changed: asyncio.Event = field(default_factory=asyncio.Event, repr=False)
    done: asyncio.Event = field(default_factory=asyncio.Event, repr=False)
    dispatched: asyncio.Event = field(default_factory=asyncio.Event, repr=False)  # first phase sent
    ops: dict[str, Operation] = field(default_factory=dict, repr=False)  # current step per drone

    @property
    def finished(self) -> bool:
        return self.status in FINAL_FLEET

    def elapsed_s(self) -> float:
        end = self.finished_mono if self.finished_mono is not None else time.monotonic()
        return end - self.started_mono

    @property
    def progress(self) -> float:
        """Phases done plus the mean progress of the current phase's steps, over the phase count."""
        if self.status == "succeeded":
            return 1.0
        total = max(1, len(self.phase_names))
        current = [op.progress if not op.finished or op.status is not OpStatus.succeeded else 1.0
                   for op in self.ops.values()]  # fmt: skip
        within = sum(current) / len(current) if current else 0.0
        return max(0.0, min(1.0, (max(self.phase, 1) - 1 + within) / total))

    def eta_s(self) -> float | None:
        etas = [op.eta_s for op in self.ops.values() if not op.finished and op.eta_s is not None]
        return max(etas) if etas else None

    def to_dict(self) -> dict[str, Any]:
        eta = self.eta_s()
        return {
            "operation_id": self.id,
            "kind": self.kind,
            "status": self.status,
            "message": self.message,
            "phase": self.phase,
            "phases": list(self.phase_names),
            "progress": round(self.progress, 3),
            "eta_s": None if eta is None or self.finished else round(eta, 1),
            "elapsed_s": round(self.elapsed_s(), 1),
            "dispatch_s": [round(d, 3) for d in self.dispatch_s],
            "drones": [m.to_dict() for m in self.members.values()],
            "notes": list(self.notes),
        }


# ------------------------------------------------------------------------------------------------
# refusing a fleet command before anything is sent
# ------------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Unable:
    """Why one drone cannot take part: the safety rule (or the gateway error's code) and the message."""

    drone_id: str
    code: str
    message: str
    details: dict[str, Any] = field(default_factory=dict)
    safety: bool = False  # refused by a safety rule (not an input or state error)

    @classmethod
    def from_error(cls, drone_id: str, exc: GatewayError) -> Unable:
        details = {k: v for k, v in exc.details.items() if k != "rule"}
        rule = exc.details.get("rule") if isinstance(exc, SafetyRefusal) else None
        return cls(drone_id, str(rule or exc.code), exc.message, details, safety=rule is not None)

    def to_dict(self) -> dict[str, Any]:
        return {"drone_id": self.drone_id, "code": self.code, "message": self.message, **self.details}


def _refusal_text(action: str, unable: Sequence[Unable], total: int) -> str:
    lines = "; ".join(f"{u.drone_id}: {u.message}" for u in unable)
    return (
        f"{action} refused, nothing was sent: {len(unable)} of {total} drone(s) cannot take part "
        f"(all must, for {action}) - {lines}"
    )


class FleetRefused(SafetyRefusal):
    """A fleet command of which nothing was sent because safety rules refused some of its drones.
    ``rule`` is the drones' rule when they share one, else ``fleet_members``; each drone's rule and
    numbers are in ``drones``."""

    code = "fleet_refused"
    http_status = 403

    def __init__(self, action: str, unable: Sequence[Unable], total: int) -> None:
        rules = sorted({u.code for u in unable})
        rule = rules[0] if len(rules) == 1 else "fleet_members"
        super().__init__(
            rule, _refusal_text(action, unable, total), rules=rules, drones=[u.to_dict() for u in unable]
        )
        self.unable = list(unable)


class FleetUnavailable(GatewayError):
    """A fleet command of which nothing was sent because some drones are unknown or not in a state to
    take part (no safety rule involved)."""

    code = "fleet_unavailable"
    http_status = 409

    def __init__(self, action: str, unable: Sequence[Unable], total: int) -> None:
        super().__init__(
            _refusal_text(action, unable, total),
            codes=sorted({u.code for u in unable}),
            drones=[u.to_dict() for u in unable],
        )
        self.unable = list(unable)


def refuse_fleet(action: str, unable: Sequence[Unable], total: int) -> GatewayError:
    """The error for a fleet command some drones cannot take part in: a safety refusal when any drone was
    refused by a rule, else an availability error. Either way every drone's reason is in it."""
    if any(u.safety for u in unable):
        return FleetRefused(action, unable, total)
    return FleetUnavailable(action, unable, total)


def check_drone_ids(drone_ids: Sequence[str], max_count: int = 64) -> list[str]:
    """A non-empty list of distinct ids; duplicates and oversize lists are refused, naming them."""
    ids = list(drone_ids)
    if not ids:
        raise InvalidArgument("drone_ids is empty: name at least one drone (see list_drones)")
    if len(ids) > max_count:
        raise InvalidArgument(f"drone_ids has {len(ids)} entries; at most {max_count} drones per command")
    bad = [i for i in ids if not isinstance(i, str) or not 0 < len(i) <= 64]
    if bad:
        raise InvalidArgument(f"drone ids must be 1..64 characters; got {bad[:3]!r}")
    dupes = sorted({i for i in ids if ids.count(i) > 1})
    if dupes:
        raise InvalidArgument(f"drone ids appear more than once: {dupes}")
    return ids


# ------------------------------------------------------------------------------------------------
# staggered return altitudes
# ------------------------------------------------------------------------------------------------


def rtl_order(
    positions: Mapping[str, tuple[float, float, float]],
    homes: Mapping[str, tuple[float, float]],
    separation_m: float,
) -> tuple[list[str], list[str]]:
    """Order drones from lowest to highest return altitude so that a drone whose straight way home
    passes within ``separation_m`` of another drone's home flies above that drone (which may already be
    descending there). Returns (order, notes); a cycle (two drones passing over each other's homes)
    cannot be ordered and is named in the notes. Ids without a known position or home go first (lowest)
    in the order given."""
    ids = list(positions)
    above: dict[str, set[str]] = {i: set() for i in ids}  # i must be above each of above[i]
    for i in ids:
        if i not in homes:
            continue
        lat, lon, _alt = positions[i]
        for j in ids:
            if j == i or j not in homes:
                continue
            if _passes_near(lat, lon, homes[i], homes[j], separation_m):
                above[i].add(j)
    order: list[str] = []
    notes: list[str] = []
    remaining = list(ids)
    while remaining:
        ready = [i for i in remaining if not (above[i] & set(remaining) - {i})]
        if not ready:  # a cycle: take the first, say so
            i = remaining[0]
            clash = sorted(above[i] & set(remaining))
            notes.append(
                f"the ways home of {i} and {', '.join(clash)} pass over each other's homes: their descents "
                "cannot both be kept below the other's return altitude"
            )
            ready = [i]
        for i in ready:
            order.append(i)
            remaining.remove(i)
    return order, notes


def _passes_near(
    lat: float, lon: float, home: tuple[float, float], other_home: tuple[float, float], sep: float
) -> bool:
    """Does the straight path (lat, lon) -> home pass within ``sep`` m of ``other_home`` (local plane)?"""
    hn, he = geo.ned_offset(lat, lon, home[0], home[1])
    on, oe = geo.ned_offset(lat, lon, other_home[0], other_home[1])
    length2 = hn * hn + he * he
    t = 0.0 if length2 < 1e-9 else max(0.0, min(1.0, (on * hn + oe * he) / length2))
    return math.hypot(on - t * hn, oe - t * he) < sep


# ------------------------------------------------------------------------------------------------
# the manager
# ------------------------------------------------------------------------------------------------

Listener = Callable[["FleetOperation"], None]
Ended = Callable[["FleetOperation"], Awaitable[None]]
"""Told once when a fleet operation has ended (e.g. to finish the audit rows of the calls it outlived)."""


class FleetOperations:
    """Runs fleet operations over the per-drone `OperationManager`; keeps the latest ones."""

    def __init__(
        self,
        operations: OperationManager,
        alive: Callable[[], bool] | None = None,
        router: Router | None = None,
        on_ended: Ended | None = None,
    ) -> None:
        """``alive`` tells a running fleet operation the gateway still runs (else it is interrupted);
        ``router`` (a cluster node) runs the steps of drones owned by other nodes on their owners;
        ``on_ended`` is awaited (in a task of its own) once each fleet operation has ended."""
        self.operations = operations
        self._alive = alive or (lambda: True)
        self.router = router
        self._on_ended = on_ended
        self._ops: dict[str, FleetOperation] = {}
        self._tasks: dict[str, asyncio.Task[None]] = {}
        self._followers: set[asyncio.Task[None]] = set()
        self._enders: set[asyncio.Task[None]] = set()
        self.listeners: list[Listener] = []

    # -- queries -------------------------------------------------------------------------------
    def get(self, operation_id: str) -> FleetOperation:
        try:
            return self._ops[operation_id]
        except KeyError:
            raise NotFound(f"no fleet operation with id '{operation_id}'") from None

    def latest(self, kind: str | None = None) -> FleetOperation | None:
        for fop in reversed(list(self._ops.values())):
            if kind is None or fop.kind == kind:
                return fop
        return None

    def running_for(self, drone_ids: Iterable[str]) -> list[FleetOperation]:
        wanted = set(drone_ids)
        return [f for f in self._ops.values() if not f.finished and wanted & set(f.drone_ids)]

    # -- commands --------------------------------------------------------------------------------
    async def start(
        self,
        kind: str,
        drone_ids: Sequence[str],
        phases: Sequence[Phase],
        params: dict[str, Any],
        session_key: str | None = None,
        plan: dict[str, Any] | None = None,
        slots: Mapping[str, dict[str, Any]] | None = None,
        notes: Sequence[str] = (),
        caller: Caller | None = None,
    ) -> FleetOperation:
        """Start a fleet operation. Its first phase's commands are sent before this returns (so a refused
        command shows at once); later phases run in a background task."""
        fop = FleetOperation(
            id=uuid.uuid4().hex[:12],
            kind=kind,
            drone_ids=list(drone_ids),
            params=params,
            members={d: Member(d, slot=(slots or {}).get(d)) for d in drone_ids},
            phase_names=[p.name for p in phases],
            session_key=session_key,
            plan=plan,
            notes=list(notes),
            caller=caller or FLEET_CALLER,
        )
        involved = {d for p in phases for d in p.steps}
        for drone_id, member in fop.members.items():
            if drone_id not in involved:
                member.status, member.message = "succeeded", "already in place: nothing to send"
        for older in self.running_for(drone_ids):
            self._finish(older, "superseded", f"superseded by {kind} {fop.id}")
        self._ops[fop.id] = fop
        self._trim()
        runner = asyncio.create_task(self._run(fop, list(phases)), name=f"fleet-{kind}-{fop.id}")
        self._tasks[fop.id] = runner
        runner.add_done_callback(lambda _t: self._tasks.pop(fop.id, None))
        await fop.dispatched.wait()  # set after the first phase's dispatch, or when it ended early
        return fop

    async def supersede(self, drone_ids: Iterable[str], by: str) -> list[FleetOperation]:
        """A direct command (hold, a single-drone move) took over some drones of running fleet ops."""
        ended = self.running_for(drone_ids)
        for fop in ended:
            self._finish(fop, "superseded", f"superseded by {by}")
        return ended

    async def wait(
        self,
        fop: FleetOperation,
        cap_s: float,
        on_progress: Callable[[FleetOperation], Awaitable[None]] | None = None,
    ) -> FleetOperation:
        """Wait until ``fop`` has finished or ``cap_s`` passed; cancelling the waiter stops nothing."""
        deadline = time.monotonic() + max(0.0, cap_s)
        last: tuple[float, str] | None = None
        while not fop.finished:
            remaining = deadline - time.monotonic()
            if remaining <= 0:
                break
            fop.changed.clear()
            with contextlib.suppress(TimeoutError):
                await asyncio.wait_for(fop.changed.wait(), timeout=min(remaining, 1.0))
            now = (round(fop.progress, 3), fop.message)
            if on_progress is not None and now != last:
                last = now
                await on_progress(fop)
        return fop

    async def stop(self) -> None:
        for fop in list(self._ops.values()):
            if not fop.finished:
                self._finish(fop, "interrupted", "gateway stopped while the fleet operation was running")
        tasks = list(self._tasks.values()) + list(self._followers)
        for task in tasks:
            task.cancel()
        for task in tasks:
            with contextlib.suppress(asyncio.CancelledError, Exception):
                await task
        for ender in list(self._enders):  # let the last outcomes be recorded before the store closes
            with contextlib.suppress(asyncio.CancelledError, Exception):
                await ender

    # -- steps of drones another cluster node owns ------------------------------------------------------
    def _elsewhere(self, drone_id: str) -> Router | None:
        router = self.router
        return router if router is not None and not router.owns(drone_id) else None

    async def _start_step(self, fop: FleetOperation, drone_id: str, step: Step) -> Operation:
        """Start the step here, or on the drone's owner: then a local mirror of the owner's operation,
        kept up to date by following it there."""
        router = self._elsewhere(drone_id)
        if router is None:
            extra = {"precheck": step.precheck} if step.precheck is not None else {}
            return await self.operations.start(
                flying(step.vehicle), step.tracker, step.send, step.params, fop.session_key, **extra
            )
        started = await router.call(
            drone_id, "run_step", fop.caller, {"drone_id": drone_id, "spec": step.spec}
        )
        mirror = Operation(
            id=str(started["operation_id"]),
            vehicle_id=drone_id,
            kind=str(started["kind"]),
            params=dict(started.get("params") or {}),
            session_key=fop.session_key,
            created_at=_now(),
        )
        _mirror(mirror, started)
        task = asyncio.create_task(self._follow(router, mirror), name=f"follow-{mirror.id}")
        self._followers.add(task)
        task.add_done_callback(self._followers.discard)
        return mirror

    async def _follow(self, router: Router, mirror: Operation) -> None:
        """Wait on the owner, again and again, until the operation there has finished."""

        async def message(body: dict[str, Any]) -> None:
            if isinstance(body.get("view"), dict):
                _mirror(mirror, body["view"])

        failures = 0
        while not mirror.finished:
            try:
                view = await router.call(
                    mirror.vehicle_id,
                    "wait",
                    FLEET_CALLER,
                    {"operation_id": mirror.id, "cap_s": FOLLOW_WAIT_S},
                    message,
                    wait_s=FOLLOW_WAIT_S,
                )
                _mirror(mirror, view)
                failures = 0
            except asyncio.CancelledError:
                raise
            except GatewayError as exc:  # the owner was lost: its successor picks the operation up
                failures += 1
                mirror.message = f"following {mirror.vehicle_id} on its owner failed: {exc.message}"
                mirror.changed.set()
                if failures >= 5:
                    _mirror(mirror, {"status": OpStatus.interrupted.value, "message": mirror.message})
                    return
                await asyncio.sleep(1.0)

    async def _hold(self, fop: FleetOperation, drone_id: str, step: Step) -> None:
        router = self._elsewhere(drone_id)
        if router is None:  # under the drone's command lock, like every command but kill
            vehicle = flying(step.vehicle)
            async with self.operations.command_lock(drone_id):
                await vehicle.hold()
                await self.operations.supersede(drone_id, f"{fop.kind} abort")
                self.operations.expect(vehicle, "hold")
            return
        await router.call(
            drone_id, "hold_step", fop.caller, {"drone_id": drone_id, "reason": f"{fop.kind} abort"}
        )

    # -- internals -------------------------------------------------------------------------------
    async def _run(self, fop: FleetOperation, phases: list[Phase]) -> None:
        try:
            for index, phase in enumerate(phases, start=1):
                if fop.finished:
                    return
                fop.phase = index
                fop.ops = {}
                if not phase.steps:
                    fop.dispatch_s.append(0.0)
                    self._changed(fop, f"phase {index} ({phase.name}): nothing to do", notify=True)
                    continue
                self._changed(fop, f"phase {index} of {len(phases)}: {phase.name}", notify=True)
                await self._dispatch(fop, phase)
                failed = await self._await_phase(fop, phase)
                if fop.finished:
                    return
                if failed and phase.abort_on_failure:
                    await self._abort(fop, phase, failed)
                    return
            self._conclude(fop)
        except asyncio.CancelledError:
            if not fop.finished:
                self._finish(fop, "interrupted", "fleet operation cancelled")
            raise
        except Exception as exc:  # a runner must never die silently
            log.exception("fleet operation %s failed", fop.id)
            self._finish(fop, "failed", f"fleet operation failed: {exc}")

    async def _dispatch(self, fop: FleetOperation, phase: Phase) -> None:
        """Send every step of the phase at once; record when each went out and was accepted."""
        t0 = time.monotonic()

        async def one(drone_id: str, step: Step) -> None:
            member = fop.members[drone_id]
            taken = self.operations.taken_over(drone_id)
            if taken is not None and (not fop.caller.is_operator or taken.locked_at >= fop.created_at):
                # a pilot or ground station has it: the gateway sends it nothing on its own
                member.status, member.message = "not_sent", f"not sent: {drone_id} was {taken.reason}"
                return
            member.sent_after_s = round(time.monotonic() - fop.started_mono, 3)
            member.status, member.message = "running", "command sent"
            try:
                op = await self._start_step(fop, drone_id, step)
            except GatewayError as exc:
                member.status, member.message, member.operation_id = "failed", exc.message, None
                return
            except Exception as exc:  # one drone's surprise must not hide the others' results
                log.exception("fleet %s: command to %s failed", fop.id, drone_id)
                member.status, member.message, member.operation_id = "failed", f"command failed: {exc}", None
                return
            member.accepted_after_s = round(time.monotonic() - fop.started_mono, 3)
            member.operation_id = op.id
            member.message = op.message
            fop.ops[drone_id] = op

        await asyncio.gather(*(one(d, s) for d, s in phase.steps.items()))
        fop.dispatch_s.append(time.monotonic() - t0)
        fop.dispatched.set()
        self._changed(fop, fop.message, notify=True)

    async def _await_phase(self, fop: FleetOperation, phase: Phase) -> list[str]:
        """Wait for every step of the phase to end; returns the drones whose step did not succeed."""
        started = time.monotonic()
        failed = [d for d in phase.steps if fop.members[d].status == "failed"]
        pending = [d for d in phase.steps if d in fop.ops]
        while pending:
            if fop.finished:
                return failed
            if not self._alive():
                self._finish(fop, "interrupted", "gateway stopped while the fleet operation was running")
                return failed
            for drone_id in list(pending):
                op = fop.ops[drone_id]
                member = fop.members[drone_id]
                step = phase.steps[drone_id]
                if op.finished:
                    pending.remove(drone_id)
                    member.status = op.status.value
                    member.message = op.message
                    if op.status is not OpStatus.succeeded:
                        failed.append(drone_id)
                    self._changed(fop, fop.message, notify=True)
                elif step.timeout_s is not None and time.monotonic() - started > step.timeout_s:
                    pending.remove(drone_id)
                    member.status = "failed"
                    member.message = f"not finished after {step.timeout_s:.0f} s: {op.message}"
                    failed.append(drone_id)
                    self._changed(fop, fop.message, notify=True)
                else:
                    member.message = op.message
            self._changed(fop, fop.message)
            if failed and phase.abort_on_failure:
                return failed
            if pending:
                await asyncio.sleep(POLL_S)
        return failed

    async def _abort(self, fop: FleetOperation, phase: Phase, failed: list[str]) -> None:
        """Hold every drone still moving in this phase (concurrently); no later phase starts."""
        moving = [d for d, op in fop.ops.items() if not op.finished]

        async def hold(drone_id: str) -> None:
            step = phase.steps[drone_id]
            member = fop.members[drone_id]
            try:
                await self._hold(fop, drone_id, step)
                member.status, member.message = "held", "held in place: the fleet operation was stopped"
            except GatewayError as exc:
                member.status, member.message = "failed", f"hold after abort failed: {exc.message}"
            except Exception as exc:
                member.status, member.message = "failed", f"hold after abort failed: {exc}"

        await asyncio.gather(*(hold(d) for d in moving))
        for member in fop.members.values():
            if member.status == "waiting":
                member.status, member.message = "not_sent", "not sent: the fleet operation was stopped"
        why = "; ".join(f"{d}: {fop.members[d].message}" for d in failed)
        self._finish(
            fop,
            "aborted",
            f"stopped in phase {fop.phase} ({phase.name}) because {why}. Drones still moving were held "
            "where they were; later phases were not started",
        )

    def _conclude(self, fop: FleetOperation) -> None:
        outcomes = [m.status for m in fop.members.values()]
        ok = sum(1 for s in outcomes if s == "succeeded")
        if ok == len(outcomes):
            self._finish(fop, "succeeded", f"all {ok} drones done")
        elif ok:
            bad = ", ".join(
                f"{m.drone_id} {m.status}" for m in fop.members.values() if m.status != "succeeded"
            )
            self._finish(fop, "partial", f"{ok} of {len(outcomes)} drones done; {bad}")
        else:
            self._finish(fop, "failed", f"no drone finished: {', '.join(sorted(set(outcomes)))}")

    def _finish(self, fop: FleetOperation, status: str, message: str) -> None:
        if fop.finished:
            return
        fop.status = status
        fop.message = message
        fop.finished_mono = time.monotonic()
        if status != "succeeded":
            for member in fop.members.values():
                if member.status == "running":
                    member.status, member.message = status, f"{member.message} (fleet operation {status})"
                elif member.status == "waiting":
                    member.status, member.message = "not_sent", f"not sent: the fleet operation was {status}"
        fop.changed.set()
        fop.done.set()
        fop.dispatched.set()
        task = self._tasks.get(fop.id)
        if task is not None and task is not asyncio.current_task():
            task.cancel()
        self._notify(fop)
        if self._on_ended is not None:
            ender = asyncio.create_task(self._ended(fop), name=f"fleet-ended-{fop.id}")
            self._enders.add(ender)
            ender.add_done_callback(self._enders.discard)

    async def _ended(self, fop: FleetOperation) -> None:
        assert self._on_ended is not None
        try:
            await self._on_ended(fop)
        except Exception:  # recording an outcome must never touch the fleet
            log.exception("recording the end of fleet operation %s failed", fop.id)

    def _changed(self, fop: FleetOperation, message: str, notify: bool = False) -> None:
        fop.message = message
        fop.changed.set()
        if notify:
            self._notify(fop)

    def _notify(self, fop: FleetOperation) -> None:
        for listener in list(self.listeners):
            try:
                listener(fop)
            except Exception:
                log.exception("fleet operation listener failed")

    def _trim(self) -> None:
        finished = [k for k, f in self._ops.items() if f.finished]
        for key in finished[: max(0, len(finished) - MAX_FINISHED_KEPT)]:
            del self._ops[key]


def _mirror(mirror: Operation, view: Mapping[str, Any]) -> None:
    """Bring a local mirror of an operation another node runs up to date with its view there."""
    mirror.progress = float(view.get("progress", mirror.progress) or 0.0)
    mirror.message = str(view.get("message") or mirror.message)
    eta = view.get("eta_s")
    mirror.eta_s = None if eta is None else float(eta)
    status = OpStatus(str(view.get("status") or "running"))
    if status is not OpStatus.running and not mirror.finished:
        mirror.status = status
        mirror.finished_at = _now()
        mirror.done.set()
    mirror.changed.set()


# ------------------------------------------------------------------------------------------------
# building fleet operations (the MCP tools and REST call these; no MCP in here)
# ------------------------------------------------------------------------------------------------

FORMATION_PHASES = (
    "climb or descend in place to transit altitudes",
    "fly to the slots",
    "climb or descend in place to the formation altitude",
)
FORMATION_TOLERANCE_M = 1.0
"""A formation leg counts as done within this distance of its waypoint: the next phase's separation
check starts from the planned point, so the barrier keeps arrivals tight."""


def step_timeout_s(distance_m: float, slowest_mps: float = 1.0, margin_s: float = 120.0) -> float:
    """Time after which a step that has not finished is given up: generous, meant to catch a stuck
    drone, never to hurry one."""
    return margin_s + max(0.0, distance_m) / slowest_mps


def collect_members(
    drone_ids: Sequence[str],
    resolve: Callable[[str], VehicleView],
    check: Callable[[VehicleView], None],
) -> tuple[dict[str, VehicleView], list[Unable]]:
    """Look every drone up (``resolve`` raises UnknownVehicle) and run ``check`` on it (raises a
    GatewayError, e.g. SafetyRefusal or VehicleNotReady, when it cannot take part). Every drone is
    checked, so one answer names all the drones that cannot take part."""
    vehicles: dict[str, VehicleView] = {}
    unable: list[Unable] = []
    for drone_id in drone_ids:
        try:
            vehicle = resolve(drone_id)
            check(vehicle)
        except GatewayError as exc:
            unable.append(Unable.from_error(drone_id, exc))
            continue
        vehicles[drone_id] = vehicle
    return vehicles, unable


Precheck = Callable[[VehicleView], None]
"""Checks a vehicle inside its command lock (e.g. "no takeoff in progress", against parallel tool calls)."""


def _bind(precheck: Precheck | None, vehicle: VehicleView) -> Callable[[], None] | None:
    return None if precheck is None else (lambda: precheck(vehicle))


def build_step(vehicle: VehicleView, spec: Mapping[str, Any], precheck: Precheck | None = None) -> Step:
    """One drone's step from its JSON description (the node owning the drone rebuilds it from the same):

    - ``{"send": "goto", "lat", "lon", "alt_m", "tolerance_m", "kind", "phase"?}``: a tracked goto;
    - ``{"send": "takeoff", "alt_m", "arm_within_s"?}`` (how long arming may wait), ``{"send": "land"}``,
      ``{"send": "rtl", "alt_m"}`` (return at that altitude above home);

    each with an optional ``timeout_s`` and ``guard`` (the action named by the takeoff guard that
    ``precheck`` runs inside the drone's command lock)."""
    send = spec.get("send")
    timeout = spec.get("timeout_s")
    timeout_s = None if timeout is None else float(timeout)
    bound = _bind(precheck, vehicle)
    if send == "goto":
        lat, lon, alt = float(spec["lat"]), float(spec["lon"]), float(spec["alt_m"])
        params: dict[str, Any] = {"lat_deg": lat, "lon_deg": lon, "alt_m": alt}
        if spec.get("phase") is not None:
            params["phase"] = int(spec["phase"])
        tolerance = float(spec.get("tolerance_m", FORMATION_TOLERANCE_M))
        tracker: Tracker = GotoTracker(lat, lon, alt, tolerance, kind=str(spec.get("kind", "formation")))
        return Step(vehicle, tracker, _goto(vehicle, lat, lon, alt), params, timeout_s, bound, dict(spec))
    if send == "takeoff":
        alt = float(spec["alt_m"])
        arm_within = spec.get("arm_within_s")
        return Step(
            vehicle,
            TakeoffTracker(alt),
            _takeoff(vehicle, alt, None if arm_within is None else float(arm_within)),
            {"alt_m": alt},
            timeout_s,
            bound,
            dict(spec),
        )
    if send == "land":
        land = lambda: flying(vehicle).land()  # noqa: E731
        return Step(vehicle, LandingTracker(kind="land"), land, {}, timeout_s, bound, dict(spec))
    if send == "rtl":
        alt = float(spec["alt_m"])
        return Step(
            vehicle,
            LandingTracker(kind="return_to_launch"),
            _rtl(vehicle, alt, set_rtl_altitude_param),
            {"rtl_alt_m": alt},
            timeout_s,
            bound,
            dict(spec),
        )
    raise InvalidArgument(f"unknown fleet step {send!r}; steps: goto, takeoff, land, rtl")


def formation_phases(
    plan: FormationPlan, vehicles: Mapping[str, VehicleView], precheck: Precheck | None = None
) -> list[Phase]:
    """The three phases of a `FormationPlan` as fleet-operation phases (each leg a tracked goto)."""
    phases: list[Phase] = []
    for index, name in enumerate(FORMATION_PHASES):
        steps: dict[str, Step] = {}
        for drone_id, wp in plan.phases[index].items():
            slot = plan.slot_for(drone_id)
            spec = {
                "send": "goto",
                "lat": wp.lat,
                "lon": wp.lon,
                "alt_m": wp.alt_rel_m,
                "tolerance_m": FORMATION_TOLERANCE_M,
                "kind": "formation",
                "phase": index + 1,
                "timeout_s": step_timeout_s(slot.distance_m),
                "guard": None if precheck is None else "formation_goto",
            }
            steps[drone_id] = build_step(vehicles[drone_id], spec, precheck)
        phases.append(Phase(name, steps, abort_on_failure=True))
    return phases


def slot_summaries(plan: FormationPlan) -> dict[str, dict[str, Any]]:
    """Per drone: its slot's target, transit altitude and distance to fly (for results)."""
    return {
        s.drone_id: {
            "target_lat_deg": round(s.lat, 7),
            "target_lon_deg": round(s.lon, 7),
            "target_alt_m": round(s.alt_rel_m, 2),
            "transit_alt_m": None if s.transit_alt_m is None else round(s.transit_alt_m, 2),
            "distance_m": round(s.distance_m, 1),
        }
        for s in plan.slots
    }


def takeoff_phase(
    vehicles: Mapping[str, VehicleView],
    altitudes: Mapping[str, float],
    precheck: Precheck | None = None,
    arm_within_s: float | None = None,
    guard: str = "fleet_takeoff",
) -> Phase:
    """Every drone takes off to its altitude; ``arm_within_s`` bounds each drone's wait to arm; ``guard``
    names the action in the takeoff guard's refusals."""
    steps = {
        d: build_step(
            v,
            {
                "send": "takeoff",
                "alt_m": altitudes[d],
                "arm_within_s": arm_within_s,
                "timeout_s": step_timeout_s(altitudes[d], slowest_mps=0.5),
                "guard": None if precheck is None else guard,
            },
            precheck,
        )
        for d, v in vehicles.items()
    }
    return Phase("take off to staggered altitudes", steps)


def land_phase(vehicles: Mapping[str, VehicleView]) -> Phase:
    return Phase("land in place", {d: build_step(v, {"send": "land"}) for d, v in vehicles.items()})


def rtl_phases(
    vehicles: Mapping[str, VehicleView],
    altitudes: Mapping[str, float],
    positions: Mapping[str, tuple[float, float, float]],
) -> list[Phase]:
    """Return to launch in two phases: (1) every drone climbs or descends in place to its return altitude,
    (2) each drone's RTL altitude is set, then RTL (the autopilot flies home at that altitude and lands;
    it would return at its current altitude if that were higher, which is why phase 1 also descends).
    The barrier keeps a drone from heading home while a neighbour is still moving through its layer."""
    climbs: dict[str, Step] = {}
    for d, v in vehicles.items():
        pos = positions.get(d)
        if pos is None or abs(pos[2] - altitudes[d]) <= FORMATION_TOLERANCE_M:
            continue
        lat, lon, alt = pos
        climbs[d] = build_step(
            v,
            {
                "send": "goto",
                "lat": lat,
                "lon": lon,
                "alt_m": altitudes[d],
                "tolerance_m": FORMATION_TOLERANCE_M,
                "kind": "fleet_climb",
                "timeout_s": step_timeout_s(abs(altitudes[d] - alt), slowest_mps=0.5),
            },
        )
    returns = {d: build_step(v, {"send": "rtl", "alt_m": altitudes[d]}) for d, v in vehicles.items()}
    return [
        Phase("climb or descend in place to return altitudes", climbs),
        Phase("return home and land", returns),
    ]


def _goto(vehicle: VehicleView, lat: float, lon: float, alt: float) -> Send:
    return lambda: flying(vehicle).goto(lat, lon, alt)


def _takeoff(vehicle: VehicleView, alt: float, arm_within_s: float | None) -> Send:
    if arm_within_s is None:
        return lambda: flying(vehicle).takeoff(alt)
    return lambda: flying(vehicle).takeoff(alt, arm_within_s)


def _rtl(
    vehicle: VehicleView, alt: float, set_rtl_altitude: Callable[[VehicleView, float], Awaitable[None]]
) -> Send:
    async def send() -> None:
        await set_rtl_altitude(vehicle, alt)
        await flying(vehicle).return_to_launch()

    return send


async def set_rtl_altitude_param(vehicle: VehicleView, alt_m: float) -> None:
    """The vehicle's return altitude above home, in its autopilot's parameter and units
    (``Vehicle.set_return_altitude``); the autopilot returns higher if it is already higher."""
    await flying(vehicle).set_return_altitude(alt_m)


def default_rtl_base_m(positions: Iterable[tuple[float, float, float]], floor_m: float = 15.0) -> float:
    """Lowest return altitude: above every drone's current altitude (an autopilot already higher than
    its RTL altitude returns at its current one, which would undo the layers), and at least ``floor_m``."""
    highest = max((p[2] for p in positions), default=0.0)
    return float(max(floor_m, math.ceil(highest + FORMATION_TOLERANCE_M)))
