"""The route factory (`gateway.api.declared`): a declaration whose route cannot call its verb is refused
when the route is made, naming what is wrong; a body made of the verb's own parameters is strict."""

from __future__ import annotations

import pytest
from fastapi import APIRouter
from pydantic import ValidationError

from gateway.api.declared import add_route, body_model
from gateway.fleet.commands.command_core import VERBS
from gateway.fleet.commands.routes import ROUTES, Route, TakeoffIn


def test_a_body_field_the_verb_does_not_take_is_refused_by_name() -> None:
    wrong = Route("climb", "Climb", body=TakeoffIn, verb="takeoff")  # alt_rel_m, not renamed to alt_m
    with pytest.raises(TypeError) as refused:
        add_route(APIRouter(), wrong)
    assert str(refused.value) == (
        "route POST /vehicles/{vehicle_id}/climb of takeoff: alt_rel_m: no parameter of the verb; "
        "alt_m: not given (body or fills)"
    )


def test_a_fixed_argument_the_verb_does_not_take_is_refused() -> None:
    with pytest.raises(TypeError, match="confirm: no parameter of the verb"):
        add_route(APIRouter(), Route("kill2", "Kill", fills={"confirm": True}, verb="kill"))


def test_the_verbs_own_parameters_make_a_strict_body() -> None:
    body = body_model(Route("mode", "Set the mode", verb="set_mode"), VERBS["set_mode"])
    assert body is not None and body.__name__ == "SetModeIn"
    assert list(body.model_fields) == ["mode"]  # not the path's drone_id
    with pytest.raises(ValidationError):
        body.model_validate({"mode": "GUIDED", "drone_id": "d1"})  # unknown fields refused
    assert body_model(Route("hold", "Hold", verb="hold"), VERBS["hold"]) is None  # label keeps its default


def test_every_declared_route_can_call_its_verb() -> None:
    router = APIRouter()
    for route in ROUTES.values():
        add_route(router, route)
    assert len(router.routes) == len(ROUTES) > 10
