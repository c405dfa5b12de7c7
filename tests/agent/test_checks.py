"""The registered checks of a compiled call and their typed outcomes."""

from __future__ import annotations

from fleet_agent.checks import (
    AfterRefusal,
    Allow,
    LinkLost,
    NothingToFly,
    OfferedTool,
    Reject,
    Replace,
    Stop,
    TurnState,
    default_checks,
    run_checks,
)
from fleet_agent.compiler import Call
from fleet_agent.mcp_link import ToolInfo
from fleet_agent.records import Refusal

TAKEOFF_SCHEMA = {
    "type": "object",
    "properties": {"drone_id": {"type": "string"}, "alt_m": {"type": "number", "exclusiveMinimum": 0}},
    "required": ["drone_id", "alt_m"],
    "additionalProperties": False,
}
TOOLS = {
    "takeoff": ToolInfo("takeoff", "", TAKEOFF_SCHEMA),
    "move_to_relative": ToolInfo("move_to_relative", "", {}),
    "formation_goto": ToolInfo("formation_goto", "", {}),
}


def _turn() -> TurnState:
    return TurnState(tools=dict(TOOLS))


def test_each_check_gives_its_outcome() -> None:
    turn = _turn()
    takeoff = Call("takeoff", {"drone_id": "alpha", "alt_m": 10.0}, "alpha")
    assert OfferedTool()(takeoff, turn) == Allow()
    assert OfferedTool()(Call("kill_motors", {}), turn) == Reject(
        "the gateway offers no kill_motors here, so it was not sent"
    )
    still = Call("move_to_relative", {"drone_id": "alpha", "north_m": 0.0, "east_m": 0.0}, "alpha")
    assert NothingToFly()(still, turn) == Reject("alpha: a move of 0 m was not sent")
    assert NothingToFly()(Call("move_to_relative", {"drone_id": "a", "alt_m": 5.0}, "a"), turn) == Allow()
    turn.refused["alpha"] = Refusal("safety_refusal", "max_altitude", "too high", {})
    assert isinstance(AfterRefusal()(takeoff, turn), Reject)
    assert AfterRefusal()(Call("land", {"drone_id": "bravo"}, "bravo"), turn) == Allow()
    assert (
        AfterRefusal()(Call("land", {"drone_id": "alpha"}, "alpha"), turn) == Allow()
    )  # landing: still sent
    assert LinkLost()(takeoff, turn) == Allow()
    turn.link_failed = True
    assert isinstance(LinkLost()(takeoff, turn), Stop)


def test_a_replace_sends_the_other_call_and_leaves_its_note() -> None:
    """No default check replaces a call (a formation of one drone cannot be planned: the schema asks
    two); a caller's own check may."""

    class Lower:
        name = "lower"

        def __call__(self, call: Call, turn: TurnState) -> Replace | Allow:
            if call.tool != "takeoff" or call.args["alt_m"] <= 30:
                return Allow()
            return Replace(Call("takeoff", {**call.args, "alt_m": 30.0}, call.drone), "capped at 30 m")

    high = Call("takeoff", {"drone_id": "bravo", "alt_m": 45.0}, "bravo")
    sent, notes, stop = run_checks([Lower(), *default_checks()], high, _turn())
    assert sent == Call("takeoff", {"drone_id": "bravo", "alt_m": 30.0}, "bravo")
    assert notes == ["capped at 30 m"] and not stop


def test_checks_run_in_order_and_the_first_reject_or_stop_wins() -> None:
    turn = _turn()
    turn.link_failed = True
    sent, notes, stop = run_checks(
        default_checks(), Call("takeoff", {"drone_id": "a", "alt_m": -1}, "a"), turn
    )
    assert sent is None and stop and notes == ["the link to the gateway failed; nothing more was sent"]
    sent, notes, stop = run_checks(
        default_checks(), Call("takeoff", {"drone_id": "a", "alt_m": 4.0}, "a"), _turn()
    )
    assert sent == Call("takeoff", {"drone_id": "a", "alt_m": 4.0}, "a") and notes == [] and not stop
