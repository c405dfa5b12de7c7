"""The operator's commands on the fleet: locks (per drone and fleet-wide), the takeover locks (a pilot,
another ground station or a failsafe took a drone), and the emergency stop.

stop_all is the operator's emergency stop: it locks the fleet (unless told not to), ends every running
fleet operation first (so a formation's own abort cannot race it), then tells every airborne drone to
hold, land or return, each as a tracked operation where the action has one. Each drone's stop is the
drone's own command through the one pass (`FlightVerbs.hold`, `land`, `return_to_launch`), under its
command lock like every command (kill is the one exception): a command still being sent to the drone
finishes first, so that the stop is the last word the drone hears rather than being overtaken by it.
"""

from __future__ import annotations

import asyncio
import logging
from collections.abc import Awaitable, Callable
from datetime import UTC, datetime
from typing import Literal

from gateway.errors import GatewayError, NoOwner, NotRun, StopPending, VehicleNotReady
from gateway.fleet.commands.command_core import command
from gateway.fleet.commands.command_pass import CommandPass
from gateway.fleet.commands.drone_verbs import FlightVerbs
from gateway.fleet.commands.routes import LockIn, Route
from gateway.fleet.commands.verb_rules import operator_only
from gateway.fleet.operations.fleet_ops import FleetOperations
from gateway.fleet.operations.views import LockResult, StopOutcome, StopResult, UnlockResult
from gateway.fleet.policy.caller import Caller
from gateway.fleet.policy.geofence import FLEET
from gateway.fleet.policy.takeover import Takeover
from gateway.fleet.vehicles.protocols import VehicleView
from gateway.link.contract import HEARD
from gateway.registry.records import AuditEntry
from gateway.registry.store import Store
from gateway.util.cancelling import cancelled_here

log = logging.getLogger(__name__)

StopAction = Literal["hold", "land", "rtl"]
STOP_LOCK_REASON = "emergency stop"
#: the stop's answer says whether its lock is stored if the database answers within this (else: later)
STORE_LOCK_WAIT_S = 1.0
_STORING: set[asyncio.Task[bool]] = set()
#: a drone whose link is being established when the stop comes gets it once heard, within this
STOP_WHEN_READY_S = 60.0
#: the link states in which that wait is worth it (not registered, not failed)
LINK_COMING = frozenset({"connecting", "connected", "link_lost"})
_WAITING: set[asyncio.Task[None]] = set()


