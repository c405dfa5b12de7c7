"""What a stop sent over the drone's own link answers, whichever node sent it (a fenced node, or a node
whose owner does not answer): a hold is an action, a land or return an operation no node tracks."""

from __future__ import annotations

from gateway.cluster.stoplink import direct_stop_answer
from gateway.fleet.operations.views import ActionResult, OperationView


def test_a_hold_answers_an_action_with_the_node_and_why() -> None:
    facts = {"via": "direct link", "node": "node-a"}
    out = ActionResult.model_validate(
        direct_stop_answer("alpha", "hold", "node-a", "its owner not answering", facts)
    )
    assert out.drone_id == "alpha" and out.action == "hold" and out.facts == facts
    assert out.message == (
        "hold (a reposition to where it is) sent over the drone's own link by node node-a, "
        "its owner not answering"
    )


def test_a_land_answers_an_untracked_operation_of_its_own_id() -> None:
    facts = {"via": "direct link", "node": "node-b", "autopilot": "ACCEPTED"}
    first = OperationView.model_validate(direct_stop_answer("bravo", "land", "node-b", "fenced", facts))
    second = OperationView.model_validate(direct_stop_answer("bravo", "land", "node-b", "fenced", facts))
    assert first.operation_id.startswith("direct-") and first.operation_id != second.operation_id
    assert (first.drone_id, first.kind, first.status, first.progress) == ("bravo", "land", "sent", 0.0)
    assert first.params == facts
    assert first.message == (
        "land sent over the drone's own link by node node-b, fenced; "
        "not tracked: its state shows when it lands"
    )
