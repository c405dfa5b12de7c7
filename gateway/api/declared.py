"""The operator's REST routes the verbs declare (``@command(route=Route(...))``,
`gateway.fleet.commands.routes`): one route factory, so a command appears on REST from its declaration
as it does on MCP (`gateway.mcp.declared`), with no route written by hand.

Each route is one call of its verb with the operator's caller: the path's vehicle id (made canonical,
`gateway.api.deps.CommandVehicleId`) fills the verb's drone parameter (a route on no one drone has
none), the JSON body the others (the declared body model, or a strict model of the verb's own
parameters), the declaration's ``fills`` the rest. The answer is `CommandOut` for an operation, an
instant command's result or a stop outcome (with the command's message), else the verb's own result
model (a lock). Items of a mission the gateway could not check (an operator's may fly them) are named
in the call's audit row. Errors are the verbs' own (`gateway.api.errors` maps them)."""

from __future__ import annotations

import inspect
import typing

from fastapi import APIRouter, Request
from pydantic import BaseModel, ConfigDict, create_model

from gateway.api.audit import AuditedRoute, note_unchecked
from gateway.api.control import CommandOut, operator
from gateway.api.deps import CommanderDep, CommandVehicleId, Principal, PrincipalDep
from gateway.fleet.commands.command_core import VERBS
from gateway.fleet.commands.commander import Commander  # imports every verb module: fills ROUTES
from gateway.fleet.commands.routes import ROUTES, Route
from gateway.fleet.operations.routing import Verb
from gateway.fleet.operations.views import ActionResult, OperationView, StopOutcome

#: verb parameters a route never offers: they keep their defaults
FILLED = ("label",)
#: the verb results the REST API answers as a `CommandOut`
COMMAND_RESULTS = (OperationView, ActionResult, StopOutcome)

_POSITIONAL = inspect.Parameter.POSITIONAL_OR_KEYWORD


def build_declared_router() -> APIRouter:
    """Every declared route, in the order the verbs were declared."""
    router = APIRouter(tags=["operator control"], route_class=AuditedRoute)
    for route in ROUTES.values():
        add_route(router, route)
    return router


def add_route(router: APIRouter, route: Route) -> None:
    """``route`` on ``router`` (see the module's docstring)."""
    verb = VERBS[route.verb]
    body = route.body if route.body is not None else body_model(route, verb)
    check_arguments(route, verb, body)
    answers = CommandOut if issubclass(verb.result, COMMAND_RESULTS) else verb.result
    fills = dict(route.fills)

    async def endpoint(
        request: Request,
        commander: Commander,
        who: Principal,
        vehicle_id: str | None = None,
        body: BaseModel | None = None,
    ) -> BaseModel:
        given = {} if body is None else {name: getattr(body, name) for name in type(body).model_fields}
        arguments = {route.renames.get(name, name): value for name, value in given.items()}
        if route.drone is not None:
            arguments[route.drone] = vehicle_id
        result: BaseModel = await verb.method(commander, operator(who), **arguments, **fills)
        note_unchecked(request, unchecked(result))
        return answer(result, verb.name)

    on_drone = (
        []
        if route.drone is None
        else [inspect.Parameter("vehicle_id", _POSITIONAL, annotation=CommandVehicleId)]
    )
    params = [
        *on_drone,
        inspect.Parameter("request", _POSITIONAL, annotation=Request),
        *([] if body is None else [inspect.Parameter("body", _POSITIONAL, annotation=body)]),
        inspect.Parameter("commander", _POSITIONAL, annotation=CommanderDep),
        inspect.Parameter("who", _POSITIONAL, annotation=PrincipalDep),
    ]
    endpoint.__name__ = endpoint.__qualname__ = route.name or f"{verb.name}_vehicle"
    endpoint.__doc__ = route.description
    endpoint.__signature__ = inspect.Signature(params, return_annotation=answers)  # type: ignore[attr-defined]
    router.add_api_route(
        route.url,
        endpoint,
        methods=[route.method],
        response_model=answers,
        summary=route.summary,
    )


def check_arguments(route: Route, verb: Verb, body: type[BaseModel] | None) -> None:
    """A declaration whose route cannot call its verb is refused at import: every body field and fixed
    argument is a parameter of the verb, and every parameter without a default is given."""
    offered = [
        *([] if route.drone is None else [route.drone]),
        *route.fills,
        *(route.renames.get(f, f) for f in (body.model_fields if body else ())),
    ]
    params = list(verb.signature.parameters.values())[2:]  # after self, caller
    unknown = sorted(set(offered) - {p.name for p in params if p.kind is _POSITIONAL})
    missing = sorted(
        p.name
        for p in params
        if p.kind is _POSITIONAL and p.default is inspect.Parameter.empty and p.name not in offered
    )
    problems = [f"{', '.join(unknown)}: no parameter of the verb"] if unknown else []
    if missing:
        problems.append(f"{', '.join(missing)}: not given (body or fills)")
    if problems:
        raise TypeError(f"route {route.key} of {verb.name}: " + "; ".join(problems))


def body_model(route: Route, verb: Verb) -> type[BaseModel] | None:
    """The verb's own parameters after the drone's, as a strict JSON body (no "10" for a number, no
    "off" for a boolean; unknown fields refused); None when the route fills them all."""
    hints = typing.get_type_hints(verb.declared, include_extras=True)
    fields: dict[str, tuple[object, object]] = {}
    for name, param in list(verb.signature.parameters.items())[2:]:  # after self, caller
        if param.kind is not _POSITIONAL or name == route.drone:
            continue  # the callbacks (keyword-only), the path's drone
        if name in FILLED or name in route.omit or name in route.fills:
            continue
        default = ... if param.default is inspect.Parameter.empty else param.default
        fields[name] = (hints[name], default)
    if not fields:
        return None
    title = "".join(word.capitalize() for word in verb.name.split("_")) + "In"
    model: type[BaseModel] = create_model(  # type: ignore[call-overload]
        title, __config__=ConfigDict(extra="forbid", strict=True), **fields
    )
    return model


def unchecked(result: BaseModel) -> object:
    """The mission items a command's result says the gateway could not check (None: none)."""
    if isinstance(result, OperationView):
        return result.params.get("unchecked")
    if isinstance(result, ActionResult):
        return result.facts.get("unchecked")
    return None


def answer(result: BaseModel, action: str) -> BaseModel:
    """The REST answer of a verb's result: `CommandOut` for a command on the drone, else the result."""
    if isinstance(result, StopOutcome):
        return CommandOut.of_outcome(result)
    if isinstance(result, OperationView):
        return CommandOut.of_operation(result, action).model_copy(update={"message": result.message})
    if isinstance(result, ActionResult):
        return CommandOut(
            vehicle_id=result.drone_id,
            action=action,
            outcome="sent",
            message=result.message,
            superseded_operation=result.superseded_operation,
        )
    return result


__all__ = ["add_route", "answer", "body_model", "build_declared_router", "check_arguments", "unchecked"]
