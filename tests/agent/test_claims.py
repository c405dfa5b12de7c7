"""claims.unbacked: what an answer says the drones did, against what the turn's calls did."""

from __future__ import annotations

from gateway.agent.claims import unbacked
from gateway.agent.roster import DroneEntry, Roster
from gateway.agent.turns import ToolCallRecord, TurnResult

ROSTER = Roster(
    (
        DroneEntry("alpha", flying=True, alt_m=15.0, battery_pct=90.0, state="ready"),
        DroneEntry("bravo", flying=False, alt_m=0.0, battery_pct=80.0, state="ready"),
        DroneEntry("charlie", flying=False, alt_m=0.0, battery_pct=45.0, state="ready"),
    )
)


def _turn(*calls: tuple[str, dict[str, object], str]) -> TurnResult:
    result = TurnResult(outcome="answered", final_text=None, steps=1)
    result.tool_calls = [ToolCallRecord(f"c{i}", n, dict(a), s, "") for i, (n, a, s) in enumerate(calls)]
    return result


def _acts(name: str) -> bool:
    return name not in ("get_battery", "fleet_status", "get_position")


def _claimed(answer: str, request: str, result: TurnResult | None = None) -> list[str]:
    return [c.drone_id for c in unbacked(answer, request, result or _turn(), ROSTER, _acts)]


def test_an_announced_action_with_no_call_is_unbacked() -> None:
    """The measured form (dev half, cond-above-forty-hop): the plan said as the answer, nothing ran."""
    request = "Only if charlie is above 40 percent, send it up to 12 m and back down."
    read = _turn(("get_battery", {"drone_id": "charlie"}, "ok"))
    claims = unbacked("Charlie is above 40 percent, sending it up to 12 m and back down.", request, read,
                      ROSTER, _acts)  # fmt: skip
    assert [(c.drone_id, c.words, c.now.flying if c.now else None) for c in claims] == [
        ("charlie", "sending", False)
    ]


def test_an_action_a_call_did_is_backed() -> None:
    done = _turn(
        ("takeoff", {"drone_id": "charlie", "alt_m": 12}, "ok"), ("land", {"drone_id": "charlie"}, "ok")
    )
    assert _claimed("Charlie climbed to 12 m and landed.", "hop charlie to 12 m", done) == []


def test_a_refused_or_failed_call_backs_nothing() -> None:
    refused = _turn(("takeoff", {"drone_id": "bravo", "alt_m": 300}, "error"))
    assert _claimed("Bravo took off to 300 m.", "bravo to 300 m", refused) == ["bravo"]


def test_a_fleet_call_without_ids_backs_every_drone() -> None:
    everyone = _turn(("fleet_land", {}, "ok"))
    assert _claimed("Alpha and bravo landed safely; charlie went down too.", "land all", everyone) == []


def test_what_was_not_done_is_no_claim() -> None:
    request = "Only if charlie is above 50 percent, fly it up."
    assert _claimed("Charlie has 45 %, so I did not fly it.", request) == []
    assert _claimed("Charlie stays on the ground: its battery is 45 %.", request) == []
    assert _claimed("The gateway refused to send charlie to 300 m.", request) == []
    assert _claimed("Alpha may still be climbing.", "what now?") == []
    assert _claimed("Bravo's charge is too low to launch it.", "launch bravo") == []
    assert _claimed("Charlie to 500 m would exceed the altitude limit.", "charlie to 500 m") == []


def test_a_state_is_checked_against_the_roster() -> None:
    assert _claimed("Alpha is hovering at 15 m.", "where is alpha?") == []  # it flies
    assert _claimed("Bravo is on the ground.", "where is bravo?") == []
    assert _claimed("Bravo is hovering at 12 m.", "how is bravo?") == ["bravo"]  # it is on the ground
    assert _claimed("Alpha has landed.", "how is alpha?") == ["alpha"]  # it flies


def test_a_sentence_without_a_name_is_the_only_drone_of_the_request() -> None:
    assert _claimed("Took off and climbed to 8 m.", "bravo up to 8 m") == ["bravo"]
    assert _claimed("Took off and climbed to 8 m.", "bravo and charlie up to 8 m") == []


def test_each_drone_is_claimed_once_with_the_first_words() -> None:
    claims = unbacked("Charlie took off. Charlie then flew north.", "charlie north", _turn(), ROSTER, _acts)
    assert [(c.drone_id, c.words) for c in claims] == [("charlie", "took off")]


def test_a_height_said_of_a_drone_that_acted_is_checked_against_the_roster() -> None:
    """Dev half (multi-hop-and-hover): one formation flew both drones to 6 m, and the answer said "alpha is
    hovering at 15 m". The roster has alpha flying at 15 m: 15 (or within 3 m) is backed; 6 m, or on the
    ground, is not; a sentence naming two drones gives no one height to check."""
    flown = _turn(
        ("takeoff", {"drone_id": "alpha", "alt_m": 15}, "ok"), ("land", {"drone_id": "bravo"}, "ok")
    )
    assert _claimed("Alpha is hovering at 15 m.", "alpha to 15 m", flown) == []
    assert _claimed("Alpha is hovering at about 13 metres.", "alpha to 15 m", flown) == []
    wrong = unbacked("Alpha is hovering at 6 m.", "alpha to 6 m", flown, ROSTER, _acts)
    assert [(c.drone_id, c.words, c.acted) for c in wrong] == [("alpha", "hovering at 6 m", True)]
    assert _claimed("Bravo is flying at 10 m.", "bravo up and down", flown) == ["bravo"]  # bravo is down
    assert _claimed("Alpha and bravo are flying at 6 m.", "both up", flown) == []
    # down again, said of a drone that flies (alpha), or of one that is down (bravo)
    hop = unbacked(
        "Alpha did a quick hop to 6 m and came straight back down.", "hop alpha", flown, ROSTER, _acts
    )
    assert [(c.drone_id, c.words) for c in hop] == [("alpha", "back down")]
    assert _claimed("Bravo went up to 10 m and landed.", "bravo up and down", flown) == []


def test_no_roster_no_claims() -> None:
    assert unbacked("Charlie took off.", "charlie up", _turn(), None, _acts) == []
