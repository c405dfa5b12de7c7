"""Fleet operations: one action on several drones, run as a group of per-drone operations.

A fleet operation (formation move, fleet takeoff, landing, return to launch) is a list of *phases*; a
phase gives some drones one step each (a command and a tracker, i.e. a per-drone `Operation` of the
`OperationManager`). Within a phase every command goes out concurrently (``asyncio.gather``), so
dispatching to N drones takes about as long as dispatching to one. A phase ends when every drone's step
has ended; only then does the next phase start. That barrier is what the formation planner's
separation guarantee rests on (`gateway.fleet.formation.formation`: every drone finishes phase k before any
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
import time
import uuid
from collections.abc import Awaitable, Callable, Iterable, Mapping, Sequence
from datetime import UTC, datetime

from pydantic import TypeAdapter

from gateway.errors import GatewayError, NotFound
from gateway.fleet.operations.fleet_operation import FLEET_CALLER, FleetOperation, Member, SlotSummary
from gateway.fleet.operations.fleet_steps import Phase, Step, StepSpec
from gateway.fleet.operations.operation_state import Operation, OpStatus, wait_reporting
from gateway.fleet.operations.operations import OperationManager
from gateway.fleet.operations.routing import RoutedCall, Router
from gateway.fleet.operations.step_mirror import follow, mirror_view
from gateway.fleet.operations.views import OperationView
from gateway.fleet.policy.caller import Caller
from gateway.util.json_types import JsonObject, JsonValue

log = logging.getLogger(__name__)

_STEP_SPEC = TypeAdapter(StepSpec)

POLL_S = 0.2
"""How often a running fleet operation looks at its drones' operations."""
MAX_FINISHED_KEPT = 50
"""Finished fleet operations kept in memory (for monitor_fleet and fleet://formation)."""


def _now() -> datetime:
    return datetime.now(UTC)


# ------------------------------------------------------------------------------------------------
# the manager
# ------------------------------------------------------------------------------------------------

Listener = Callable[["FleetOperation"], None]
RunHere = Callable[[Caller, str, StepSpec], Awaitable[Operation]]
"""Runs one drone's step (its JSON spec) on this node, as the drone's operation."""
HoldHere = Callable[[Caller, str, str], Awaitable[Operation | None]]
"""Holds one drone (the reason names the fleet operation); the operation it ended."""
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
        self._run_here: RunHere | None = None
        self._hold_here: HoldHere | None = None

    def run_steps_with(self, run_here: RunHere, hold_here: HoldHere) -> None:
        """How a step on a drone this node owns is run: the Commander's pass (`FleetStepVerbs.step_here`,
        `FleetStepVerbs.hold_here`), the same one every command on one drone takes."""
        self._run_here, self._hold_here = run_here, hold_here

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
        params: JsonObject,
        session_key: str | None = None,
        plan: JsonObject | None = None,
        slots: Mapping[str, SlotSummary] | None = None,
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

    async def supersede(
        self, drone_ids: Iterable[str], by: str, before: datetime | None = None
    ) -> list[FleetOperation]:
        """A direct command (hold, a single-drone move) took over some drones of running fleet ops;
        ``before``: only those started before it (a stop heard from another node, made then)."""
        ended = [f for f in self.running_for(drone_ids) if before is None or f.created_at < before]
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
        return await wait_reporting(fop, cap_s, lambda f: (round(f.progress, 3), f.message), on_progress)

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
            if self._run_here is None:
                raise RuntimeError("fleet steps are not bound to a command pass (run_steps_with)")
            return await self._run_here(fop.caller, drone_id, step.spec)
        started = OperationView.model_validate(
            await router.call(
                RoutedCall(
                    drone_id, "run_step", fop.caller, {"drone_id": drone_id, "spec": _json_spec(step.spec)}
                )
            )
        )
        mirror = Operation(
            id=started.operation_id,
            vehicle_id=drone_id,
            kind=started.kind,
            params=dict(started.params),
            session_key=fop.session_key,
            created_at=_now(),
        )
        mirror_view(mirror, started)
        task = asyncio.create_task(follow(router, mirror), name=f"follow-{mirror.id}")
        self._followers.add(task)
        task.add_done_callback(self._followers.discard)
        return mirror

    async def _hold(self, fop: FleetOperation, drone_id: str, step: Step) -> None:
        router = self._elsewhere(drone_id)
        if router is None:  # the pass: under the drone's command lock, like every command but kill
            if self._hold_here is None:
                raise RuntimeError("fleet steps are not bound to a command pass (run_steps_with)")
            await self._hold_here(fop.caller, drone_id, f"{fop.kind} abort")
            return
        await router.call(
            RoutedCall(
                drone_id, "hold_step", fop.caller, {"drone_id": drone_id, "reason": f"{fop.kind} abort"}
            )
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


def _json_spec(spec: StepSpec) -> JsonValue:
    """A step's spec as the JSON a routed call carries to the drone's owner."""
    json_spec: JsonValue = _STEP_SPEC.dump_python(spec, mode="json")
    return json_spec
