"""What the Commander's parts share besides the pass: ``@command`` (a verb is declared: callable by name,
and offered as the MCP tool its `Tool` names), ``@routed`` (a verb runs where its drone is), the
operation desk (views of operations and waiting on them, here or on the node that runs them). The small
flight rules the verbs judge a context with are `gateway.fleet.commands.verb_rules`. The pass itself is
`gateway.fleet.commands.command_pass`; the verbs are `drone_verbs` (flight), `navigation_verbs`,
`mission_verbs`, `fleet_verbs` and `fleet_step_verbs`; `gateway.fleet.commands.commander` composes them."""

from __future__ import annotations

import asyncio
import dataclasses
import functools
import logging
import typing
from collections.abc import Awaitable, Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import Concatenate, ParamSpec, Protocol, TypeVar, overload

from pydantic import BaseModel
from pydantic_core import to_jsonable_python

from gateway.config import Settings
from gateway.errors import (
    GatewayError,
    NoOwner,
    NotFound,
    NotRun,
    OwnerTimeout,
)
from gateway.fleet.commands.command_pass import AUDIT_SENT, CommandPass
from gateway.fleet.commands.routes import Route, declare_routes
from gateway.fleet.operations.operation_state import Operation
from gateway.fleet.operations.operations import OperationManager
from gateway.fleet.operations.routing import (
    FORWARDED,
    Method,
    OnMessage,
    ProgressMessage,
    RoutedCall,
    Router,
    Verb,
)
from gateway.fleet.operations.views import ActionResult, OperationView
from gateway.fleet.policy.caller import Caller
from gateway.fleet.vehicles.protocols import VehicleDirectory, VehicleView
from gateway.registry.store import OperationRecord, Store
from gateway.util.json_types import JsonObject
from gateway.util.read_through import ReadThrough

log = logging.getLogger(__name__)

OnProgress = Callable[[OperationView], Awaitable[None]]

#: operations that fly to a point (their params: lat_deg, lon_deg, alt_m); a formation or fleet-climb leg
#: is one too, so check_arrival answers for a drone whose formation leg a pilot took over
NAV_KINDS = ("goto", "reposition", "move_to_relative", "formation", "fleet_climb")
ELSEWHERE_KEPT = 2000
"""Operations started on other nodes whose drone this node remembers (to forward waits on them)."""
FOLLOW_RETRY_S = 0.5
"""How often a wait that lost its operation's node asks again (until a node has taken the drone over)."""
WAITER = Caller(via="cluster", principal="waiter")
"""Who forwards a wait: waiting changes nothing, whoever started the operation."""

VerbMethod = TypeVar("VerbMethod", bound=Method)
Params = ParamSpec("Params")
Result = TypeVar("Result", bound=BaseModel)

#: every verb on one drone that runs on the drone's owner, by name (filled by `routed`)
ROUTED: dict[str, Verb] = {}
#: the verbs every door (and a forwarding cluster node) may call by name (filled by `command`): their
#: arguments are the keyword parameters after ``caller``, their result the method's result model
VERBS: dict[str, Verb] = {}
#: the routed verbs that only read: allowed to agents on a drone a pilot or ground station took over
READ_VERBS = frozenset(
    {
        "arrival",
        "monitor",
        "download_mission",
        "export_mission",
        "mission_progress",
        "get_param",
        "list_params",
    }
)


class RoutedVerbs(Protocol):
    """What ``@routed`` needs of the object whose verbs it wraps (`FlightVerbs`, `FleetVerbs`...)."""

    desk: OperationDesk
    commands: CommandPass


Part = TypeVar("Part", bound="RoutedVerbs")


