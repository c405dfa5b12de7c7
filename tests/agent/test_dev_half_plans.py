"""The host never makes a correct plan wrong: for every request of the corpus's development half, the
rewriting the host does before it compiles (`fleet_agent.consistency.read_plan`, the planner's own path)
leaves the plan of the scripted ideal pilot as it is, so the calls compiled from it are the ideal ones
whatever the fleet reads. Only the development half is read here."""

from __future__ import annotations

import copy

import pytest

from bench.agent_harness.missions import MissionContext
from bench.agent_harness.pilot import plan_of
from bench.nl_corpus import CorpusEntry, select
from fleet_agent.consistency import read_plan
from fleet_agent.plan import parse_plan

FLEET = ["alpha", "bravo", "charlie"]
CTX = MissionContext(
    homes={
        "alpha": (47.397742, 8.545494, 488.0),
        "bravo": (47.397742, 8.545594, 488.0),
        "charlie": (47.397742, 8.545694, 488.0),
    }
)
DEV = select("dev")


def test_the_development_half_is_read_and_only_it() -> None:
    assert len(DEV) >= 150 and {e.half for e in DEV} == {"dev"}


@pytest.mark.parametrize("entry", DEV, ids=lambda e: e.id)
def test_the_ideal_plan_of_a_dev_request_is_compiled_as_the_pilot_wrote_it(entry: CorpusEntry) -> None:
    request = entry.mission.prompt(CTX)
    data = plan_of(entry.mission.plan(CTX), FLEET)
    ideal = parse_plan(copy.deepcopy(data), FLEET)
    plan, _ = read_plan(request, FLEET, copy.deepcopy(data))
    assert plan.model_dump(mode="json") == ideal.model_dump(mode="json"), request
