"""The pool of worked examples the host shows nearest a request: every plan in it is one the host
compiles as written, none of its requests is of the corpus's test half, and nearness reads what is asked
and in which language, not the drone or the numbers."""

from __future__ import annotations

import copy
from typing import Any

import pytest

from bench.nl_corpus import select
from fleet_agent.consistency import read_plan
from fleet_agent.plan import parse_plan
from fleet_agent.prompt import POOL, POOL_FLEET, messages_for, nearest, prefix_messages
from tests.agent.test_dev_half_plans import CTX

FLEET = ["alpha", "bravo", "charlie"]


def test_the_pool_holds_requests_of_the_development_half_only() -> None:
    test_half = {e.mission.prompt(CTX) for e in select("test")}
    dev_half = {e.mission.prompt(CTX) for e in select("dev")}
    requests = [text for text, _ in POOL]
    assert len(requests) >= 100 and len(set(requests)) == len(requests)
    assert not test_half & set(requests)
    assert set(requests) <= dev_half


@pytest.mark.parametrize("example", POOL, ids=lambda e: e[0][:40])
def test_a_pool_plan_is_compiled_as_written_and_leaves_nothing_of_its_request_out(
    example: tuple[str, dict[str, Any]],
) -> None:
    request, data = example
    written = parse_plan(copy.deepcopy(data), POOL_FLEET)
    plan, gaps = read_plan(request, POOL_FLEET, copy.deepcopy(data))
    assert gaps == [] and plan.model_dump(mode="json") == written.model_dump(mode="json")
    assert data["in_english"], request


def test_the_nearest_example_of_a_pool_request_is_itself_whatever_its_drone_and_numbers() -> None:
    for request, plan in POOL[:: max(1, len(POOL) // 25)]:
        renumbered = "".join(str((int(c) + 3) % 10) if c.isdigit() else c for c in request)
        renamed = renumbered.replace("alpha", "hawk").replace("Alpha", "Hawk")
        assert nearest(renamed, ["hawk", "bravo", "charlie"])[-1] == (request, plan), request
    assert messages_for(POOL[0][0], FLEET) == [
        *prefix_messages(FLEET),
        {"role": "user", "content": f"Fleet: alpha, bravo, charlie\nRequest: {POOL[0][0]}"},
    ]  # none unless asked for


def test_the_nearest_examples_come_after_the_fixed_prefix_renamed_for_the_fleet() -> None:
    fleet = ["hawk", "kite", "owl"]
    request, _ = POOL[0]
    messages = messages_for(request.replace("alpha", "hawk"), fleet, count=3)
    prefix = prefix_messages(fleet)
    near = messages[len(prefix) : -1]
    assert messages[: len(prefix)] == prefix and len(near) == 6
    assert [m["role"] for m in near] == ["user", "assistant"] * 3
    shown = " ".join(m["content"] for m in near)
    assert not [name for name in POOL_FLEET if name in shown.lower()]
    assert messages[-1]["content"].startswith("Fleet: hawk, kite, owl")