class OperatorVerbs:
    """Locks, takeover locks and the emergency stop; only an operator may lock, unlock, release or stop."""

    def __init__(
        self, commands: CommandPass, flight: FlightVerbs, fleet: FleetOperations, store: Store | None
    ) -> None:
        self.commands = commands
        self.flight = flight
        self.fleet = fleet
        self.store = store
        self.registry, self.router, self.locks = commands.registry, commands.router, commands.locks

    def _operator_only(self, caller: Caller, what: str) -> None:
        operator_only(caller, f"{what}; agents cannot change locks or stop the fleet")

    @command(
        route=(
            Route("lock", "Lock a drone against agents", name="lock_vehicle", drone="scope", body=LockIn),
            Route(
                "fleet/lock",
                "Lock the whole fleet against agents",
                name="lock_fleet",
                drone=None,
                body=LockIn,
                fills={"scope": FLEET},
            ),
        )
    )
    async def lock(self, caller: Caller, scope: str, reason: str) -> LockResult:
        """Lock one drone (its id) or the fleet ("*") against agents' actuating commands: at once on this
        node and every node that hears the broadcast; stored (later, if the database is unreachable)."""
        self._operator_only(caller, "lock drones")
        result = await self._lock_now(caller, scope, reason)
        result.stored = await self._store_lock(result)
        return result

    async def _lock_now(self, caller: Caller, scope: str, reason: str) -> LockResult:
        """The lock in memory and on the bus: it holds before anything is written."""
        if scope != FLEET:
            self.registry.get(scope)  # UnknownVehicle names the known ids
        lock = self.locks.lock(scope, reason, caller.principal, at=datetime.now(UTC))
        log.warning(
            "operator %s locked %s: %s", lock.by, "the fleet" if scope == FLEET else scope, lock.reason
        )
        result = LockResult.of(lock)
        if self.router is not None:  # every node refuses agents from now on
            await self.router.announce("lock", result.model_dump(mode="json", exclude={"stored"}))
        return result

    async def _store_lock(self, lock: LockResult) -> bool:
        """True when the lock is in the database now; False when it is kept until the database is back."""
        if self.store is None:
            return True
        stored = await self.store.save_lock(lock.scope, lock.reason, lock.by, lock.locked_at)
        if stored is None:
            log.warning("the lock of %s is kept on this node until the database is back", lock.scope)
        return stored is not None

    @command(
        route=(
            Route("lock", "Unlock a drone", method="DELETE", name="unlock_vehicle", drone="scope"),
            Route(
                "fleet/lock",
                "Remove the fleet lock",
                method="DELETE",
                name="unlock_fleet",
                drone=None,
                fills={"scope": FLEET},
            ),
        )
    )
    async def unlock(self, caller: Caller, scope: str) -> UnlockResult:
        self._operator_only(caller, "unlock drones")
        removed = self.locks.unlock(scope)
        stored = await self.store.delete_lock(scope) if self.store is not None else False
        if self.router is not None:
            await self.router.announce("unlock", {"scope": scope})
        if removed or stored:
            log.warning("operator %s unlocked %s", caller.principal, "the fleet" if scope == FLEET else scope)
        return UnlockResult(scope=scope, was_locked=removed is not None or stored)

    # ------------------------------------------------------------------------------------------------
    # takeover locks: a pilot, another ground station or a failsafe took a drone
    # (gateway.fleet.policy.takeover)
    # ------------------------------------------------------------------------------------------------

    async def taken_over(self, vehicle: VehicleView, takeover: Takeover) -> None:
        """The OperationManager saw a mode change the gateway did not command (its operation already
        ended as interrupted): lock the drone for agents, persist and audit the lock, tell the other
        nodes. Nothing is sent to the drone."""
        lock = self.locks.take_over(vehicle.id, takeover.lock_reason(), at=takeover.at)
        if self.store is not None:
            try:
                await self.store.save_takeover(lock.scope, lock.reason, lock.by, lock.locked_at)
                await self.store.add_audit(
                    AuditEntry(
                        principal="autopilot",
                        source="gateway",
                        vehicle_id=vehicle.id,
                        action="takeover",
                        arguments=takeover.to_record(),
                        outcome="ok",
                        error=takeover.message(),
                        t=takeover.at,
                        operation_id=takeover.operation_id,
                    )
                )
            except Exception:  # the lock holds in memory whatever the database says
                log.exception("could not store the takeover of %s", vehicle.id)
        if self.router is not None:
            await self.router.announce(
                "takeover",
                {"scope": lock.scope, "reason": lock.reason, "by": lock.by, "at": lock.locked_at.isoformat()},
            )

    @command(
        route=Route(
            "takeover",
            "Release a drone taken over by a pilot or ground station",
            method="DELETE",
            name="release_takeover",
            description="Agents may command the drone again (the pilot or ground station is done with it).",
        )
    )
    async def release(self, caller: Caller, drone_id: str) -> UnlockResult:
        """An operator gives a taken-over drone back to agents (the pilot is done with it)."""
        self._operator_only(caller, "release a drone taken over by a pilot or ground station")
        self.registry.get(drone_id)
        removed = self.locks.release(drone_id)
        stored = await self.store.delete_takeover(drone_id) if self.store is not None else False
        if self.router is not None:
            await self.router.announce("release", {"scope": drone_id})
        if removed or stored:
            log.warning("operator %s released %s after a takeover", caller.principal, drone_id)
        return UnlockResult(scope=drone_id, was_locked=removed is not None or stored)

    @command
    async def stop_all(
        self, caller: Caller, action: StopAction = "hold", lock: bool = True, lock_reason: str | None = None
    ) -> StopResult:
        """Emergency stop: lock the fleet (unless ``lock`` is false and no reason is given), end every
        running fleet operation, then every airborne drone holds, lands or returns, all at once."""
        self._operator_only(caller, "stop the fleet")
        # Nothing here waits on the database: the lock holds in memory (and on every node that hears the
        # broadcast) before the drones are told, and is stored beside the stops, later if need be.
        fleet_lock = None
        storing: asyncio.Task[bool] | None = None
        if lock or lock_reason:
            fleet_lock = await self._lock_now(caller, FLEET, lock_reason or STOP_LOCK_REASON)
            storing = asyncio.create_task(self._store_lock(fleet_lock))
            _STORING.add(storing)  # it may outlive this call (a database that hangs)
            storing.add_done_callback(_STORING.discard)
        vehicles = list(self.registry.all())
        superseded = await self.fleet.supersede([v.id for v in vehicles], f"operator stop ({action})")
        if self.router is not None:  # fleet operations coordinated by other nodes end there too
            await self.router.announce("stop", {"action": action, "by": caller.principal})

        results = await asyncio.gather(*(self._stop_member(caller, v, action) for v in vehicles))
        if fleet_lock is not None and storing is not None:
            done, _ = await asyncio.wait({storing}, timeout=STORE_LOCK_WAIT_S)
            fleet_lock.stored = bool(done and not storing.exception() and storing.result())
        return StopResult(
            action=action,
            fleet_lock=fleet_lock,
            superseded_fleet_operations=[f.id for f in superseded],
            results=list(results),
        )

    async def _stop_member(self, caller: Caller, vehicle: VehicleView, action: StopAction) -> StopOutcome:
        """One drone of a fleet stop: its outcome, never an exception."""
        state = str(vehicle.state)
        # a drone owned elsewhere goes to its node's router whatever it reads here: with no owner
        # (its node lost, or fenced) the router still finds a path to it, or says what it does next
        remote = getattr(vehicle, "remote", False)
        if state in ("registered", "failed") and not remote:
            return StopOutcome(
                drone_id=vehicle.id, action=action, outcome="skipped", message=f"not connected ({state})"
            )
        if vehicle.on_ground() is True:
            return StopOutcome(drone_id=vehicle.id, action=action, outcome="skipped", message="on the ground")
        try:
            return await self.stop_one(caller, vehicle.id, action)
        except StopPending as exc:
            return StopOutcome(drone_id=vehicle.id, action=action, outcome="taking_over", message=exc.message)
        except VehicleNotReady as exc:
            if state not in LINK_COMING:
                return StopOutcome(drone_id=vehicle.id, action=action, outcome="failed", message=exc.message)
            # this node's own link to it is being established (a drone it has just taken over, a
            # sidecar restarting): the stop goes as soon as the link is ready
            self._stop_when_ready(caller, vehicle.id, action)
            return StopOutcome(
                drone_id=vehicle.id,
                action=action,
                outcome="taking_over",
                message=f"{exc.message}: this node sends the {action} as soon as it hears the drone "
                f"(it keeps trying for {STOP_WHEN_READY_S:g} s; the log and the audit say when it is "
                "sent)",
            )
        except (NotRun, NoOwner) as exc:
            return StopOutcome(drone_id=vehicle.id, action=action, outcome="unreached", message=exc.message)
        except GatewayError as exc:
            return StopOutcome(drone_id=vehicle.id, action=action, outcome="failed", message=exc.message)
        except Exception as exc:  # one drone's failure must not stop the others
            log.exception("fleet stop: %s failed on %s", action, vehicle.id)
            return StopOutcome(drone_id=vehicle.id, action=action, outcome="failed", message=repr(exc))
        except asyncio.CancelledError as exc:
            if cancelled_here():
                raise  # the stop itself is cancelled
            # something the drone's stop awaited ended cancelled: its failure, not the fleet stop's
            log.exception("fleet stop: %s on %s was cancelled under it", action, vehicle.id)
            return StopOutcome(drone_id=vehicle.id, action=action, outcome="failed", message=repr(exc))

    def _stop_when_ready(self, caller: Caller, drone_id: str, action: StopAction) -> None:
        """The stop of a drone whose link is being established, sent once the drone is heard (in the
        background, for at most STOP_WHEN_READY_S)."""

        def state() -> str | None:
            try:
                return str(self.registry.get(drone_id).state)
            except GatewayError:  # no longer registered
                return None

        async def wait_and_stop() -> None:
            await send_once_heard(drone_id, action, state, lambda: self.stop_one(caller, drone_id, action))

        task = asyncio.create_task(wait_and_stop(), name=f"stop-when-ready-{drone_id}")
        _WAITING.add(task)
        task.add_done_callback(_WAITING.discard)

    @command(
        route=(
            Route("hold", "Hold position (operator)", name="hold_vehicle", fills={"action": "hold"}),
            Route("land", "Land (operator)", name="land_vehicle", fills={"action": "land"}),
            Route("rtl", "Return to launch (operator)", name="rtl_vehicle", fills={"action": "rtl"}),
        )
    )
    async def stop_one(self, caller: Caller, drone_id: str, action: StopAction) -> StopOutcome:
        """One drone's part of a stop: hold (ends its operation), land or RTL (tracked operations that
        supersede it). The REST hold/land/RTL routes are this too."""
        previous = self.commands.running(drone_id)
        if action == "hold":
            held = await self.flight.hold(caller, drone_id, "operator hold")
            return StopOutcome(
                drone_id=drone_id,
                action=action,
                outcome="sent",
                superseded_operation=held.superseded_operation,
            )
        op = await (
            self.flight.land(caller, drone_id)
            if action == "land"
            else self.flight.return_to_launch(caller, drone_id)
        )
        return StopOutcome(
            drone_id=drone_id,
            action=action,
            outcome="sent",
            superseded_operation=None if previous is None else previous.operation_id,
            operation_id=op.operation_id,
        )


async def send_once_heard(
    drone_id: str, action: str, state: Callable[[], str | None], stop: Callable[[], Awaitable[object]],
    within_s: float = STOP_WHEN_READY_S, every_s: float = 0.2,
) -> bool:  # fmt: skip
    """Send ``stop`` once ``state()`` says the drone is heard, trying again while its link comes and
    goes (VehicleNotReady), for at most ``within_s``; whether it was sent. ``state()`` None: the drone
    is no longer registered."""
    loop = asyncio.get_running_loop()
    deadline = loop.time() + within_s
    while loop.time() < deadline:
        now = state()
        if now is None:
            return False
        if now in HEARD:
            try:
                await stop()
            except VehicleNotReady:  # the link dropped again between the reading and the send
                pass
            except GatewayError as exc:
                log.error("%s: %s once its link was up failed: %s", drone_id, action, exc.message)
                return False
            else:
                log.warning("%s: %s sent once its link was up (%s)", drone_id, action, now)
                return True
        await asyncio.sleep(every_s)
    log.error("%s: its link was not up within %.0f s: %s not sent", drone_id, within_s, action)
    return False