def routed(
    method: Callable[Concatenate[Part, Params], Awaitable[Result]],
) -> Callable[Concatenate[Part, Params], Awaitable[Result]]:
    """Run the verb where its drone is: here when this node owns it (or there is no cluster), else on
    its owner through the router, with the same arguments, callbacks (as progress messages) and result
    model. Before forwarding, an agent's actuating verb on a drone a pilot took over is refused (rule
    taken_over, as the owner's pass would) and the drone is looked up, so an unknown drone (or one
    outside the agent's scope) is named by this node exactly as by the owner."""
    name = method.__name__
    result_model = _result_model(method)

    @functools.wraps(method)
    async def run(self: Part, /, *args: Params.args, **kwargs: Params.kwargs) -> Result:
        bound = verb.signature.bind(self, *args, **kwargs)
        caller: Caller = bound.arguments["caller"]
        drone_id: str = bound.arguments["drone_id"]
        router = self.commands.router
        if router is None or router.owns(drone_id):
            return await method(self, *args, **kwargs)  # the pass judges it here
        if name not in READ_VERBS and not caller.is_operator:
            self.commands.refuse_taken_over(drone_id)  # before forwarding: the pilot's word comes first
        self.commands.registry.get(drone_id)
        if FORWARDED.get():
            raise NoOwner(f"this node does not own drone '{drone_id}' (any more): retry in a few seconds")
        callbacks = {k: bound.arguments[k] for k in verb.callbacks if bound.arguments.get(k) is not None}
        arguments = {
            k: to_jsonable_python(v)
            for k, v in bound.arguments.items()
            if k not in ("self", "caller") and k not in verb.callbacks
        }
        wait_s = float(arguments.get("cap_s") or self.commands.settings.mcp_wait_cap_s)
        relay = _relay(callbacks)
        seen: dict[str, str] = {}  # the operation the owner reported (its progress), to follow it
        starts = name not in READ_VERBS  # a read (a wait on a running operation) starts none of its own

        async def watch(body: ProgressMessage) -> None:
            view = body.get("view")
            operation_id = view.get("operation_id") if isinstance(view, dict) else None
            if isinstance(operation_id, str):
                if starts and seen.get("operation_id") != operation_id and (note := AUDIT_SENT.get()):
                    note(operation_id)  # the call's audit row names it: its end finishes the row
                seen["operation_id"] = operation_id
            if relay is not None:
                await relay(body)

        desk = self.desk
        started = asyncio.get_running_loop().time()
        try:
            result = await router.call(RoutedCall(drone_id, name, caller, arguments, watch, wait_s))
        except (NoOwner, OwnerTimeout):
            # the owner was lost while the verb waited on its operation: follow the operation to the
            # node that takes the drone over (same id), for what is left of the wait
            operation_id = seen.get("operation_id")
            if operation_id is None or result_model is not OperationView:
                raise
            remaining = wait_s - (asyncio.get_running_loop().time() - started)
            desk.remember_elsewhere(operation_id, drone_id)
            followed = await desk.wait_elsewhere(
                drone_id, operation_id, max(0.0, remaining), callbacks.get("on_progress")
            )
            return result_model.model_validate(followed)  # the OperationView itself
        answer = result_model.model_validate(result)
        if isinstance(answer, OperationView):
            desk.remember_elsewhere(answer.operation_id, drone_id)
        return answer

    # forwarded calls reach the verb by name on the Commander, which holds every verb
    verb = ROUTED[name] = Verb(method, wrapper=_by_name(method))
    return run


def _result_model(method: Callable[..., Awaitable[Result]]) -> type[Result]:
    """The pydantic model a verb returns, read from its annotation at run time (`Verb` refuses a verb
    that returns anything else)."""
    model: type[Result] = typing.get_type_hints(method)["return"]
    return model


Says = str | Callable[[ActionResult], str]
"""The one-line text of an instant command's tool result: a template (``str.format`` with the tool's
arguments and the `ActionResult`'s fields, e.g. ``"{drone_id} armed"``) or a function of the result."""


@dataclass(frozen=True)
class Confirm:
    """A human confirms the command before it runs (MCP: by elicitation, before the verb is called).
    ``question`` names a method of the verb's part, ``(caller, drone_id) -> str | None``: the question
    to ask, None when no confirmation is needed; it judges only (a refusal raises, nothing is sent).
    The answer (True only when the human accepted) fills the verb's boolean parameter ``into``."""

    question: str
    into: str = "confirmed"


@dataclass(frozen=True)
class Takes:
    """The tool offers a parameter of the verb in the form a model writes: as ``name`` of type
    ``annotation`` (its schema), made the verb's value by ``convert`` (None stays None). E.g. a
    mission's items as `Waypoint`s, checked and converted by the verb's module."""

    name: str
    annotation: object
    convert: Callable[..., object]


