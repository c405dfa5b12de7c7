"""The safety evaluation on the simulator: every scenario of `tests.safety_eval.scenarios` played by a hostile
agent (or operator) against one gateway, judged by what reached the simulated autopilot. A scenario whose
door is still open is a strict expected failure naming it (it fails the run once the door closes, so the
mark is removed then)."""

from __future__ import annotations

from collections.abc import AsyncIterator

import pytest
import pytest_asyncio

from tests.helpers.timing import scaled
from tests.safety_eval.harness import Arena, Scenario, arena
from tests.safety_eval.scenarios import ALL

#: one scenario's bound: the walks over MCP and REST wait on four flight phases, each up to a scaled 90 s
#: (tests.safety_eval.harness.Arena.until); under load those deadlines outgrew pytest's 180 s, which then
#: cut the scenario before it said which phase failed (full run of 2026-11-30 20:17, load up to 6.8)
SCENARIO_LIMIT_S = 420


def _param(s: Scenario) -> object:
    marks = [pytest.mark.xfail(strict=True, reason=f"open door: {s.open_door}")] if s.open_door else []
    return pytest.param(s, id=s.name, marks=marks)


@pytest_asyncio.fixture(scope="module", loop_scope="module")
async def hostile_arena(tmp_path_factory: pytest.TempPathFactory) -> AsyncIterator[Arena]:
    async with arena(tmp_path_factory.mktemp("safety-eval")) as a:
        yield a


def test_at_least_sixty_distinct_scenarios() -> None:
    names = [s.name for s in ALL]
    assert len(set(names)) == len(names), "scenario names repeat"
    assert len(names) >= 60


@pytest.mark.asyncio(loop_scope="module")
@pytest.mark.timeout(scaled(SCENARIO_LIMIT_S))
@pytest.mark.parametrize("scenario", [_param(s) for s in ALL])
async def test_scenario_held_at_the_autopilot(hostile_arena: Arena, scenario: Scenario) -> None:
    verdict = await hostile_arena.run(scenario)
    assert verdict.held, (
        f"{scenario.name} ({scenario.rule}) went through: {verdict.through}\n"
        f"gateway answered: {[a.text for a in verdict.answers]}\nreached: {verdict.reached}"
    )
