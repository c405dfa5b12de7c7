"""The Commander's router on a cluster node: verbs for drones another node owns go to that owner.

Both ends of one mechanism (`gateway.fleet.operations.routing` says what crosses):

- :class:`ClusterRouter` is the router the runtime gives the Commander and the fleet operations: a verb
  for a drone this node does not own goes, with the caller of the door it came through and its JSON
  arguments, to the drone's subject on NATS (`gateway.cluster.bus`), where only the owner listens;
- :func:`answer` runs such a call on the owner: the same verb of its own Commander (so the policy, the
  takeoff guard inside the drone's command lock, and the agent's scope are judged there again, on
  the owner's fresh telemetry), its callbacks sent back as progress messages, its result as JSON.
"""

from __future__ import annotations

import dataclasses
import logging
from collections.abc import Awaitable, Callable, Mapping
from typing import TYPE_CHECKING, Protocol

from gateway.errors import InvalidArgument
from gateway.fleet.commands.command_core import ROUTED
from gateway.fleet.commands.commander import Commander
from gateway.fleet.operations.routing import ACTING, FORWARDED, ProgressMessage, RoutedCall
from gateway.fleet.operations.views import OperationView
from gateway.fleet.policy.caller import Caller
from gateway.fleet.policy.safety_inputs import RunningOperation
from gateway.util.json_types import JsonObject, JsonValue

from .bus import ProgressSink
from .remote import RemoteVehicle

if TYPE_CHECKING:
    from gateway.fleet.vehicles.registry import Registry

log = logging.getLogger("gateway.cluster.forwarding")

#: calls an owner answers besides the routed verbs
WAIT = "wait"
ENDED_KEPT = 2000
"""Operations of other nodes this node has seen end (newer than the owners' last snapshots)."""


#: a call sent to the drone's owner (`gateway.cluster.owner_calls.OwnerCalls.forward`)
Forward = Callable[[RoutedCall], Awaitable[JsonValue]]


class Forwarder(Protocol):
    """Sends a call to the drone's owner (`gateway.cluster.owner_calls.OwnerCalls`)."""

    @property
    def forward(self) -> Forward: ...


class RouterNode(Protocol):
    """What the router reads of its node (`gateway.cluster.node.ClusterNode`, which passes itself)."""

    @property
    def registry(self) -> Registry | None: ...

    @property
    def calls(self) -> Forwarder: ...

    async def announce(self, kind: str, body: JsonObject) -> None: ...


class ClusterRouter:
    """Where a drone's verbs run, seen from this node."""

    def __init__(self, node: RouterNode) -> None:
        self.node = node
        self._ended: dict[str, str] = {}  # operation id -> its final status, as the owner answered

    def _note(self, body: object) -> None:
        """Remember an operation the owner reported as ended: its snapshots may still say running for a
        snapshot period, and a check here must not refuse a drone for an operation that is over."""
        if isinstance(body, dict) and isinstance(body.get("operation_id"), str):
            status = body.get("status")
            if isinstance(status, str) and status != "running":
                self._ended[body["operation_id"]] = status
                while len(self._ended) > ENDED_KEPT:
                    del self._ended[next(iter(self._ended))]

    def owns(self, drone_id: str) -> bool:
        registry = self.node.registry
        return registry is not None and registry.is_local(drone_id)

    def published(self, drone_id: str) -> JsonObject | None:
        """The latest operation of a drone owned elsewhere as its owner published it with its last
        snapshot, aged by that snapshot's age; ended if this node has seen it end since."""
        registry = self.node.registry
        vehicle = None if registry is None else registry.find(drone_id)
        if not isinstance(vehicle, RemoteVehicle) or vehicle.operation is None:
            return None
        op = dict(vehicle.operation)
        ended = self._ended.get(str(op.get("id")))
        if ended is not None and op.get("status") == "running":
            op["status"] = ended
        elapsed, age = op.get("elapsed_s"), vehicle.snapshot_age_s
        if isinstance(elapsed, int | float) and age is not None:
            op["elapsed_s"] = round(elapsed + age, 1)
        return op

    def running(self, drone_id: str) -> RunningOperation | None:
        op = self.published(drone_id)
        if op is None or op.get("status") != "running":
            return None
        target = op.get("target_alt_m")
        return RunningOperation(
            str(op.get("id")),
            str(op.get("kind")),
            str(op.get("message") or ""),
            float(target) if isinstance(target, int | float) else None,
        )

    async def call(self, routed: RoutedCall) -> JsonValue:
        on_message = routed.on_message

        async def observe(body: ProgressMessage) -> None:
            self._note(body.get("view"))
            if on_message is not None:
                await on_message(body)

        result = await self.node.calls.forward(dataclasses.replace(routed, on_message=observe))
        self._note(result)
        return result

    async def announce(self, kind: str, body: JsonObject) -> None:
        await self.node.announce(kind, body)


async def answer(
    commander: Commander,
    name: str,
    arguments: JsonObject,
    caller_body: Mapping[str, object],
    progress: ProgressSink,
) -> object:
    """Run a call another node forwarded (this node owns its drone); the JSON result."""
    caller = Caller.from_dict(caller_body)
    forwarded = FORWARDED.set(True)
    acting = ACTING.set(caller)
    try:

        async def view_progress(view: OperationView) -> None:
            await progress({"view": view.model_dump(mode="json")})

        async def notice(text: str) -> None:
            await progress({"notice": text})

        if name == WAIT:
            operation_id, cap_s = arguments.get("operation_id"), arguments.get("cap_s")
            if not isinstance(operation_id, str) or not isinstance(cap_s, int | float):
                raise InvalidArgument(
                    f"wait needs operation_id (text) and cap_s (seconds); got {arguments!r}"
                )
            view = await commander.wait(operation_id, float(cap_s), view_progress)
            return view.model_dump(mode="json")
        verb = ROUTED.get(name)
        if verb is None:
            raise InvalidArgument(
                f"unknown forwarded call {name!r}; calls: {', '.join(sorted([*ROUTED, WAIT]))}"
            )
        parsed = verb.parse(arguments)
        callbacks: dict[str, Callable[..., Awaitable[None]]] = {
            "notify": notice,
            "on_progress": view_progress,
        }
        parsed.update({k: v for k, v in callbacks.items() if k in verb.callbacks})
        result = await verb.method(commander, caller, **parsed)
        return result.model_dump(mode="json")
    finally:
        ACTING.reset(acting)
        FORWARDED.reset(forwarded)