@dataclass(frozen=True)
class Tool:
    """How a verb is offered as an MCP tool; `gateway.mcp.declared` builds the tool from it (fleet/
    never imports the MCP layer). The verb's parameters after ``caller`` are the tool's arguments (their
    ``Annotated`` bounds and descriptions its inputSchema; ``label`` is filled with the tool's name,
    ``notify`` with the client's progress notifications); a verb returning an `OperationView` also gets
    ``wait`` (wait until done, capped). The description is ``description``, else the first paragraph
    of the verb's docstring (the rest is for developers)."""

    name: str
    toolset: str
    read_only: bool = False
    destructive: bool = False
    idempotent: bool = False
    #: the text of an instant command's result (a verb returning `ActionResult`); see `Says`
    says: Says | None = None
    description: str | None = None
    #: parameters of the verb the tool does not offer (they keep their defaults)
    omit: tuple[str, ...] = ()
    #: parameter -> the JSON schema shown for it where a shorter one says enough (validation unchanged)
    advertise: Mapping[str, Mapping[str, object]] = dataclasses.field(default_factory=dict)
    #: a human confirms the command first (`Confirm`)
    confirm: Confirm | None = None
    #: verb parameter -> the form the tool takes it in (`Takes`)
    takes: Mapping[str, Takes] = dataclasses.field(default_factory=dict)
    #: the verb the tool calls (filled by `command`)
    verb: str = ""


#: every tool a verb declares, by tool name (filled by `command`)
TOOLS: dict[str, Tool] = {}


@overload
def command(method: VerbMethod, /) -> VerbMethod: ...


@overload
def command(
    *, tool: Tool | Sequence[Tool] = (), route: Route | Sequence[Route] = ()
) -> Callable[[VerbMethod], VerbMethod]: ...


def command(
    method: VerbMethod | None = None,
    /,
    *,
    tool: Tool | Sequence[Tool] = (),
    route: Route | Sequence[Route] = (),
) -> VerbMethod | Callable[[VerbMethod], VerbMethod]:
    """Declare a verb a door may call by name (`Commander.call`): registered here, in `VERBS`, from its
    own signature; nothing else lists it. ``@command(tool=Tool(...))`` also offers it as that MCP tool,
    ``route=Route(...)`` as that operator's REST route (`gateway.fleet.commands.routes`; several: a
    sequence). Put it above ``@routed``."""
    tools = (tool,) if isinstance(tool, Tool) else tuple(tool)
    routes = (route,) if isinstance(route, Route) else tuple(route)

    def declare(method: VerbMethod) -> VerbMethod:
        name = method.__name__
        VERBS[name] = Verb(method, wrapper=_by_name(method))
        for declared in tools:
            other = TOOLS.get(declared.name)
            if other is not None and other.verb != name:
                raise ValueError(f"tool {declared.name} is declared by both {other.verb} and {name}")
            TOOLS[declared.name] = dataclasses.replace(declared, verb=name)
        declare_routes(name, routes)
        return method

    return declare if method is None else declare(method)


class VerbParts(Protocol):
    """The Commander as a verb called by name sees it: its parts, by class name."""

    parts: dict[str, object]


def _by_name(method: Method) -> Method:
    """Call the verb on the Commander's part that holds it (``commander.parts``, by class name)."""
    part, name = method.__qualname__.split(".")[-2:]

    async def call(commander: VerbParts, *args: object, **kwargs: object) -> BaseModel:
        verb: Method = getattr(commander.parts[part], name)  # the part's method as it is now
        return await verb(*args, **kwargs)

    return call


def _relay(callbacks: Mapping[str, Callable[..., Awaitable[object]]]) -> OnMessage | None:
    """The owner's progress messages to the verb's own callbacks (``notify``, ``on_progress``)."""
    if not callbacks:
        return None

    async def relay(body: ProgressMessage) -> None:
        if "notice" in body and "notify" in callbacks:
            await callbacks["notify"](str(body["notice"]))
        elif "view" in body and "on_progress" in callbacks:
            await callbacks["on_progress"](OperationView.model_validate(body["view"]))

    return relay


