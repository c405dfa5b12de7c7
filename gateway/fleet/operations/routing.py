"""Where a verb runs: here, or on the cluster node that owns the drone.

A gateway alone has no router and runs everything itself. On a cluster node (`gateway.cluster`) the
Commander's verbs on one drone, the waits on its operations and the per-drone steps of fleet operations
go to the drone's owner when this node does not own it: `Router.call` sends a `RoutedCall` (the verb's
name, the caller and the verb's JSON arguments), and the owner runs the same verb through its own
Commander (so its safety checks, the agent's scope and the drone's command lock apply there, on fresh
telemetry).
Results, refusals and errors come back as the same models and error classes; the owner's progress
messages arrive through ``on_message`` while the call runs.

Progress messages are JSON objects: ``{"view": <OperationView>}`` (an operation's progress),
``{"fleet": <FleetView>}`` or ``{"notice": "<text>"}`` (what a command waits for before it is sent).
"""

from __future__ import annotations

import inspect
import typing
from collections.abc import Awaitable, Callable, Mapping
from contextvars import ContextVar
from dataclasses import dataclass
from typing import Any, Protocol

from pydantic import BaseModel, ConfigDict, ValidationError, create_model
from typing_extensions import TypedDict  # pydantic validates ProgressMessage on Python 3.11

from gateway.errors import InvalidArgument
from gateway.fleet.policy.caller import Caller
from gateway.fleet.policy.safety_inputs import RunningOperation
from gateway.util.json_types import JsonMapping, JsonObject, JsonValue


class ProgressMessage(TypedDict, total=False):
    """What a verb run on the drone's owner reports while it runs: a notice (for its ``notify``) or its
    operation's view as JSON (for its ``on_progress``)."""

    notice: str
    view: dict[str, object]


OnMessage = Callable[[ProgressMessage], Awaitable[None]]

#: set while a node runs a call another node forwarded to it: such a call is never forwarded again
#: (during a handover the drone's new owner is found by the first node, not by a chain of them)
FORWARDED: ContextVar[bool] = ContextVar("forwarded", default=False)

#: the caller of a call that reaches this node from a door or from another node (scopes read it)
ACTING: ContextVar[Caller | None] = ContextVar("acting", default=None)


@dataclass(frozen=True)
class RoutedCall:
    """A verb to run on the drone's owner: the drone, the verb's name, its caller, its JSON arguments,
    who hears its progress messages, and how long the verb itself may wait (added to the forwarding
    timeout)."""

    drone_id: str
    verb: str
    caller: Caller
    arguments: JsonMapping
    on_message: OnMessage | None = None
    wait_s: float = 0.0


class Router(Protocol):
    """What the Commander needs of a cluster (`gateway.cluster.forwarding.ClusterRouter`)."""

    def owns(self, drone_id: str) -> bool:
        """Whether this node runs the drone (its sidecar, its operations)."""

    def running(self, drone_id: str) -> RunningOperation | None:
        """The running operation of a drone owned elsewhere, as its owner last published it."""

    def published(self, drone_id: str) -> JsonObject | None:
        """The latest operation of a drone owned elsewhere, as its owner last published it (keys:
        id, kind, status, progress, message, eta_s, elapsed_s, params); None when there is none."""

    async def call(self, routed: RoutedCall) -> JsonValue:
        """Run the verb on the drone's owner (its arguments: what JSON encodes); its JSON result, or its
        error raised here as the same class."""

    async def announce(self, kind: str, body: JsonObject) -> None:
        """Tell every other node (operator locks, the emergency stop)."""


Method = Callable[..., Awaitable[BaseModel]]


class Verb:
    """A verb's signature as data: the method, the model its JSON arguments are validated with (its
    keyword parameters after ``caller``; keyword-only ones are callbacks, never part of the arguments),
    the names of those callbacks and the model of its result."""

    def __init__(self, method: Method, wrapper: Method | None = None) -> None:
        """``wrapper``: what to call instead of ``method`` (e.g. the routing in front of it)."""
        self.method = wrapper or method
        #: the method as declared (its annotated signature: an MCP tool's schema, `gateway.mcp.declared`)
        self.declared = method
        self.name = method.__name__
        self.signature = inspect.signature(method)
        hints = typing.get_type_hints(method)
        fields: dict[str, Any] = {}  # Any: pydantic, create_model's field definitions
        self.callbacks: frozenset[str] = frozenset()
        for name, param in list(self.signature.parameters.items())[2:]:
            if param.kind is inspect.Parameter.KEYWORD_ONLY:
                self.callbacks |= {name}
                continue
            if param.kind is not inspect.Parameter.POSITIONAL_OR_KEYWORD:
                continue
            default = ... if param.default is inspect.Parameter.empty else param.default
            fields[name] = (hints[name], default)
        self.arguments: type[BaseModel] = create_model(
            f"{method.__name__}_arguments", __config__=ConfigDict(extra="forbid"), **fields
        )
        result = hints["return"]
        if not (isinstance(result, type) and issubclass(result, BaseModel)):
            raise TypeError(f"verb {self.name} must return a pydantic model; it returns {result!r}")
        self.result: type[BaseModel] = result

    def parse(self, arguments: Mapping[str, object]) -> dict[str, object]:
        """The JSON arguments as the method's keyword arguments; InvalidArgument names what is wrong."""
        try:
            parsed = self.arguments.model_validate(arguments)
        except ValidationError as exc:
            problems = "; ".join(
                f"{'.'.join(str(p) for p in err['loc']) or 'arguments'}: {err['msg']}" for err in exc.errors()
            )
            raise InvalidArgument(f"invalid arguments for {self.name}: {problems}") from None
        return {k: getattr(parsed, k) for k in parsed.model_fields_set}