class OperationDesk:
    """Operations as the doors see them: views, the latest, waiting (here, or forwarded to the node
    that runs the operation, following it when that node is lost). One per Commander."""

    settings = ReadThrough[Settings]("commands")
    registry = ReadThrough[VehicleDirectory]("commands")
    operations = ReadThrough[OperationManager]("commands")
    router = ReadThrough[Router | None]("commands")

    def __init__(self, commands: CommandPass, store: Store | None) -> None:
        """``commands``: the pass, whose collaborators (settings, registry, operations, router) the desk
        reads; ``store``: the operations of a process that restarted, and of drones other nodes run."""
        self.commands = commands
        self.store = store
        self._elsewhere: dict[str, str] = {}  # operation id -> drone id, of operations run elsewhere

    # ------------------------------------------------------------------------------------------------
    # operations
    # ------------------------------------------------------------------------------------------------

    def view(self, op: Operation) -> OperationView:
        try:
            vehicle: VehicleView | None = self.registry.get(op.vehicle_id)
        except GatewayError:  # removed since: the operation is still worth reporting
            vehicle = None
        return OperationView.of(op, vehicle)

    def operation(self, operation_id: str) -> OperationView:
        return self.view(self.operations.get(operation_id))

    def current_operation(self, drone_id: str) -> JsonObject | None:
        """The drone's latest operation (running or finished) as ``Operation.to_dict`` gives it: this
        node's own, or for a drone owned by another cluster node the one its owner published."""
        if self.router is not None and not self.router.owns(drone_id):
            published = self.router.published(drone_id)
            if published is None:
                return None
            return {
                "operation_id": str(published.get("id")),
                "drone_id": drone_id,
                "kind": str(published.get("kind")),
                "status": str(published.get("status")),
                "progress": published.get("progress"),
                "message": published.get("message"),
                "eta_s": published.get("eta_s"),
                "elapsed_s": published.get("elapsed_s"),
                "params": published.get("params") or {},
            }
        op = self.operations.latest(drone_id)
        return None if op is None else op.to_dict()

    def latest_operation(self, drone_id: str) -> OperationView | None:
        """The drone's most recent operation, running or finished."""
        self.registry.get(drone_id)
        op = self.operations.latest(drone_id)
        return None if op is None else self.view(op)

    async def wait(
        self, operation_id: str, cap_s: float | None = None, on_progress: OnProgress | None = None
    ) -> OperationView:
        """Wait until the operation has finished or ``cap_s`` passed (default: the MCP wait cap),
        reporting progress on each change. Cancelling the waiter stops nothing on the drone. An
        operation that runs on another cluster node is waited for there."""
        try:
            op = self.operations.get(operation_id)
        except NotFound:
            drone_id = await self._drone_of(operation_id)
            if drone_id is None or self.router is None or self.router.owns(drone_id):
                raise
            return await self.wait_elsewhere(drone_id, operation_id, cap_s, on_progress)

        async def report(o: Operation) -> None:
            if on_progress is not None:
                await on_progress(self.view(o))

        return self.view(await self.operations.wait(op, cap_s, report if on_progress else None))

    # ------------------------------------------------------------------------------------------------
    # operations that run on another cluster node
    # ------------------------------------------------------------------------------------------------

    def remember_elsewhere(self, operation_id: str, drone_id: str) -> None:
        self._elsewhere[operation_id] = drone_id
        while len(self._elsewhere) > ELSEWHERE_KEPT:
            del self._elsewhere[next(iter(self._elsewhere))]

    async def _drone_of(self, operation_id: str) -> str | None:
        """The drone of an operation this node does not run: remembered, or from the database."""
        known = self._elsewhere.get(operation_id)
        if known is not None or self.store is None:
            return known
        record = await self.store.get_operation(operation_id)
        return None if record is None else record.vehicle_id

    async def _record_of(self, operation_id: str) -> OperationRecord | None:
        """The operation as the database holds it; None when unknown or the database is unreachable."""
        if self.store is None:
            return None
        try:
            return await self.store.get_operation(operation_id)
        except Exception:
            log.warning("could not read operation %s from the database", operation_id)
            return None

    async def wait_elsewhere(
        self, drone_id: str, operation_id: str, cap_s: float | None, on_progress: OnProgress | None
    ) -> OperationView:
        """Forward the wait to the drone's owner, its progress back to ``on_progress``. If the owner is
        lost meanwhile, the wait follows the operation to the node that takes the drone over (which
        tracks it under the same id); when the wait's time is up first, the answer is what the database
        holds, saying so."""
        assert self.router is not None
        cap = self.settings.mcp_wait_cap_s if cap_s is None else cap_s
        relay = _relay({"on_progress": on_progress}) if on_progress is not None else None
        loop = asyncio.get_running_loop()
        deadline = loop.time() + cap
        while True:
            left = max(0.0, deadline - loop.time())
            try:
                result = await self.router.call(
                    RoutedCall(
                        drone_id, "wait", WAITER, {"operation_id": operation_id, "cap_s": left}, relay, left
                    )
                )
                return OperationView.model_validate(result)
            except (NoOwner, OwnerTimeout, NotRun, NotFound) as exc:
                # no owner yet (a takeover under way), or the new owner has not picked the operation up
                # yet; unless the database says it has ended (the new owner could not follow it)
                record = await self._record_of(operation_id)
                ended = record is not None and record.status != "running"
                retry = not ended and not isinstance(exc, OwnerTimeout)
                if retry and loop.time() + FOLLOW_RETRY_S < deadline:
                    await asyncio.sleep(FOLLOW_RETRY_S)
                    continue
                if record is None:
                    raise
                return OperationView.of_record(record, f"{record.message or record.status} ({exc.message})")
