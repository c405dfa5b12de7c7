"""The generalisation corpus (bench/nl_corpus.py) and how bench/nl_missions.py selects it (no model)."""

from __future__ import annotations

import importlib.util
import itertools
import math
import re
import sys
from collections import Counter
from collections.abc import Callable, Iterator
from pathlib import Path
from types import ModuleType

import pytest

from bench.agent_harness.missions import DroneTruth, Evidence, MissionContext
from bench.nl_corpus import CLASSES, DRONES, HALVES, CorpusEntry, corpus, farthest_apart, formation_at, select
from gateway.fleet.geo import ned_offset, offset_position

BENCH = Path(__file__).resolve().parents[2] / "bench" / "nl_missions.py"
HOMES = {
    "alpha": (47.397742, 8.545494, 488.0),
    "bravo": (47.397742, 8.545594, 488.0),
    "charlie": (47.397742, 8.545694, 488.0),
}
CTX = MissionContext(homes=HOMES)


IDLE = {d: DroneTruth(*HOMES[d][:2], 0.0, False, 90.0) for d in DRONES}


def ev(
    final: dict[str, DroneTruth], track: dict[str, list[DroneTruth]] | None = None, text: str = "Done."
) -> Evidence:
    """The drones in ``final``, the others idle on their pads; their ends as the track unless given."""
    return Evidence({**IDLE, **final}, track or {d: [t] for d, t in final.items()}, [], text)


def landed_at(lat_lon: tuple[float, float]) -> DroneTruth:
    return DroneTruth(*lat_lon, 0.0, False, 90.0)


def over(lat_lon: tuple[float, float], alt: float) -> DroneTruth:
    return DroneTruth(*lat_lon, alt, alt >= 1.0, 90.0)


@pytest.fixture(scope="module")
def bench() -> Iterator[ModuleType]:
    spec = importlib.util.spec_from_file_location("nl_missions_corpus", BENCH)
    assert spec and spec.loader
    module = importlib.util.module_from_spec(spec)
    sys.modules["nl_missions_corpus"] = module
    try:
        spec.loader.exec_module(module)
        yield module
    finally:
        sys.modules.pop("nl_missions_corpus", None)


def _sentence_length(request: str) -> int:
    """Words, or for a request in a script written without spaces (Chinese, Japanese), its characters of
    that script over two (about a word each two)."""
    unspaced = sum(1 for ch in request if "\u3040" <= ch <= "\u30ff" or "\u4e00" <= ch <= "\u9fff")
    return max(len(request.split()), unspaced // 2)


def test_every_entry_has_a_class_a_half_a_request_a_check_and_a_plan() -> None:
    entries = corpus()
    assert len(entries) >= 40
    assert len({e.id for e in entries}) == len(entries), "ids are unique"
    assert {e.cls for e in entries} == set(CLASSES), "every class is present"
    for e in entries:
        assert e.cls in CLASSES and e.half in HALVES, e.id
        assert set(e.mission.drones) <= set(DRONES), e.id
        request = e.mission.prompt(CTX)
        assert isinstance(request, str) and _sentence_length(request) >= 4, e.id
        assert callable(e.mission.check), e.id
        assert e.mission.plan(CTX), e.id
        assert set(e.mission.battery_pct) <= set(e.mission.drones), e.id


def test_requests_are_not_worded_as_tool_names() -> None:
    tool_words = ("move_to_relative", "formation_goto", "go_to_location", "return_to_launch", "_m", "alt_m")
    for e in corpus():
        request = e.mission.prompt(CTX)
        assert not any(w in request for w in tool_words), (e.id, request)
    assert len({e.mission.prompt(CTX) for e in corpus()}) == len(corpus()), "no request twice"


#: the test half until 2026-11-29 (second round), moved to dev because its figures had informed a decision
#: about the host
SECOND_ROUND_MOVED = frozenset({
    "ask-charlie-height", "ask-least-charge", "compound-out-and-home", "compound-there-and-back",
    "cond-bravo-below-bar-reports", "cond-charlie-decides-in-flight", "cond-charlie-up-or-down",
    "cond-de-alpha-west", "form-arrowhead-east", "form-es-column-south", "form-ring-northwest",
    "lang-de-charlie-south-land", "lang-es-bravo-hover", "lang-fr-alpha-east-land", "multi-all-hover",
    "multi-mixed-orders", "multi-pair-up-down", "pattern-alpha-small-square", "pattern-bravo-hexagon",
    "pattern-charlie-survey", "place-alpha-land-north-of-charlie", "place-bravo-land-east-of-home",
    "place-charlie-beside-moved-alpha", "place-fr-charlie-west-of-alpha", "refuse-bravo-1500m",
    "refuse-bravo-300m", "refuse-charlie-flat", "rel-back-and-up", "rel-east-at-alt-land", "rel-south-hover",
    "single-alpha-home", "single-bravo-bob", "units-alpha-eighty-feet", "units-bravo-feet-south",
    "units-charlie-feet-km",
})  # fmt: skip


#: the test half until 2026-11-30, moved to dev because its figures had been measured
THIRD_ROUND_MOVED = frozenset({
    "ask2-any-under-half", "ask2-it-charlie-battery", "ask2-pair-charge", "compound2-alpha-partial-retrace",
    "compound2-charlie-leg-climb-home", "compound2-de-bravo-corner-home", "cond2-alpha-provided-half",
    "cond2-charlie-then-alpha-if", "cond2-es-bravo-under-forty", "form2-fr-line-west",
    "form2-pair-column-northeast", "form2-v-south", "lang2-fr-bravo-out-back", "lang2-it-charlie-orbit",
    "lang2-pt-alpha-west-hover", "multi2-es-all-up-down", "multi2-out-back-and-wait", "multi2-stacked",
    "pattern2-alpha-triangle-north", "pattern2-charlie-survey-east", "pattern2-de-bravo-square",
    "place2-alpha-west-of-moved-charlie-lower", "place2-charlie-north-of-home-after-leg",
    "place2-es-alpha-south-of-charlie", "refuse2-alpha-500ft", "refuse2-fr-charlie-far-north",
    "refuse2-one-of-two-low", "rel2-alpha-drift-west-land", "rel2-charlie-northeast-hover",
    "rel2-de-bravo-north-east", "single2-bravo-hang", "single2-charlie-quick-look", "single2-nl-alpha-hover",
    "units2-alpha-miles-feet", "units2-charlie-km-feet-climb", "units2-es-bravo-yards-feet",
})  # fmt: skip


#: the third test half (now ``_third_round``), moved to dev later on 2026-11-30 (each entry marked "third
#: round") because its figures had been measured
THIRD_HALF_MOVED = frozenset({
    "ask3-all-able-to-launch", "ask3-alpha-ready-for-job", "ask3-fr-charge-first",
    "compound3-alpha-lower-leg-home", "compound3-bravo-halfway-back", "compound3-pt-charlie-south-west-land",
    "cond3-de-alpha-far-or-near", "cond3-es-charlie-in-range", "cond3-every-drone-over-half",
    "form3-circle-southeast", "form3-nl-row-east", "form3-single-file-north", "lang3-de-alpha-southeast-land",
    "lang3-es-charlie-west-home", "lang3-nl-bravo-north-land", "multi3-it-pair-hover", "multi3-twice-as-high",
    "multi3-west-east-apart", "pattern3-bravo-rectangle", "pattern3-charlie-circles-alpha",
    "pattern3-es-charlie-hexagon-left", "place3-bravo-midway", "place3-charlie-west-of-bravo-home",
    "place3-de-charlie-east-of-alpha", "refuse3-alpha-a-mile", "refuse3-charlie-one-metre",
    "refuse3-fr-bravo-climb-over-ceiling", "rel3-alpha-southwest-land", "rel3-bravo-east-first",
    "rel3-es-charlie-west-south", "single3-bravo-test-flight", "single3-charlie-target-height",
    "single3-fr-alpha-stay-up", "units3-charlie-mile-yards", "units3-de-bravo-feet-km",
    "units3-it-alpha-feet-yards",
})  # fmt: skip


#: the fourth test half (now ``_fourth_round``), moved to dev later on 2026-11-30 (each entry marked
#: "fourth round") because its figures had been measured
FOURTH_HALF_MOVED = frozenset({
    "ask4-bravo-and-which-other", "ask4-de-bravo-charge-flying", "ask4-fr-ground-and-weakest",
    "compound4-bravo-leg-three-times", "compound4-charlie-past-home", "compound4-it-alpha-first-turn",
    "cond4-bravo-if-fuller-than-alpha", "cond4-pl-charlie-unless-low", "cond4-pt-bravo-at-least",
    "form4-de-wedge-north", "form4-es-column-northwest", "form4-pair-feet-east", "lang4-nl-pair-up-one-lands",
    "lang4-pl-bravo-northwest-land", "lang4-pt-charlie-climb-more-land", "multi4-each-in-turn",
    "multi4-fr-three-heights", "multi4-pl-all-but-bravo", "pattern4-charlie-orbit-spot-north",
    "pattern4-de-bravo-five-passes", "pattern4-pt-alpha-pentagon", "place4-charlie-parked-south-of-alpha",
    "place4-es-charlie-west-north-of-alpha", "place4-it-charlie-southwest-of-moved-alpha",
    "refuse4-bravo-far-west-of-charlie", "refuse4-it-charlie-circle-flat", "refuse4-nl-row-450ft",
    "rel4-alpha-bearing", "rel4-bravo-further-lower", "rel4-nl-charlie-southeast",
    "single4-alpha-vertical-test", "single4-charlie-wheels-up", "single4-pl-bravo-aloft",
    "units4-alpha-quarter-km", "units4-charlie-square-feet", "units4-pl-bravo-feet-down",
})  # fmt: skip


#: the fifth test half (now ``_fifth_round``), moved to dev later on 2026-11-30 (each entry marked "fifth
#: round") because its figures had been measured
FIFTH_HALF_MOVED = frozenset({
    "ask5-it-which-over-half", "ask5-pl-two-drones-height-charge", "ask5-status-before-start",
    "compound5-alpha-two-steps-down", "compound5-de-charlie-u-turn", "compound5-fr-bravo-back-over-start",
    "cond5-it-alpha-three-tiers", "cond5-nl-low-ones-stay", "cond5-pt-charlie-twenty-points-more",
    "form5-es-wedge-south", "form5-pair-abreast-west-land", "form5-sv-row-west",
    "lang5-cs-charlie-north-land", "lang5-it-alpha-climb-stay", "lang5-sv-bravo-east-home",
    "multi5-each-north-of-own-pad", "multi5-es-pair-south-hover", "multi5-sv-alpha-lands-charlie-stays",
    "pattern5-bravo-mow-south", "pattern5-cs-charlie-two-laps", "pattern5-fr-alpha-octagon",
    "place5-alpha-stacked-over-charlie", "place5-cs-alpha-lands-north-of-charlie",
    "place5-de-alpha-over-charlie-pad", "refuse5-charlie-steps-to-150", "refuse5-de-bravo-miles-and-back",
    "refuse5-fr-alpha-skim", "rel5-alpha-half-that-west", "rel5-pl-charlie-south-east-climb",
    "rel5-sv-bravo-out-back-lower", "single5-bravo-report-height", "single5-cs-alpha-up-down",
    "single5-sv-charlie-hover", "units5-alpha-ft-miles", "units5-nl-charlie-feet-west",
    "units5-pt-bravo-feet-then-metres",
})  # fmt: skip


#: the sixth test half (now ``_sixth_round``), moved to dev on 2026-12-01 (each entry marked "sixth round")
#: because its figures had been measured
SIXTH_HALF_MOVED = frozenset({
    "ask6-de-spread-of-charges", "ask6-fi-lower-of-pair-airborne", "ask6-ro-closest-to-half",
    "compound6-cs-charlie-middle-of-first-leg", "compound6-es-alpha-retrace",
    "compound6-nl-alpha-battery-midway", "cond6-fleet-average", "cond6-pl-bravo-metres-per-percent",
    "cond6-ro-charlie-instead", "form6-da-pair-southwest", "form6-fr-line-slid-north",
    "form6-tr-column-feet-north", "lang6-da-charlie-west-home", "lang6-fi-alpha-north-land",
    "lang6-tr-bravo-climb-stay", "multi6-no-alpha-hop-bravo-stays", "multi6-south-two-land-one-home",
    "multi6-tr-alpha-on-bravo-waits", "pattern6-alpha-spokes", "pattern6-de-charlie-expanding-square",
    "pattern6-pt-bravo-zigzag", "place6-fi-charlie-bearing-from-alpha", "place6-nl-flanking-bravo",
    "place6-ro-charlie-lands-north-of-bravo", "refuse6-cs-bravo-feet-over-ceiling",
    "refuse6-da-charlie-sea-miles", "refuse6-es-bravo-wide-orbit", "rel6-it-charlie-half-higher-sw",
    "rel6-no-bravo-back-toward-start", "rel6-sv-alpha-nne", "single6-charlie-await-orders",
    "single6-da-alpha-hover", "single6-ro-bravo-up-down", "units6-alpha-yards-height",
    "units6-no-charlie-feet-sea-miles", "units6-tr-bravo-feet-west",
})  # fmt: skip

SEVENTH_HALF_MOVED = frozenset({
    "ask7-ca-bravo-three-quarters", "ask7-el-all-but-bravo", "ask7-hu-how-many-over-half",
    "compound7-ca-bravo-lands-and-again", "compound7-sv-alpha-turn-left",
    "compound7-tr-charlie-lower-back-over-home", "cond7-fi-fuller-flies-square",
    "cond7-fr-bravo-land-or-home", "cond7-nl-charlie-two-thirds", "form7-column-north-of-charlie",
    "form7-cs-line-then-lower", "form7-el-triangle-east", "lang7-hr-bravo-north-hover",
    "lang7-hu-charlie-southwest-land", "lang7-sk-alpha-east-home", "multi7-de-down-one-by-one",
    "multi7-hr-pair-east-home", "multi7-no-pair-south-bravo-hop", "pattern7-no-alpha-heptagon",
    "pattern7-pl-charlie-passes-east", "pattern7-sv-bravo-shuttle", "place7-da-alpha-below-charlie",
    "place7-fi-chain-west-then-north", "place7-pt-swap-pads", "refuse7-alpha-kilometre-square",
    "refuse7-ro-charlie-km-height", "refuse7-sk-charlie-low-beside-alpha", "rel7-es-charlie-signed",
    "rel7-it-bravo-stop-short", "rel7-pl-alpha-same-direction", "single7-ca-alpha-words",
    "single7-charlie-off-pad", "single7-el-bravo-up-down", "units7-bravo-prime-feet",
    "units7-ro-charlie-orbit-feet", "units7-tr-charlie-feet-east-of-alpha",
})  # fmt: skip


EIGHTH_HALF_MOVED = frozenset({
    "ask8-et-alpha-charge-anyone-flying", "ask8-uk-lowest-charge", "ask8-which-below-half",
    "compound8-bg-charlie-half-back-land", "compound8-bravo-drop-midway", "compound8-lt-alpha-two-legs-home",
    "cond8-et-alpha-low-goes-home", "cond8-fuller-of-bravo-charlie-east", "cond8-lv-bravo-short-hop-if-low",
    "form8-id-pair-northwest", "form8-ru-column-east-land", "form8-wedge-feet-overhead",
    "lang8-et-bravo-south-home", "lang8-ru-charlie-east-land", "lang8-vi-alpha-climb-more",
    "multi8-opposite-ways-land", "multi8-sl-pair-east-charlie-ground", "multi8-uk-three-heights",
    "pattern8-charlie-ring-east-ccw", "pattern8-lv-bravo-rectangle-left", "pattern8-ru-alpha-pentagon-left",
    "place8-charlie-north-of-parked-alpha", "place8-sl-alpha-sw-of-charlie", "place8-uk-alpha-above-charlie",
    "refuse8-all-three-one-low", "refuse8-lt-charlie-far-east", "refuse8-ru-alpha-450-feet",
    "rel8-alpha-third-back", "rel8-sl-bravo-se-and-up", "rel8-vi-charlie-ne-then-lower",
    "single8-alpha-up-then-lower", "single8-id-charlie-up-down", "single8-ru-bravo-hover",
    "units8-bg-alpha-feet-yards", "units8-charlie-cm-miles", "units8-es-bravo-km-feet-down",
})  # fmt: skip


NINTH_HALF_MOVED = frozenset({
    "ask9-alpha-and-charlie-figures", "ask9-ja-fullest", "ask9-pl-charlie-enough",
    "compound9-charlie-climb-between-home", "compound9-pl-bravo-east-south-land",
    "compound9-tr-alpha-out-back-hover", "cond9-alpha-far-or-near", "cond9-fr-charlie-up-if-charged",
    "cond9-ro-bravo-low-lands-at-once", "form9-ko-pair-column-overhead", "form9-pt-line-north-hover",
    "form9-triangle-west-land", "lang9-ja-charlie-north-land", "lang9-ko-bravo-east-hover",
    "lang9-zh-alpha-southwest-land", "multi9-bravo-down-charlie-stays", "multi9-de-pair-hop-bravo-stays",
    "multi9-zh-west-and-north", "pattern9-charlie-four-lines-east", "pattern9-de-alpha-square-right",
    "pattern9-zh-bravo-hexagon-home", "place9-alpha-north-of-moved-charlie",
    "place9-fr-charlie-east-of-alpha", "place9-ko-alpha-north-of-charlie", "refuse9-alpha-drained",
    "refuse9-de-charlie-130m", "refuse9-tr-bravo-2km-west", "rel9-alpha-sw-then-back-ne",
    "rel9-it-bravo-south-lower", "rel9-nl-charlie-west-twice", "single9-charlie-park-in-air",
    "single9-ja-bravo-hover", "single9-pt-alpha-hop", "units9-alpha-feet-yards-se",
    "units9-cs-charlie-yards-land", "units9-ro-bravo-feet-km",
})  # fmt: skip


TENTH_HALF_MOVED = frozenset({
    "ask10-ar-every-battery", "ask10-bravo-charge-no-move", "ask10-ru-lowest-charge",
    "compound10-bravo-south-east-hold", "compound10-el-charlie-east-climb-land",
    "compound10-hu-alpha-west-north-home", "cond10-bravo-at-least-70-goes-high",
    "cond10-es-alpha-north-if-charged", "cond10-sv-charlie-low-stays", "form10-da-pair-east-land",
    "form10-es-column-south", "form10-ring-overhead", "lang10-ar-bravo-north-land",
    "lang10-hi-charlie-east-hover", "lang10-th-alpha-south-home", "multi10-hi-alpha-north-charlie-hop",
    "multi10-sv-all-three-hover", "multi10-two-heights-both-land", "pattern10-bravo-pentagon-home",
    "pattern10-el-alpha-square-left", "pattern10-es-charlie-triangle-left",
    "place10-charlie-south-of-hovering-alpha", "place10-id-alpha-west-of-charlie",
    "place10-uk-charlie-north-of-alpha", "refuse10-charlie-one-and-a-half-km", "refuse10-sv-bravo-drained",
    "refuse10-vi-alpha-150m", "rel10-charlie-drop-and-west", "rel10-fi-alpha-higher-north",
    "rel10-no-bravo-east-half-back", "single10-ar-alpha-hop", "single10-bravo-sit-at-35",
    "single10-es-charlie-hover", "units10-ca-alpha-feet-hover", "units10-charlie-feet-yards-nw",
    "units10-hu-bravo-km-west-land",
})  # fmt: skip


ELEVENTH_HALF_MOVED = frozenset({
    "ask11-fullest-and-lead", "ask11-sl-charlie-charge", "ask11-zh-under-forty",
    "compound11-charlie-three-sides-land", "compound11-lv-bravo-sw-north-land",
    "compound11-tl-alpha-north-lower-home", "cond11-bg-charlie-east-unless-low", "cond11-charlie-three-bands",
    "cond11-ko-fuller-of-alpha-bravo", "form11-fr-triangle-east", "form11-it-line-southwest",
    "form11-pair-column-southeast-land", "lang11-bn-bravo-south-home", "lang11-fa-alpha-west-hover",
    "lang11-he-charlie-northwest-land", "multi11-charlie-west-alpha-same-height",
    "multi11-sk-pair-south-north", "multi11-sw-all-three-hop", "pattern11-bravo-rectangle-left",
    "pattern11-cs-alpha-passes-west-south", "pattern11-ro-charlie-triangle-right",
    "place11-alpha-lands-north-of-hovering-charlie", "place11-lt-charlie-lands-east-of-alpha",
    "place11-sk-alpha-west-below-moved-charlie", "refuse11-pair-charlie-drained",
    "refuse11-pl-alpha-far-southwest", "refuse11-tr-bravo-400-feet", "rel11-alpha-north-west-offset",
    "rel11-et-charlie-west-and-up", "rel11-ja-bravo-southeast-lower", "single11-bravo-low-hold",
    "single11-hr-alpha-hover", "single11-ms-charlie-hop", "units11-alpha-yards-up-ne-land",
    "units11-nl-charlie-feet-yards-west", "units11-sw-bravo-feet-miles-ne",
})  # fmt: skip


TWELFTH_HALF_MOVED = frozenset({
    "ask12-ar-too-low-to-launch", "ask12-ja-lower-of-pair", "ask12-needs-charge-for-job",
    "compound12-bravo-east-then-past-pad", "compound12-de-charlie-corner-climb-home",
    "compound12-vi-alpha-south-west-back", "cond12-bravo-stands-in", "cond12-es-both-or-one",
    "cond12-ko-charlie-check-aloft", "form12-fr-file-northeast-land", "form12-hu-pair-abreast-west",
    "form12-v-north", "lang12-sr-charlie-south-home", "lang12-ta-alpha-west-hover",
    "lang12-ur-bravo-northeast-land", "multi12-alpha-nw-land-bravo-up", "multi12-sv-three-ways-home",
    "multi12-zh-pair-south-bravo-high", "pattern12-charlie-orbit-pad-from-east",
    "pattern12-hi-bravo-passes-north", "pattern12-nl-alpha-square-south-left",
    "place12-charlie-alongside-alpha-west", "place12-tr-alpha-south-of-moved-charlie",
    "place12-uk-charlie-lands-sw-of-alpha", "refuse12-id-alpha-miles-northwest",
    "refuse12-ru-bravo-half-metre", "refuse12-stack-over-ceiling", "rel12-alpha-offset-then-nudge-up",
    "rel12-fi-charlie-lower-south", "rel12-it-bravo-northeast-climbing", "single12-charlie-camera-check",
    "single12-pt-bravo-above-pad", "single12-th-alpha-hop", "units12-alpha-feet-miles-home",
    "units12-el-charlie-feet-km-land", "units12-pl-bravo-feet-yards-lower",
})  # fmt: skip


THIRTEENTH_HALF_MOVED = frozenset({
    "ask13-longer-leg-of-pair", "ask13-tr-charlie-vs-bravo", "ask13-zh-closest-pair",
    "compound13-alpha-climb-leg-drop-leg", "compound13-gl-bravo-east-low-back",
    "compound13-ja-alpha-ne-then-nw", "cond13-charlie-short-of-job", "cond13-de-weakest-stays",
    "cond13-vi-bravo-holds-if-low", "form13-north-south-row-over-pads", "form13-pt-pair-either-side-of-bravo",
    "form13-ru-wedge-southeast-land", "lang13-hy-bravo-north-home", "lang13-ka-alpha-southeast-hover",
    "lang13-mr-charlie-west-land", "multi13-fan-out-bravo-climbs", "multi13-it-highest-lands",
    "multi13-kk-north-lands-south-hovers", "pattern13-charlie-triangle-two-laps",
    "pattern13-hi-bravo-square-round-pad", "pattern13-pl-alpha-diamond", "place13-charlie-east-above-alpha",
    "place13-id-flanking-charlie", "place13-nl-charlie-over-landed-alpha", "refuse13-az-bravo-low-anyway",
    "refuse13-fr-bravo-north-east-too-far", "refuse13-row-lifted-over-ceiling", "rel13-alpha-climb-to-not-by",
    "rel13-ar-charlie-bearing-300", "rel13-is-charlie-west-lower-further", "single13-af-alpha-motor-test",
    "single13-bravo-radio-relay", "single13-ko-charlie-hover-till-told",
    "units13-bravo-feet-drop-yards-south", "units13-es-charlie-yards-feet-land",
    "units13-uk-alpha-yards-back",
})  # fmt: skip


FOURTEENTH_HALF_MOVED = frozenset({
    "ask14-he-alpha-or-bravo-by-how-much", "ask14-under-a-third", "ask14-zh-average-charge",
    "compound14-alpha-staircase-north-home", "compound14-el-charlie-east-climb-back-over-pad",
    "compound14-eo-bravo-three-legs-land", "cond14-de-height-by-charge", "cond14-fa-fuller-lands-southwest",
    "cond14-within-ten-points", "form14-fr-pair-column-west-land", "form14-row-north-bravo-lands",
    "form14-sq-triangle-south", "lang14-gu-bravo-east-home", "lang14-mk-alpha-south-hover",
    "lang14-ne-charlie-northwest-land", "multi14-alpha-up-level-with-bravo",
    "multi14-es-bravo-lands-south-charlie-higher", "multi14-hr-pair-northeast-charlie-hop",
    "pattern14-alpha-figure-eight-squares", "pattern14-ca-charlie-right-triangle",
    "pattern14-fi-bravo-square-two-heights", "place14-charlie-southeast-above-alpha",
    "place14-ms-charlie-lands-north-of-moved-alpha", "place14-tr-alpha-northwest-of-charlie",
    "refuse14-charlie-yards-over-ceiling", "refuse14-cs-charlie-feet-west-too-far",
    "refuse14-uz-alpha-three-times-higher", "rel14-alpha-climb-by-the-legs",
    "rel14-eu-charlie-south-east-offset", "rel14-ko-bravo-third-back-half-height",
    "single14-charlie-wanted-overhead", "single14-cy-alpha-over-pad", "single14-ja-bravo-check-hop",
    "units14-bravo-inches-tenth-mile", "units14-ro-charlie-feet-down-metres-ne",
    "units14-sv-alpha-feet-km-yards-land",
})  # fmt: skip


FIFTEENTH_HALF_MOVED = frozenset({
    "ask15-sum-alpha-charlie", "ask15-th-bravo-short-of-full", "ask15-vi-rank-by-charge",
    "compound15-bravo-stairs-northeast", "compound15-lv-charlie-east-climb-north",
    "compound15-pl-alpha-south-half-back-climb", "cond15-charlie-job-or-hop",
    "cond15-it-charlie-west-or-alpha-east", "cond15-sl-alpha-climb-or-land", "form15-nl-v-northeast",
    "form15-pair-column-east-alpha-overhead", "form15-sr-row-then-raise", "lang15-pa-alpha-west-home",
    "lang15-sw-charlie-southwest-land", "lang15-uk-bravo-northeast-hover",
    "multi15-bn-alpha-north-charlie-down", "multi15-no-pair-west-bravo-lands-charlie-home",
    "multi15-three-jobs", "pattern15-ar-charlie-rectangle-east-first", "pattern15-bravo-l-out-and-back",
    "pattern15-is-alpha-triangle-right", "place15-charlie-lands-northwest-of-alpha",
    "place15-hi-charlie-south-above-moved-alpha", "place15-id-charlie-northeast-then-alpha-lands",
    "refuse15-alpha-long-leg-south", "refuse15-hu-charlie-climb-over-ceiling",
    "refuse15-tl-bravo-low-battery", "rel15-bravo-north-east-dropping", "rel15-et-alpha-east-then-lower",
    "rel15-pt-charlie-southwest-then-higher", "single15-charlie-just-off-the-ground", "single15-ga-alpha-hop",
    "single15-lt-bravo-hold-till-told", "units15-alpha-feet-west-south-land",
    "units15-bg-charlie-feet-km-climb", "units15-da-bravo-yards-south-feet-up",
})  # fmt: skip


SIXTEENTH_HALF_MOVED = frozenset({
    "ask16-ar-closest-to-bravo", "ask16-charlie-runs-left", "ask16-sv-second-most-charge",
    "compound16-alpha-north-then-fifty-from-pad", "compound16-ja-charlie-legs-from-height",
    "compound16-lb-bravo-low-leg-north", "cond16-fr-pair-abreast-or-fuller", "cond16-he-all-or-none",
    "cond16-heights-by-rank", "form16-ca-column-north-then-home", "form16-diagonal-row-nw-se",
    "form16-ru-row-spread-wider", "lang16-be-bravo-west-hover", "lang16-el-alpha-southeast-land",
    "lang16-ml-charlie-northeast-home", "multi16-alpha-charlie-swap-heights",
    "multi16-de-pair-north-alpha-lands-charlie-on", "multi16-ur-all-up-bravo-higher-two-land",
    "pattern16-charlie-five-pointed-star", "pattern16-hi-bravo-letter-z",
    "pattern16-ro-alpha-semicircle-north", "place16-charlie-behind-alpha",
    "place16-ms-charlie-north-of-alpha-pad-half-bravo", "place16-tr-charlie-follows-alpha",
    "refuse16-alpha-second-leg-too-far", "refuse16-bs-row-charlie-low", "refuse16-es-bravo-triple-height",
    "rel16-af-charlie-east-climbing-gradient", "rel16-alpha-east-corrected-to-west",
    "rel16-zh-bravo-mirror-across-pad", "single16-charlie-over-the-mast", "single16-ht-bravo-two-hops",
    "single16-ko-alpha-three-steps", "units16-bravo-feet-and-inches", "units16-fa-charlie-feet-km-nw-down",
    "units16-pt-alpha-feet-miles-yards-land",
})  # fmt: skip


SEVENTEENTH_HALF_MOVED = frozenset({
    "ask17-bravo-hover-minutes", "ask17-th-charlie-twice-alpha", "ask17-vi-below-average",
    "compound17-charlie-three-hops-east", "compound17-hu-bravo-halving-legs",
    "compound17-sk-charlie-dip-then-home", "cond17-charlie-three-laps-or-stay",
    "cond17-fi-fuller-north-other-south", "cond17-id-sum-over-120", "form17-el-stepped-row",
    "form17-nl-circle-by-radius", "form17-row-turned-into-column", "lang17-kn-alpha-south-climb-hover",
    "lang17-mn-charlie-east-home", "lang17-te-bravo-northwest-land", "multi17-bravo-same-as-alpha-higher",
    "multi17-cs-cross-at-two-heights", "multi17-pl-north-by-multiples", "pattern17-alpha-two-rings",
    "pattern17-is-bravo-square-and-back", "pattern17-sw-charlie-upright-square",
    "place17-charlie-on-alpha-line-twice-out", "place17-ta-charlie-stays-as-alpha-moves",
    "place17-tl-charlie-relieves-alpha", "refuse17-bravo-above-sea-level", "refuse17-da-row-lowered-too-low",
    "refuse17-no-v-far-north", "rel17-charlie-nose-east-forward-left", "rel17-hr-alpha-undo-last-two",
    "rel17-uk-bravo-four-north-three-east", "single17-charlie-quarter-of-ceiling",
    "single17-it-bravo-roof-height", "single17-mt-alpha-up-down-up", "units17-alpha-kmh-for-seconds",
    "units17-bg-charlie-yards-and-feet", "units17-et-bravo-feet-north-metres-east",
})  # fmt: skip


EIGHTEENTH_HALF_MOVED = frozenset({
    "ask18-id-alpha-against-other-two", "ask18-more-left-after-jobs", "ask18-sv-charge-in-band",
    "compound18-charlie-detour-round-hangar", "compound18-de-bravo-out-low-back-high",
    "compound18-ko-alpha-lands-out-back-higher", "cond18-ar-fuller-then-distance-by-level",
    "cond18-first-in-order-with-enough", "cond18-fr-fullest-kept-in-reserve", "form18-pt-row-by-total-length",
    "form18-ring-drawn-in", "form18-zh-pair-over-charlie-pad", "lang18-am-alpha-north-lower-hover",
    "lang18-si-bravo-west-land", "lang18-tg-charlie-southeast-home", "multi18-alpha-bravo-leapfrog-north",
    "multi18-it-south-by-own-height", "multi18-ja-charlie-watches-alpha-run", "pattern18-bravo-bow-tie",
    "pattern18-cs-charlie-rectangle-by-area", "pattern18-ru-alpha-turns-of-forty",
    "place18-charlie-alpha-in-the-middle", "place18-uk-charlie-right-of-alpha-heading",
    "place18-vi-charlie-over-alpha-mid-height", "refuse18-alpha-ten-percent-over-ceiling",
    "refuse18-pl-charlie-into-the-pit", "refuse18-ro-bravo-speed-for-time-too-far", "rel18-bravo-two-oclock",
    "rel18-fa-charlie-on-by-the-descent", "rel18-hi-alpha-right-turn-from-northeast",
    "single18-alpha-between-trees-and-line", "single18-he-charlie-halfway-down",
    "single18-tr-bravo-height-corrected", "units18-alpha-knots-for-seconds",
    "units18-es-bravo-feet-above-sea-level", "units18-nl-charlie-feet-over-mast",
})  # fmt: skip


NINETEENTH_HALF_MOVED = frozenset({
    "ask19-bn-total-above-reserve", "ask19-first-to-run-out", "ask19-ur-bravo-against-midpoint",
    "compound19-bg-charlie-zigzag-straight-back", "compound19-bravo-route-told-backwards",
    "compound19-hu-alpha-marker-posts", "cond19-ca-all-up-low-ones-land", "cond19-charlie-north-by-its-lead",
    "cond19-sk-middle-charge-flies", "form19-ms-v-with-bravo-leading", "form19-row-spaced-by-height",
    "form19-th-row-in-reverse-order", "lang19-km-alpha-east-land", "lang19-lo-charlie-north-west-hover",
    "lang19-zu-bravo-south-home", "multi19-fi-pair-takes-turns-hopping", "multi19-hand-over-in-turn",
    "multi19-no-charlie-mirrors-alpha", "pattern19-charlie-sawtooth-profile",
    "pattern19-sl-alpha-hexagon-by-perimeter", "pattern19-sr-bravo-rectangle-by-diagonal",
    "place19-ceb-charlie-west-by-alpha-height", "place19-charlie-between-ten-from-alpha",
    "place19-jv-charlie-where-alpha-was", "refuse19-af-bravo-climb-rate-over-ceiling",
    "refuse19-et-alpha-diagonal-past-limit", "refuse19-row-too-tight", "rel19-alpha-quarter-turn-round-pad",
    "rel19-sw-charlie-pad-to-its-southwest", "rel19-tl-bravo-grid-squares", "single19-alpha-under-crane-hook",
    "single19-da-bravo-down-in-steps", "single19-el-charlie-tallest-tree", "units19-alpha-chains",
    "units19-ky-charlie-millimetres", "units19-lt-bravo-paces",
})  # fmt: skip


TWENTIETH_HALF_MOVED = frozenset({
    "ask20-bg-lead-over-second", "ask20-jv-charlie-missions-left", "ask20-spread-fullest-emptiest",
    "compound20-bravo-lands-at-first-sensor", "compound20-sk-alpha-west-climb-south-land",
    "compound20-sw-charlie-half-way-back", "cond20-alpha-lead-of-twenty-or-charlie",
    "cond20-da-sixty-percent-fly-north", "cond20-ky-bravo-or-alpha-south-land", "form20-ca-triangle-south",
    "form20-column-west", "form20-sr-row-over-charlie-pad", "lang20-my-alpha-west-land",
    "lang20-so-charlie-east-north-land", "lang20-yo-bravo-north-east-hover",
    "multi20-alpha-charlie-swap-pads", "multi20-hu-spread-bravo-back-down",
    "multi20-th-pair-north-one-returns", "pattern20-alpha-mow-north", "pattern20-bn-charlie-square-left",
    "pattern20-tl-bravo-triangle-right", "place20-af-charlie-east-of-alpha",
    "place20-charlie-north-lower-than-alpha", "place20-sl-charlie-over-alpha-pad-above-bravo",
    "refuse20-ceb-alpha-down-to-one-metre", "refuse20-charlie-low-battery",
    "refuse20-ms-bravo-second-leg-too-far", "rel20-bravo-staircase-north", "rel20-el-alpha-quarter-back",
    "rel20-lt-charlie-southeast-climb", "single20-bravo-level-with-mast-light",
    "single20-fi-alpha-twice-as-high", "single20-ur-charlie-two-hops", "units20-alpha-feet-yards",
    "units20-et-bravo-cm-km", "units20-no-charlie-feet-km",
})  # fmt: skip


def test_halves_are_disjoint_and_stratified_by_class() -> None:
    """The dev half holds every entry written before the twenty-first test half (771, and the 36 of the
    twentieth test half, moved later on 2026-12-05); the test half is the twenty-first
    (``_twenty_first_test_half``), 3 a class."""
    dev, test = select("dev"), select("test")
    assert not {e.id for e in dev} & {e.id for e in test}
    assert len(dev) + len(test) == len(corpus()) == len(select("all"))
    assert len(test) == 36 and len(dev) == 807
    assert Counter(e.cls for e in test) == Counter(dict.fromkeys(CLASSES, 3))
    per_dev = Counter(e.cls for e in dev)
    assert per_dev == Counter({
        "single": 65, "multi": 71, "compound": 73, "conditional": 73, "formation": 68, "relative": 70,
        "question": 67, "refusal": 64, "units": 63, "pattern": 63, "placement": 67, "language": 63,
    })  # fmt: skip


def test_the_test_entries_seen_are_dev_and_replaced_by_new_ones() -> None:
    """The rounds of 2026-11-29 to 2026-12-05: the 8 test entries seen while tuning, then the whole test
    half (35) whose figures had informed a decision, then fifteen times the whole test half (36) once
    measured, once the whole test half (36) whose failures had informed changes to the host, and three times
    more the whole test half (36) once measured on both models, moved to dev; the test half holds none of
    them."""
    first_round = {
        "cond-half-battery-go",
        "cond-fullest-flies",
        "cond-weaker-flies",
        "form-column-north",
        "form-wedge-east",
        "place-charlie-south-of-alpha",
        "place-alpha-west-of-flying-bravo",
        "place-alpha-northeast-of-charlie",
    }
    moved = (
        first_round
        | SECOND_ROUND_MOVED
        | THIRD_ROUND_MOVED
        | THIRD_HALF_MOVED
        | FOURTH_HALF_MOVED
        | FIFTH_HALF_MOVED
        | SIXTH_HALF_MOVED
        | SEVENTH_HALF_MOVED
        | EIGHTH_HALF_MOVED
        | NINTH_HALF_MOVED
        | TENTH_HALF_MOVED
        | ELEVENTH_HALF_MOVED
        | TWELFTH_HALF_MOVED
        | THIRTEENTH_HALF_MOVED
        | FOURTEENTH_HALF_MOVED
        | FIFTEENTH_HALF_MOVED
        | SIXTEENTH_HALF_MOVED
        | SEVENTEENTH_HALF_MOVED
        | EIGHTEENTH_HALF_MOVED
        | NINETEENTH_HALF_MOVED
        | TWENTIETH_HALF_MOVED
    )
    by_id = {e.id: e for e in corpus()}
    assert all(by_id[i].half == "dev" for i in moved)
    test_ids = {e.id for e in select("test")}
    assert not test_ids & moved
    # the new test requests are new wordings, not the moved ones reworded into the same ids
    old_requests = {by_id[i].mission.prompt(CTX) for i in moved}
    assert not {e.mission.prompt(CTX) for e in select("test")} & old_requests


def test_the_test_half_is_written_in_several_languages() -> None:
    """Beside the language class, at least 12 test requests are in a language other than English: each
    of them has none of the English words every English request of the half uses one of."""
    english = re.compile(r"\b(the|to|and|up|at|of|is|then|with|any)\b", re.IGNORECASE)
    others = [e for e in select("test") if e.cls != "language" and not english.search(e.mission.prompt(CTX))]
    assert len(others) >= 12, [e.id for e in others]
    assert len({e.cls for e in others}) >= 10, "spread over the classes"
    assert all(not english.search(e.mission.prompt(CTX)) for e in select("test") if e.cls == "language")


def test_select_refuses_an_unknown_half() -> None:
    with pytest.raises(ValueError, match=r"half must be one of \['dev', 'test', 'all'\]; got 'train'"):
        select("train")


@pytest.mark.parametrize("half", ["dev", "test", "all"])
def test_the_bench_half_option_selects_that_half(bench: ModuleType, half: str) -> None:
    args = bench.parse_args(["--half", half])
    missions, where = bench.chosen_missions(args)
    assert [m.id for m in missions] == [e.id for e in select(half)]
    assert all(where[m.id][1] in ((half,) if half != "all" else HALVES) for m in missions)


def test_missions_with_a_half_run_those_requests_of_it(bench: ModuleType) -> None:
    wanted = [e.id for e in select("dev")][:2]
    missions, _ = bench.chosen_missions(bench.parse_args(["--half", "dev", "--missions", ",".join(wanted)]))
    assert [m.id for m in missions] == wanted


def test_missions_naming_no_request_of_the_half_are_refused(bench: ModuleType) -> None:
    test_id = select("test")[0].id
    with pytest.raises(SystemExit, match=f"--missions '{test_id}' names no request of the dev half"):
        bench.chosen_missions(bench.parse_args(["--half", "dev", "--missions", test_id]))


def test_without_half_the_bench_runs_its_own_missions(bench: ModuleType) -> None:
    missions, where = bench.chosen_missions(bench.parse_args([]))
    assert where == {} and "takeoff-land" in {m.id for m in missions}


def test_on_sitl_requests_that_set_a_battery_are_left_out(bench: ModuleType) -> None:
    missions, _ = bench.chosen_missions(bench.parse_args(["--half", "all", "--sitl"]))
    ids = {m.id for m in missions}
    assert ids and all(not m.battery_pct for m in missions)
    assert ids < {e.id for e in corpus()}


def test_runs_are_reported_per_half_and_class(bench: ModuleType) -> None:
    def run(mission: str, cls: str, half: str, ok: bool) -> object:
        r = bench.MissionRun(mission, ok, "detail", 1, 0, 0, 10, 5, 1, "answered", 1.0, ["takeoff()=ok"])
        r.cls, r.half, r.failure = cls, half, None if ok else "wrong_outcome"
        return r

    runs = [
        run("a", "single", "test", True),
        run("b", "single", "test", False),
        run("c", "refusal", "dev", True),
    ]
    rows = bench.class_rows(runs)
    assert ["dev", "refusal", "1/1", "100 %", "-"] in rows
    assert ["test", "single", "1/2", "50 %", "wrong_outcome"] in rows
    assert ["test", "TOTAL", "1/2", "50 %", "wrong_outcome"] in rows
    assert bench.failure_lines(runs) == ["- `b` run 1: wrong_outcome - detail; calls: takeoff()=ok"]


def test_shared_dir_option_and_env_find_the_local_model_script(
    bench: ModuleType, monkeypatch, tmp_path
) -> None:
    monkeypatch.delenv("FLEET_SHARED_DIR", raising=False)
    assert bench.local_model_script(bench.parse_args([])) == bench.LOCAL_MODEL_SCRIPT
    args = bench.parse_args(["--shared-dir", str(tmp_path)])
    assert bench.local_model_script(args) == tmp_path / "llm" / "serve-local-model"
    monkeypatch.setenv("FLEET_SHARED_DIR", str(tmp_path / "elsewhere"))
    assert (
        bench.local_model_script(bench.parse_args([])) == tmp_path / "elsewhere" / "llm" / "serve-local-model"
    )


def _hovering(drone: str, north: float, east: float, alt: float) -> DroneTruth:
    lat, lon = CTX.point(drone, north, east)
    return DroneTruth(lat, lon, alt, True, 90.0)


def test_formation_check_reads_spacing_centre_and_altitude() -> None:
    # bravo's home is the centre of the three homes; a line 8 m apart there at 20 m passes
    good = {d: _hovering("bravo", 0, east, 20) for d, east in zip(DRONES, (-8, 0, 8), strict=True)}
    ev = Evidence(final=good, track={}, tool_results=[], final_text="done")
    assert formation_at(CTX, ev, DRONES, 20, 8, 0, 0).ok
    assert not formation_at(CTX, ev, DRONES, 20, 8, 40, 0).ok, "the centre was asked 40 m north"
    assert not formation_at(CTX, ev, DRONES, 20, 15, 0, 0).ok, "15 m spacing was asked"
    low = {d: _hovering("bravo", 0, east, 5) for d, east in zip(DRONES, (-8, 0, 8), strict=True)}
    assert not formation_at(CTX, Evidence(low, {}, [], "done"), DRONES, 20, 8, 0, 0).ok


def test_farthest_apart_tells_three_in_a_ring_from_three_in_a_row() -> None:
    row = {d: _hovering("bravo", 0, east, 20) for d, east in zip(DRONES, (-10, 0, 10), strict=True)}
    ring = {
        d: _hovering("bravo", n, e, 20)
        for d, (n, e) in zip(DRONES, ((5.77, 0), (-2.89, 5), (-2.89, -5)), strict=True)
    }
    assert farthest_apart(Evidence(ring, {}, [], "done"), DRONES, 10).ok
    assert not farthest_apart(Evidence(row, {}, [], "done"), DRONES, 10).ok, (
        "a row 10 m apart has its ends 20 m apart"
    )
    assert farthest_apart(Evidence(row, {}, [], "done"), DRONES, 20).ok


def test_every_check_fails_when_nothing_happened() -> None:
    """No drone moved, nothing was refused, the answer says nothing: no request is done by that."""
    idle = {d: DroneTruth(*HOMES[d][:2], 0.0, False, 90.0) for d in DRONES}
    ev = Evidence(final=idle, track={d: [t] for d, t in idle.items()}, tool_results=[], final_text="Done.")
    assert [e.id for e in corpus() if e.mission.check(CTX, ev).ok] == []


def test_an_interrupted_bench_still_reports_the_runs_that_finished(
    bench: ModuleType, monkeypatch, tmp_path
) -> None:
    import asyncio
    import json

    async def one_then_cancelled(args, console) -> list:
        args.tool_list = "9 of 54 tools"
        r = bench.MissionRun("single-bravo-bob", True, "ok", 2, 0, 0, 10, 5, 2, "answered", 1.0, [])
        r.cls, r.half = "single", "test"
        args.completed.append(r)
        raise asyncio.CancelledError

    monkeypatch.setattr(bench, "run_missions", one_then_cancelled)
    out = tmp_path / "runs.json"
    assert bench.main(["--half", "test", "--json", str(out)]) == 130
    data = json.loads(out.read_text())
    assert data["interrupted"] is True and [r["mission"] for r in data["runs"]] == ["single-bravo-bob"]


def _entry(mid: str) -> CorpusEntry:
    return next(e for e in corpus() if e.id == mid)


def _track(drone: str, legs: list[tuple[float, float]], alt: float) -> list[DroneTruth]:
    """Samples every metre along ``legs`` flown from the drone's home at ``alt``."""
    out, north, east = [_hovering(drone, 0, 0, alt)], 0.0, 0.0
    for n, e in legs:
        steps = max(1, int(max(abs(n), abs(e))))
        for i in range(1, steps + 1):
            out.append(_hovering(drone, north + n * i / steps, east + e * i / steps, alt))
        north, east = north + n, east + e
    return out


def test_a_wrong_outcome_fails_the_second_round_checks() -> None:
    """Each trap the test half of 2026-11-29 (second round, now dev) set: the right outcome passes, the
    likely wrong one fails."""

    # feet read as metres: 45 m instead of 45 ft
    units = _entry("units2-charlie-km-feet-climb").mission.check
    assert units(CTX, ev({"charlie": _hovering("charlie", -40, 0, 45 * 0.3048)})).ok
    assert not units(CTX, ev({"charlie": _hovering("charlie", -40, 0, 45)})).ok

    # a drone placed from itself instead of from the drone named
    lat, lon = CTX.point("charlie", -20, 0)
    place = _entry("place2-es-alpha-south-of-charlie").mission.check
    assert place(CTX, ev({"alpha": DroneTruth(lat, lon, 16, True, 90.0)})).ok
    assert not place(CTX, ev({"alpha": _hovering("alpha", -20, 0, 16)})).ok

    # a triangle turning left instead of right
    tri = _entry("pattern2-alpha-triangle-north").mission.check
    right = _track("alpha", [(24, 0), (-12, 20.78), (-12, -20.78)], 10)
    left = _track("alpha", [(24, 0), (-12, -20.78), (-12, 20.78)], 10)
    assert tri(CTX, ev({"alpha": right[-1]}, {"alpha": right})).ok
    assert not tri(CTX, ev({"alpha": left[-1]}, {"alpha": left})).ok

    # a question answered in part, or answered by flying
    ask = _entry("ask2-pair-charge").mission.check
    assert ask(CTX, ev({}, text="Bravo has 44 %, charlie 67 %.")).ok
    assert not ask(CTX, ev({}, text="Bravo has 44 %.")).ok
    assert not ask(CTX, ev({"bravo": _hovering("bravo", 0, 0, 10)}, text="Bravo 44 %, charlie 67 %.")).ok


def test_a_wrong_outcome_fails_the_third_test_half_checks() -> None:
    """Each trap the test half of 2026-11-30 sets: the right outcome passes, the likely wrong one fails."""
    idle = {d: DroneTruth(*HOMES[d][:2], 0.0, False, 90.0) for d in DRONES}

    def landed(drone: str, north: float, east: float) -> DroneTruth:
        lat, lon = CTX.point(drone, north, east)
        return DroneTruth(lat, lon, 0.0, False, 90.0)

    # "halfway back": landing at home, or where the leg ended, is wrong
    half = _entry("compound3-bravo-halfway-back").mission.check
    flown = _track("bravo", [(40, 0), (-20, 0)], 12)
    assert half(CTX, ev({"bravo": landed("bravo", 20, 0)}, {"bravo": flown})).ok
    assert not half(
        CTX, ev({"bravo": landed("bravo", 0, 0)}, {"bravo": _track("bravo", [(40, 0), (-40, 0)], 12)})
    ).ok
    assert not half(CTX, ev({"bravo": landed("bravo", 40, 0)}, {"bravo": _track("bravo", [(40, 0)], 12)})).ok

    # both branches fly: the branch the battery does not allow flies too far
    branch = _entry("cond3-de-alpha-far-or-near").mission.check
    assert branch(CTX, ev({"alpha": _hovering("alpha", 15, 0, 15)})).ok
    assert not branch(CTX, ev({"alpha": _hovering("alpha", 40, 0, 15)})).ok

    # feet read as metres, and "0,08 km" read as 8 m
    feet = _entry("units3-de-bravo-feet-km").mission.check
    right = _track("bravo", [(0, 0)], 110 * 0.3048) + _track("bravo", [(80, 0)], 110 * 0.3048)
    assert feet(CTX, ev({"bravo": landed("bravo", 80, 0)}, {"bravo": right})).ok
    as_metres = _track("bravo", [(80, 0)], 110)
    assert not feet(CTX, ev({"bravo": landed("bravo", 80, 0)}, {"bravo": as_metres})).ok
    assert not feet(CTX, ev({"bravo": landed("bravo", 8, 0)}, {"bravo": _track("bravo", [(8, 0)], 33.5)})).ok

    # an orbit around the drone's own home instead of around the drone named
    orbit = _entry("pattern3-charlie-circles-alpha").mission.check

    def circle(centre: str) -> list[DroneTruth]:
        offset = [(n - c) for n, c in zip(CTX.point(centre, 0, 0), CTX.point("charlie", 0, 0), strict=True)]
        points = [(15, 0), (0, 15), (-15, 0), (0, -15), (15, 0)]
        return [
            DroneTruth(
                CTX.point("charlie", n, e)[0] + offset[0], CTX.point("charlie", n, e)[1] + offset[1], 20, True
            )
            for n, e in points
        ]

    home = landed("charlie", 0, 0)
    assert orbit(CTX, ev({"charlie": home}, {"charlie": [*circle("alpha"), home]})).ok
    assert not orbit(CTX, ev({"charlie": home}, {"charlie": [*circle("charlie"), home]})).ok

    # a hexagon turning right instead of left
    hexagon = _entry("pattern3-es-charlie-hexagon-left").mission.check
    left = _track(
        "charlie", [(0, 15), (12.99, 7.5), (12.99, -7.5), (0, -15), (-12.99, -7.5), (-12.99, 7.5)], 12
    )
    right_turns = _track(
        "charlie", [(0, 15), (-12.99, 7.5), (-12.99, -7.5), (0, -15), (12.99, -7.5), (12.99, 7.5)], 12
    )
    assert hexagon(CTX, ev({"charlie": home}, {"charlie": left})).ok
    assert not hexagon(CTX, ev({"charlie": home}, {"charlie": right_turns})).ok

    # placed from the drone itself instead of from the drone named
    place = _entry("place3-de-charlie-east-of-alpha").mission.check
    lat, lon = CTX.point("alpha", 0, 25)
    assert place(CTX, ev({"charlie": DroneTruth(lat, lon, 15, True, 90.0)})).ok
    assert not place(CTX, ev({"charlie": _hovering("charlie", 0, 25, 15)})).ok

    # a hover too low for the gateway: taking off anyway, or with no refusal, fails
    low = _entry("refuse3-charlie-one-metre").mission.check
    refused = [{"name": "takeoff", "status": "error", "text": "1 m is below the minimum of 2 m above home"}]
    assert low(
        CTX, Evidence(idle, {d: [t] for d, t in idle.items()}, refused, "Refused: below the minimum.")
    ).ok
    assert not low(
        CTX, ev({"charlie": _hovering("charlie", 0, 0, 2)}, text="Charlie hovers at 2 m, the minimum.")
    ).ok


def test_a_wrong_outcome_fails_the_fourth_test_half_checks() -> None:
    """Each trap the fourth test half sets: the right outcome passes, the likely wrong one fails."""
    ft = 0.3048
    idle = {d: DroneTruth(*HOMES[d][:2], 0.0, False, 90.0) for d in DRONES}

    # feet read as metres
    feet = _entry("units4-pl-bravo-feet-down").mission.check
    climb = _track("bravo", [(0, 0)], 35 * ft)
    right = _hovering("bravo", 200 * ft, 0, 20 * ft)
    assert feet(CTX, ev({"bravo": right}, {"bravo": [*climb, right]})).ok
    as_metres = _hovering("bravo", 200, 0, 20)
    assert not feet(CTX, ev({"bravo": as_metres}, {"bravo": [*_track("bravo", [(0, 0)], 35), as_metres]})).ok

    # a formation whose spacing and height in feet are read as metres
    pair = _entry("form4-pair-feet-east").mission.check
    mid_lat, mid_lon = (
        (HOMES["alpha"][0] + HOMES["bravo"][0]) / 2,
        (HOMES["alpha"][1] + HOMES["bravo"][1]) / 2,
    )

    def abreast(spacing: float, alt: float) -> dict[str, DroneTruth]:
        return {
            d: DroneTruth(*offset_position(mid_lat, mid_lon, 0, 30 + side * spacing / 2), alt, True, 90.0)
            for d, side in (("alpha", -1), ("bravo", 1))
        }

    assert pair(CTX, ev(abreast(40 * ft, 60 * ft))).ok
    assert not pair(CTX, ev(abreast(40, 60))).ok

    # parked from the drone itself instead of from the drone named
    park = _entry("place4-charlie-parked-south-of-alpha").mission.check
    assert park(CTX, ev({"charlie": landed_at(CTX.point("alpha", -15, 0))})).ok
    assert not park(CTX, ev({"charlie": landed_at(CTX.point("charlie", -15, 0))})).ok

    # an orbit flown clockwise instead of counter-clockwise
    orbit = _entry("pattern4-charlie-orbit-spot-north").mission.check
    home = landed_at(CTX.point("charlie", 0, 0))
    ccw = _track("charlie", [(15, 0), (15, 15), (15, -15), (-15, -15), (-15, 15), (-15, 0)], 12)
    cw = _track("charlie", [(15, 0), (15, -15), (15, 15), (-15, 15), (-15, -15), (-15, 0)], 12)
    assert orbit(CTX, ev({"charlie": home}, {"charlie": [*ccw, home]})).ok
    assert not orbit(CTX, ev({"charlie": home}, {"charlie": [*cw, home]})).ok

    # a pentagon turning left instead of right
    pentagon = _entry("pattern4-pt-alpha-pentagon").mission.check
    sides = [(20 * math.cos(math.radians(b)), 20 * math.sin(math.radians(b))) for b in range(0, 360, 72)]
    right_turns = _track("alpha", sides, 10)
    left_turns = _track("alpha", [(n, -e) for n, e in sides], 10)
    assert pentagon(CTX, ev({"alpha": right_turns[-1]}, {"alpha": right_turns})).ok
    assert not pentagon(CTX, ev({"alpha": left_turns[-1]}, {"alpha": left_turns})).ok

    # a leg flown once instead of three times
    legs = _entry("compound4-bravo-leg-three-times").mission.check
    thrice = _track("bravo", [(0, 45)], 8)
    assert legs(CTX, ev({"bravo": landed_at(CTX.point("bravo", 0, 45))}, {"bravo": thrice})).ok
    once = _track("bravo", [(0, 15)], 8)
    assert not legs(CTX, ev({"bravo": landed_at(CTX.point("bravo", 0, 15))}, {"bravo": once})).ok

    # a bearing measured from east instead of from north
    bearing = _entry("rel4-alpha-bearing").mission.check
    assert bearing(CTX, ev({"alpha": _hovering("alpha", 20, 34.64, 15)})).ok
    assert not bearing(CTX, ev({"alpha": _hovering("alpha", 34.64, 20, 15)})).ok

    # the condition ignored: bravo flown although it has less charge than alpha
    fuller = _entry("cond4-bravo-if-fuller-than-alpha").mission.check
    assert fuller(CTX, ev({"alpha": _hovering("alpha", 0, 0, 10)})).ok
    assert not fuller(
        CTX, ev({"alpha": _hovering("alpha", 0, 0, 10), "bravo": _hovering("bravo", 0, 0, 10)})
    ).ok

    # a formation above the ceiling: refused and nothing climbed, not flown anyway
    ceiling = _entry("refuse4-nl-row-450ft").mission.check
    refused = [
        {"name": "formation_goto", "status": "error", "text": "137.2 m is above the altitude limit of 120 m"}
    ]
    assert ceiling(
        CTX, Evidence(idle, {d: [t] for d, t in idle.items()}, refused, "Refused: above the limit.")
    ).ok
    high = {d: _hovering(d, 0, 0, 137) for d in DRONES}
    assert not ceiling(
        CTX, Evidence(high, {d: [t] for d, t in high.items()}, refused, "Refused: above the limit.")
    ).ok


def test_a_wrong_outcome_fails_the_fifth_test_half_checks() -> None:
    """Each trap the fifth test half (now dev, moved in the fifth round) set: the right outcome passes, the
    likely wrong one fails."""
    ft = 0.3048
    idle = {d: DroneTruth(*HOMES[d][:2], 0.0, False, 90.0) for d in DRONES}

    # feet read as metres
    feet = _entry("units5-nl-charlie-feet-west").mission.check
    assert feet(CTX, ev({"charlie": _hovering("charlie", 0, -100 * ft, 45 * ft)})).ok
    assert not feet(CTX, ev({"charlie": _hovering("charlie", 0, -100, 45)})).ok

    # a height in feet read as metres before a climb given in metres
    mixed = _entry("units5-pt-bravo-feet-then-metres").mission.check
    north = 120 * ft
    right = [*_track("bravo", [(north, 0)], 30 * ft), _hovering("bravo", north, 0, 20)]
    down = landed_at(CTX.point("bravo", north, 0))
    assert mixed(CTX, ev({"bravo": down}, {"bravo": [*right, down]})).ok
    as_metres = _track("bravo", [(north, 0)], 30)
    assert not mixed(CTX, ev({"bravo": down}, {"bravo": [*as_metres, down]})).ok

    # alpha placed from itself, or from where charlie took off instead of where it flew
    charlie_east = _hovering("charlie", 0, 20, 12)
    stacked = _entry("place5-alpha-stacked-over-charlie").mission.check
    above = DroneTruth(*CTX.point("charlie", 0, 20), 22.0, True, 90.0)
    assert stacked(CTX, ev({"charlie": charlie_east, "alpha": above})).ok
    assert not stacked(CTX, ev({"charlie": charlie_east, "alpha": _hovering("alpha", 0, 20, 22)})).ok
    pad = _entry("place5-de-alpha-over-charlie-pad").mission.check
    charlie_south = _hovering("charlie", -30, 0, 10)
    over_pad = DroneTruth(*CTX.point("charlie", 0, 0), 12.0, True, 90.0)
    assert pad(CTX, ev({"charlie": charlie_south, "alpha": over_pad})).ok
    assert not pad(CTX, ev({"charlie": charlie_south, "alpha": _hovering("alpha", 0, 0, 12)})).ok
    north_of = _entry("place5-cs-alpha-lands-north-of-charlie").mission.check
    charlie_there = _hovering("charlie", 0, 20, 10)
    assert north_of(CTX, ev({"charlie": charlie_there, "alpha": landed_at(CTX.point("charlie", 15, 20))})).ok
    assert not north_of(
        CTX, ev({"charlie": charlie_there, "alpha": landed_at(CTX.point("charlie", 15, 0))})
    ).ok

    # an octagon turning right instead of left
    octagon = _entry("pattern5-fr-alpha-octagon").mission.check
    sides = [(10 * math.cos(math.radians(b)), 10 * math.sin(math.radians(b))) for b in range(90, -270, -45)]
    home = landed_at(CTX.point("alpha", 0, 0))
    assert octagon(CTX, ev({"alpha": home}, {"alpha": [*_track("alpha", sides, 12), home]})).ok
    mirrored = [(-n, e) for n, e in sides]
    assert not octagon(CTX, ev({"alpha": home}, {"alpha": [*_track("alpha", mirrored, 12), home]})).ok

    # one lap instead of two
    laps = _entry("pattern5-cs-charlie-two-laps").mission.check
    lap = [(10.0, 10.0), (-10.0, 10.0), (-10.0, -10.0), (10.0, -10.0)]
    over_home = _hovering("charlie", 0, 0, 14)
    twice = _track("charlie", [(0, 10), *lap, *lap, (0, -10)], 14)
    assert laps(CTX, ev({"charlie": over_home}, {"charlie": twice})).ok
    once = _track("charlie", [(0, 10), *lap, (0, -10)], 14)
    assert not laps(CTX, ev({"charlie": over_home}, {"charlie": once})).ok

    # the fuller drone flown although it is not 20 points fuller
    points = _entry("cond5-pt-charlie-twenty-points-more").mission.check
    assert points(CTX, ev({"bravo": _hovering("bravo", 0, 20, 10)})).ok
    assert not points(CTX, ev({"charlie": _hovering("charlie", 0, 20, 10)})).ok

    # the leg and the drop flown once instead of twice
    steps = _entry("compound5-alpha-two-steps-down").mission.check
    flown = [*_track("alpha", [(0, -15)], 24), *_track("alpha", [(0, -30)], 16)[16:]]
    assert steps(CTX, ev({"alpha": _hovering("alpha", 0, -30, 8)}, {"alpha": flown})).ok
    assert not steps(
        CTX, ev({"alpha": _hovering("alpha", 0, -15, 16)}, {"alpha": _track("alpha", [(0, -15)], 24)})
    ).ok

    # back over the start without coming down the 6 m asked
    lower = _entry("rel5-sv-bravo-out-back-lower").mission.check
    out = _track("bravo", [(35, 0)], 16)
    assert lower(CTX, ev({"bravo": _hovering("bravo", 0, 0, 10)}, {"bravo": out})).ok
    assert not lower(CTX, ev({"bravo": _hovering("bravo", 0, 0, 16)}, {"bravo": out})).ok

    # a pair set down abreast 50 m west passes; left hovering there, or set down where they were, fails
    pair = _entry("form5-pair-abreast-west-land").mission.check
    mid_lat, mid_lon = (
        (HOMES["alpha"][0] + HOMES["charlie"][0]) / 2,
        (HOMES["alpha"][1] + HOMES["charlie"][1]) / 2,
    )

    def abreast(east: float, alt: float) -> dict[str, DroneTruth]:
        return {
            d: DroneTruth(*offset_position(mid_lat, mid_lon, 0, east + side * 10), alt, alt > 0, 90.0)
            for d, side in (("alpha", -1), ("charlie", 1))
        }

    assert pair(CTX, ev(abreast(-50, 0.0))).ok
    assert not pair(CTX, ev(abreast(-50, 12.0))).ok
    assert not pair(CTX, ev(abreast(0, 0.0))).ok

    # skimming at the lowest altitude the gateway allows instead of being refused
    skim = _entry("refuse5-fr-alpha-skim").mission.check
    refused = [{"name": "takeoff", "status": "error", "text": "0.5 m is below the minimum altitude of 2 m"}]
    assert skim(
        CTX, Evidence(idle, {d: [t] for d, t in idle.items()}, refused, "Refused: below the minimum.")
    ).ok
    low = {**idle, "alpha": _hovering("alpha", 30, 0, 2)}
    assert not skim(
        CTX, Evidence(low, {d: [t] for d, t in low.items()}, refused, "Refused: below the minimum.")
    ).ok


def test_a_wrong_outcome_fails_the_sixth_test_half_checks() -> None:
    """Each trap the sixth test half (now dev, moved in the sixth round) set: the right outcome passes, the
    likely wrong one fails."""
    ft, yd, nm = 0.3048, 0.9144, 1852.0
    idle = {d: DroneTruth(*HOMES[d][:2], 0.0, False, 90.0) for d in DRONES}

    def over(lat_lon: tuple[float, float], alt: float) -> DroneTruth:
        return DroneTruth(*lat_lon, alt, True, 90.0)

    # feet read as metres, for the height and the leg
    feet = _entry("units6-tr-bravo-feet-west").mission.check
    down = landed_at(CTX.point("bravo", 0, -150 * ft))
    assert feet(CTX, ev({"bravo": down}, {"bravo": [*_track("bravo", [(0, -150 * ft)], 40 * ft), down]})).ok
    as_metres = landed_at(CTX.point("bravo", 0, -150))
    assert not feet(
        CTX, ev({"bravo": as_metres}, {"bravo": [*_track("bravo", [(0, -150)], 40), as_metres]})
    ).ok

    # a height in yards, and a descent in feet, read as metres
    yards = _entry("units6-alpha-yards-height").mission.check
    right = _hovering("alpha", -100 * yd, 0, 50 * yd - 40 * ft)
    assert yards(
        CTX, ev({"alpha": right}, {"alpha": [*_track("alpha", [(-100 * yd, 0)], 50 * yd), right]})
    ).ok
    wrong = _hovering("alpha", -100, 0, 50 - 40 * ft)
    assert not yards(CTX, ev({"alpha": wrong}, {"alpha": [*_track("alpha", [(-100, 0)], 50), wrong]})).ok

    # nautical miles read as kilometres
    sea = _entry("units6-no-charlie-feet-sea-miles").mission.check
    assert sea(CTX, ev({"charlie": _hovering("charlie", 0, 0.02 * nm, 50 * ft)})).ok
    assert not sea(CTX, ev({"charlie": _hovering("charlie", 0, 20, 50 * ft)})).ok

    # drones placed from themselves instead of from bravo
    flank = _entry("place6-nl-flanking-bravo").mission.check
    bravo_north = _hovering("bravo", 30, 0, 15)
    right_flanks = {
        "alpha": over(CTX.point("bravo", 30, -10), 15),
        "charlie": over(CTX.point("bravo", 30, 10), 15),
    }
    assert flank(CTX, ev({"bravo": bravo_north, **right_flanks})).ok
    own_flanks = {"alpha": _hovering("alpha", 30, -10, 15), "charlie": _hovering("charlie", 30, 10, 15)}
    assert not flank(CTX, ev({"bravo": bravo_north, **own_flanks})).ok

    # a bearing from alpha measured from charlie instead, or from east instead of north
    bearing = _entry("place6-fi-charlie-bearing-from-alpha").mission.check
    alpha_north = _hovering("alpha", 20, 0, 12)
    n, e = 25 * math.cos(math.radians(120)), 25 * math.sin(math.radians(120))
    assert bearing(CTX, ev({"alpha": alpha_north, "charlie": over(CTX.point("alpha", 20 + n, e), 12)})).ok
    assert not bearing(CTX, ev({"alpha": alpha_north, "charlie": _hovering("charlie", n, e, 12)})).ok
    assert not bearing(CTX, ev({"alpha": alpha_north, "charlie": over(CTX.point("alpha", 20 + e, n), 12)})).ok

    # charlie set down north of bravo's pad instead of where bravo landed
    beside = _entry("place6-ro-charlie-lands-north-of-bravo").mission.check
    bravo_west = landed_at(CTX.point("bravo", 0, -25))
    assert beside(CTX, ev({"bravo": bravo_west, "charlie": landed_at(CTX.point("bravo", 15, -25))})).ok
    assert not beside(CTX, ev({"bravo": bravo_west, "charlie": landed_at(CTX.point("bravo", 15, 0))})).ok

    # a zigzag flown as one straight line east
    zigzag = _entry("pattern6-pt-bravo-zigzag").mission.check
    d15 = 15 / math.sqrt(2)
    end = landed_at(CTX.point("bravo", 0, 4 * d15))
    zig = _track("bravo", [(d15, d15), (-d15, d15)] * 2, 12)
    assert zigzag(CTX, ev({"bravo": end}, {"bravo": [*zig, end]})).ok
    straight = _track("bravo", [(0, 4 * d15)], 12)
    assert not zigzag(CTX, ev({"bravo": end}, {"bravo": [*straight, end]})).ok

    # an expanding square turning left instead of right
    search = _entry("pattern6-de-charlie-expanding-square").mission.check
    legs = [(10.0, 0.0), (0.0, 10.0), (-20.0, 0.0), (0.0, -20.0), (30.0, 0.0)]
    rightward = _track("charlie", legs, 10)
    assert search(CTX, ev({"charlie": rightward[-1]}, {"charlie": rightward})).ok
    leftward = _track("charlie", [(n, -e) for n, e in legs], 10)
    assert not search(CTX, ev({"charlie": leftward[-1]}, {"charlie": leftward})).ok

    # spokes flown as a round trip that never comes back over home in between
    spokes = _entry("pattern6-alpha-spokes").mission.check
    home = landed_at(CTX.point("alpha", 0, 0))
    out_and_in = _track("alpha", [(20, 0), (-20, 0), (0, 20), (0, -20), (-20, 0), (20, 0)], 10)
    assert spokes(CTX, ev({"alpha": home}, {"alpha": [*out_and_in, home]})).ok
    ring = _track("alpha", [(20, 0), (-20, 20), (-20, -20), (20, 0)], 10)
    assert not spokes(CTX, ev({"alpha": home}, {"alpha": [*ring, home]})).ok

    # straight home instead of back along the route, leg by leg
    retrace = _entry("compound6-es-alpha-retrace").mission.check
    home = landed_at(CTX.point("alpha", 0, 0))
    back = _track("alpha", [(20, 0), (0, 30), (0, -30), (-20, 0)], 14)
    assert retrace(CTX, ev({"alpha": home}, {"alpha": [*back, home]})).ok
    direct = _track("alpha", [(20, 0), (0, 30), (-20, -30)], 14)
    assert not retrace(CTX, ev({"alpha": home}, {"alpha": [*direct, home]})).ok

    # landed at the end of the route instead of over the middle of the first leg
    middle = _entry("compound6-cs-charlie-middle-of-first-leg").mission.check
    route = _track("charlie", [(0, 40), (20, 0)], 15)
    mid = landed_at(CTX.point("charlie", 0, 20))
    assert middle(CTX, ev({"charlie": mid}, {"charlie": [*route, mid]})).ok
    end = landed_at(CTX.point("charlie", 20, 40))
    assert not middle(CTX, ev({"charlie": end}, {"charlie": [*route, end]})).ok

    # the battery reading left out of the answer
    midway = _entry("compound6-nl-alpha-battery-midway").mission.check
    home = landed_at(CTX.point("alpha", 0, 0))
    west = {"alpha": [*_track("alpha", [(0, -30), (0, 30)], 12), home]}
    assert midway(CTX, ev({"alpha": home}, west, text="Alpha had 72 % and is home.")).ok
    assert not midway(CTX, ev({"alpha": home}, west, text="Alpha is home.")).ok

    # as many metres as per cent: a fixed leg fails
    per_cent = _entry("cond6-pl-bravo-metres-per-percent").mission.check
    assert per_cent(CTX, ev({"bravo": _hovering("bravo", 42, 0, 10)})).ok
    assert not per_cent(CTX, ev({"bravo": _hovering("bravo", 10, 0, 10)})).ok

    # alpha flown although it is under 40 %, instead of charlie
    instead = _entry("cond6-ro-charlie-instead").mission.check
    assert instead(CTX, ev({"charlie": _hovering("charlie", 0, 0, 20)})).ok
    assert not instead(CTX, ev({"alpha": _hovering("alpha", 0, 0, 20)})).ok

    # the average read as a threshold each drone must pass (bravo, at 55 %, left down)
    average = _entry("cond6-fleet-average").mission.check
    up = {d: _hovering(d, 0, 0, 10) for d in DRONES}
    assert average(CTX, ev(up)).ok
    assert not average(CTX, ev({d: up[d] for d in ("alpha", "charlie")})).ok

    # a line formed where the drones are and never slid north
    slide = _entry("form6-fr-line-slid-north").mission.check

    def row(north: float) -> dict[str, DroneTruth]:
        return {d: _hovering("bravo", north, east, 12) for d, east in zip(DRONES, (-10, 0, 10), strict=True)}

    assert slide(CTX, ev(row(30))).ok
    assert not slide(CTX, ev(row(0))).ok

    # a column spaced 50 m instead of 50 ft
    column = _entry("form6-tr-column-feet-north").mission.check

    def file_of(spacing: float) -> dict[str, DroneTruth]:
        return {
            d: _hovering("bravo", 20 + k * spacing, 0, 40) for d, k in zip(DRONES, (-1, 0, 1), strict=True)
        }

    assert column(CTX, ev(file_of(50 * ft))).ok
    assert not column(CTX, ev(file_of(50))).ok

    # north-north-east flown as north-east
    nne = _entry("rel6-sv-alpha-nne").mission.check
    a = math.radians(22.5)
    assert nne(CTX, ev({"alpha": _hovering("alpha", 30 * math.cos(a), 30 * math.sin(a), 12)})).ok
    assert not nne(CTX, ev({"alpha": _hovering("alpha", 30 / math.sqrt(2), 30 / math.sqrt(2), 12)})).ok

    # 15 m back toward the start read as 15 m from the start
    back_toward = _entry("rel6-no-bravo-back-toward-start").mission.check
    out = _track("bravo", [(0, 40)], 10)
    assert back_toward(CTX, ev({"bravo": _hovering("bravo", 0, 25, 10)}, {"bravo": out})).ok
    assert not back_toward(CTX, ev({"bravo": _hovering("bravo", 0, 15, 10)}, {"bravo": out})).ok

    # charlie landed with the others instead of coming home
    split = _entry("multi6-south-two-land-one-home").mission.check
    south = {d: landed_at(CTX.point(d, -25, 0)) for d in ("alpha", "bravo")}
    went = {d: [*_track(d, [(-25, 0)], 10), south.get(d, landed_at(CTX.point(d, 0, 0)))] for d in DRONES}
    assert split(CTX, ev({**south, "charlie": landed_at(CTX.point("charlie", 0, 0))}, went)).ok
    assert not split(CTX, ev({**south, "charlie": landed_at(CTX.point("charlie", -25, 0))}, went)).ok

    # the climb to stay at flown as a leg north
    stay = _entry("lang6-tr-bravo-climb-stay").mission.check
    assert stay(CTX, ev({"bravo": _hovering("bravo", 0, 0, 20)})).ok
    assert not stay(CTX, ev({"bravo": _hovering("bravo", 8, 0, 12)})).ok

    # the landing at the end dropped
    north_land = _entry("lang6-fi-alpha-north-land").mission.check
    flown = _track("alpha", [(30, 0)], 14)
    landed = landed_at(CTX.point("alpha", 30, 0))
    assert north_land(CTX, ev({"alpha": landed}, {"alpha": [*flown, landed]})).ok
    assert not north_land(CTX, ev({"alpha": flown[-1]}, {"alpha": flown})).ok

    # the fuller of the pair named instead of the emptier one, or the spread's readings left out
    pair = _entry("ask6-fi-lower-of-pair-airborne").mission.check
    assert pair(CTX, ev({}, text="bravo: 52 %, on the ground; charlie: 90 %, on the ground")).ok
    assert not pair(CTX, ev({}, text="charlie: 90 %, on the ground")).ok
    spread = _entry("ask6-de-spread-of-charges").mission.check
    assert spread(CTX, ev({}, text="34 Prozentpunkte.")).ok
    assert spread(CTX, ev({}, text="alpha: 81 %; bravo: 47 %; charlie: 66 %")).ok
    assert not spread(CTX, ev({}, text="Alpha hat 81 %.")).ok

    # a climb past the ceiling given in feet: refused and not flown through
    ceiling = _entry("refuse6-cs-bravo-feet-over-ceiling").mission.check
    refused = [
        {
            "name": "move_to_relative",
            "status": "error",
            "text": "125.7 m is above the altitude limit of 120 m",
        }
    ]
    at_80 = {**idle, "bravo": _hovering("bravo", 0, 0, 80)}
    assert ceiling(
        CTX, Evidence(at_80, {d: [t] for d, t in at_80.items()}, refused, "Refused: above the limit.")
    ).ok
    high = {**idle, "bravo": _hovering("bravo", 0, 0, 125.7)}
    assert not ceiling(
        CTX, Evidence(high, {d: [t] for d, t in high.items()}, refused, "Refused: above the limit.")
    ).ok


def test_a_wrong_outcome_fails_the_seventh_test_half_checks() -> None:
    """Each trap the seventh test half sets: the right outcome passes, the likely wrong one fails."""
    ft = 0.3048
    idle = {d: DroneTruth(*HOMES[d][:2], 0.0, False, 90.0) for d in DRONES}

    def over(lat_lon: tuple[float, float], alt: float) -> DroneTruth:
        return DroneTruth(*lat_lon, alt, True, 90.0)

    def flown(drone: str, legs: list[tuple[float, float]], alt: float, end: DroneTruth) -> Evidence:
        return ev({drone: end}, {drone: [*_track(drone, legs, alt), end]})

    def refused(final: dict[str, DroneTruth], text: str) -> Evidence:
        result = [{"name": "takeoff", "status": "error", "text": text}]
        truth = {**idle, **final}
        return Evidence(truth, {d: [t] for d, t in truth.items()}, result, "Refused: over the limit.")

    def polygon(sides: int, side: float, first_deg: float, turn_deg: float) -> list[tuple[float, float]]:
        bearings = [math.radians(first_deg + i * turn_deg) for i in range(sides)]
        return [(side * math.cos(b), side * math.sin(b)) for b in bearings]

    home = {d: landed_at(CTX.point(d, 0, 0)) for d in DRONES}

    # a number written in words misread ("sis" alone is six)
    words = _entry("single7-ca-alpha-words").mission.check
    assert words(CTX, ev({"alpha": _hovering("alpha", 0, 0, 26)})).ok
    assert not words(CTX, ev({"alpha": _hovering("alpha", 0, 0, 6)})).ok

    # the landing at the end dropped, or a landing added to a request that keeps the drone up
    up_down = _entry("single7-el-bravo-up-down").mission.check
    assert up_down(CTX, flown("bravo", [(0, 0)], 13, home["bravo"])).ok
    assert not up_down(CTX, ev({"bravo": _hovering("bravo", 0, 0, 13)})).ok
    off_pad = _entry("single7-charlie-off-pad").mission.check
    assert off_pad(CTX, ev({"charlie": _hovering("charlie", 0, 0, 17)})).ok
    assert not off_pad(CTX, flown("charlie", [(0, 0)], 17, home["charlie"])).ok

    # the pair left where it flew instead of coming home
    pair = _entry("multi7-hr-pair-east-home").mission.check
    out = {d: [*_track(d, [(0, 20), (0, -20)], 10), home[d]] for d in ("bravo", "charlie")}
    assert pair(CTX, ev({d: home[d] for d in ("bravo", "charlie")}, out)).ok
    east = {d: landed_at(CTX.point(d, 0, 20)) for d in ("bravo", "charlie")}
    assert not pair(CTX, ev(east, {d: [*_track(d, [(0, 20)], 10), east[d]] for d in east})).ok

    # all three brought down, alpha too
    one_by_one = _entry("multi7-de-down-one-by-one").mission.check
    up = {d: [*_track(d, [(0, 0)], 15), home[d]] for d in DRONES}
    assert one_by_one(
        CTX,
        ev({"alpha": _hovering("alpha", 0, 0, 15), "bravo": home["bravo"], "charlie": home["charlie"]}, up),
    ).ok
    assert not one_by_one(CTX, ev(dict(home), up)).ok

    # bravo's landing dropped
    south = _entry("multi7-no-pair-south-bravo-hop").mission.check
    pair_south = {d: _hovering(d, -15, 0, 12) for d in ("alpha", "charlie")}
    hop = [*_track("bravo", [(0, 0)], 25), home["bravo"]]
    assert south(
        CTX,
        ev({**pair_south, "bravo": home["bravo"]}, {**{d: [t] for d, t in pair_south.items()}, "bravo": hop}),
    ).ok
    assert not south(CTX, ev({**pair_south, "bravo": _hovering("bravo", 0, 0, 25)})).ok

    # the landing at the far point dropped (flown there and straight back), or a landing added at the end
    again = _entry("compound7-ca-bravo-lands-and-again").mission.check
    there = [*_track("bravo", [(0, 30)], 12), landed_at(CTX.point("bravo", 0, 30))]
    over_start = _hovering("bravo", 0, 0, 8)
    assert again(
        CTX, ev({"bravo": over_start}, {"bravo": [*there, _hovering("bravo", 0, 30, 8), over_start]})
    ).ok
    straight_back = [*_track("bravo", [(0, 30), (0, -30)], 12), over_start]
    assert not again(CTX, ev({"bravo": over_start}, {"bravo": straight_back})).ok
    assert not again(CTX, ev({"bravo": home["bravo"]}, {"bravo": [*there, home["bravo"]]})).ok

    # a left turn after flying north flown as a right turn
    left = _entry("compound7-sv-alpha-turn-left").mission.check
    assert left(CTX, flown("alpha", [(30, 0), (0, -15)], 10, landed_at(CTX.point("alpha", 30, -15)))).ok
    assert not left(CTX, flown("alpha", [(30, 0), (0, 15)], 10, landed_at(CTX.point("alpha", 30, 15)))).ok

    # back over home read as a return home that lands
    over_home = _entry("compound7-tr-charlie-lower-back-over-home").mission.check
    south_leg = _track("charlie", [(-25, 0)], 14)
    assert over_home(
        CTX,
        ev(
            {"charlie": _hovering("charlie", 0, 0, 6)},
            {"charlie": [*south_leg, _hovering("charlie", 0, 0, 6)]},
        ),
    ).ok
    assert not over_home(CTX, ev({"charlie": home["charlie"]}, {"charlie": [*south_leg, home["charlie"]]})).ok

    # two thirds read as 60 %: charlie, at 61 %, flown
    thirds = _entry("cond7-nl-charlie-two-thirds").mission.check
    assert thirds(CTX, ev({}, text="charlie: battery 61 %, on the ground.")).ok
    assert not thirds(CTX, ev({"charlie": _hovering("charlie", 0, 0, 12)}, text="charlie: battery 61 %.")).ok

    # the low branch ignored: brought home instead of set down where it is
    land_or_home = _entry("cond7-fr-bravo-land-or-home").mission.check
    assert land_or_home(CTX, flown("bravo", [(30, 0)], 10, landed_at(CTX.point("bravo", 30, 0)))).ok
    assert not land_or_home(CTX, flown("bravo", [(30, 0), (-30, 0)], 10, home["bravo"])).ok

    # the emptier drone flown instead of the fuller one
    fuller = _entry("cond7-fi-fuller-flies-square").mission.check
    square = [(15, 0), (0, 15), (-15, 0), (0, -15)]
    assert fuller(CTX, flown("charlie", square, 10, home["charlie"])).ok
    assert not fuller(CTX, flown("alpha", square, 10, home["alpha"])).ok

    # a triangle of three flown as a row with the same spacing
    triangle = _entry("form7-el-triangle-east").mission.check
    r = 16 / math.sqrt(3)
    ring = {
        d: _hovering("bravo", n, 25 + e, 14)
        for d, (n, e) in zip(DRONES, ((r, 0), (-r / 2, 8), (-r / 2, -8)), strict=True)
    }
    assert triangle(CTX, ev(ring)).ok
    row = {d: _hovering("bravo", 0, 25 + e, 14) for d, e in zip(DRONES, (-16, 0, 16), strict=True)}
    assert not triangle(CTX, ev(row)).ok

    # the column centred north of the pair's own centre instead of north of charlie
    column = _entry("form7-column-north-of-charlie").mission.check
    right = {"alpha": over(CTX.point("charlie", 35, 0), 15), "bravo": over(CTX.point("charlie", 25, 0), 15)}
    assert column(CTX, ev(right)).ok
    mid = CTX.point("alpha", 0, 0)[1] / 2 + CTX.point("bravo", 0, 0)[1] / 2
    own = {
        "alpha": over((CTX.point("alpha", 35, 0)[0], mid), 15),
        "bravo": over((CTX.point("alpha", 25, 0)[0], mid), 15),
    }
    assert not column(CTX, ev(own)).ok

    # the line formed and never lowered
    lowered = _entry("form7-cs-line-then-lower").mission.check
    line = {d: (-10 + 10 * k) for k, d in enumerate(DRONES)}
    climbed = {d: [_hovering("bravo", 0, e, 20), _hovering("bravo", 0, e, 8)] for d, e in line.items()}
    low = {d: _hovering("bravo", 0, e, 8) for d, e in line.items()}
    assert lowered(CTX, ev(low, climbed)).ok
    assert not lowered(CTX, ev({d: _hovering("bravo", 0, e, 20) for d, e in line.items()})).ok

    # a signed offset read without its sign
    signed = _entry("rel7-es-charlie-signed").mission.check
    assert signed(CTX, ev({"charlie": _hovering("charlie", -20, 15, 12)})).ok
    assert not signed(CTX, ev({"charlie": _hovering("charlie", 20, 15, 12)})).ok

    # "the same direction" flown back the other way
    same = _entry("rel7-pl-alpha-same-direction").mission.check
    west = _track("alpha", [(0, -25)], 10)
    assert same(
        CTX, ev({"alpha": _hovering("alpha", 0, -50, 15)}, {"alpha": [*west, _hovering("alpha", 0, -50, 15)]})
    ).ok
    assert not same(
        CTX, ev({"alpha": _hovering("alpha", 0, 0, 15)}, {"alpha": [*west, _hovering("alpha", 0, 0, 15)]})
    ).ok

    # flown to the point itself instead of 10 m short of it
    short = _entry("rel7-it-bravo-stop-short").mission.check
    assert short(CTX, ev({"bravo": _hovering("bravo", 30, 0, 14)})).ok
    assert not short(CTX, ev({"bravo": _hovering("bravo", 40, 0, 14)})).ok

    # questions: the readings listed pass; a count, a yes or no, or the wrong drone's reading does not
    listing = (
        "alpha: battery 64 %, on the ground. bravo: battery 45 %, on the ground. "
        "charlie: battery 77 %, on the ground."
    )
    how_many = _entry("ask7-hu-how-many-over-half").mission.check
    assert how_many(CTX, ev({}, text=listing)).ok
    assert not how_many(CTX, ev({}, text="Kettőnek.")).ok
    quarters = _entry("ask7-ca-bravo-three-quarters").mission.check
    assert quarters(CTX, ev({}, text="bravo: battery 71 %, on the ground.")).ok
    assert not quarters(CTX, ev({}, text="No: under 75 %.")).ok
    but_bravo = _entry("ask7-el-all-but-bravo").mission.check
    assert but_bravo(CTX, ev({}, text="alpha: battery 58 %. charlie: battery 43 %.")).ok
    assert not but_bravo(CTX, ev({}, text="bravo: battery 90 %.")).ok

    # a height in kilometres flown as metres past the ceiling
    km = _entry("refuse7-ro-charlie-km-height").mission.check
    assert km(CTX, refused({}, "150 m is above the altitude limit of 120 m")).ok
    high = _hovering("charlie", 0, 0, 150)
    assert not km(
        CTX, Evidence({**idle, "charlie": high}, {"charlie": [high]}, [], "Charlie is at 150 m.")
    ).ok

    # kilometres read as metres: a small square flown, nothing refused
    big_square = _entry("refuse7-alpha-kilometre-square").mission.check
    assert big_square(
        CTX,
        refused({"alpha": _hovering("alpha", 0, 0, 30)}, "1500 m from home is beyond the 1000 m geofence"),
    ).ok
    assert not big_square(
        CTX, flown("alpha", [(1.5, 0), (0, 1.5), (-1.5, 0), (0, -1.5)], 30, home["alpha"])
    ).ok

    # a refusal for charlie's battery answered as if charlie had flown
    low_battery = _entry("refuse7-sk-charlie-low-beside-alpha").mission.check
    assert low_battery(CTX, refused({}, "charlie's battery 19 % is below the takeoff minimum of 30 %")).ok
    result = [{"name": "takeoff", "status": "error", "text": "battery below the takeoff minimum"}]
    assert not low_battery(
        CTX, Evidence(dict(idle), {d: [t] for d, t in idle.items()}, result, "Charlie is in place.")
    ).ok

    # feet written with a prime read as metres
    prime = _entry("units7-bravo-prime-feet").mission.check
    assert prime(CTX, ev({"bravo": _hovering("bravo", 0, -90 * ft, 55 * ft)})).ok
    assert not prime(CTX, ev({"bravo": _hovering("bravo", 0, -90, 55)})).ok

    # an orbit's radius in feet flown in metres
    orbit = _entry("units7-ro-charlie-orbit-feet").mission.check

    def round_home(radius: float) -> list[tuple[float, float]]:
        return [
            (radius, 0),
            (-radius, radius),
            (-radius, -radius),
            (radius, -radius),
            (radius, radius),
            (-radius, 0),
        ]

    assert orbit(CTX, flown("charlie", round_home(60 * ft), 12, home["charlie"])).ok
    assert not orbit(CTX, flown("charlie", round_home(60), 12, home["charlie"])).ok

    # placed in feet from alpha: from charlie itself, or in metres
    east_of_alpha = _entry("units7-tr-charlie-feet-east-of-alpha").mission.check
    assert east_of_alpha(CTX, ev({"charlie": over(CTX.point("alpha", 0, 60 * ft), 45 * ft)})).ok
    assert not east_of_alpha(CTX, ev({"charlie": _hovering("charlie", 0, 60 * ft, 45 * ft)})).ok
    assert not east_of_alpha(CTX, ev({"charlie": over(CTX.point("alpha", 0, 60), 45 * ft)})).ok

    # a heptagon turned left instead of right
    heptagon = _entry("pattern7-no-alpha-heptagon").mission.check
    assert heptagon(CTX, flown("alpha", polygon(7, 12, 90, 360 / 7), 10, home["alpha"])).ok
    assert not heptagon(CTX, flown("alpha", polygon(7, 12, 90, -360 / 7), 10, home["alpha"])).ok

    # the shuttle flown once
    shuttle = _entry("pattern7-sv-bravo-shuttle").mission.check
    assert shuttle(CTX, flown("bravo", [(30, 0), (-30, 0)] * 3, 10, home["bravo"])).ok
    assert not shuttle(CTX, flown("bravo", [(30, 0), (-30, 0)], 10, home["bravo"])).ok

    # passes stepped west instead of east
    passes = _entry("pattern7-pl-charlie-passes-east").mission.check

    def mow(step: float) -> list[tuple[float, float]]:
        return [(-30, 0), (0, step), (30, 0), (0, step), (-30, 0), (0, step), (30, 0), (0, -3 * step)]

    assert passes(CTX, flown("charlie", mow(8), 12, home["charlie"])).ok
    assert not passes(CTX, flown("charlie", mow(-8), 12, home["charlie"])).ok

    # alpha placed from itself instead of under charlie
    below = _entry("place7-da-alpha-below-charlie").mission.check
    charlie_north = _hovering("charlie", 15, 0, 20)
    assert below(CTX, ev({"charlie": charlie_north, "alpha": over(CTX.point("charlie", 15, 0), 12)})).ok
    assert not below(CTX, ev({"charlie": charlie_north, "alpha": _hovering("alpha", 15, 0, 12)})).ok

    # alpha placed north of where charlie took off instead of where charlie went
    chain = _entry("place7-fi-chain-west-then-north").mission.check
    charlie_west = over(CTX.point("alpha", 0, -20), 14)
    assert chain(CTX, ev({"charlie": charlie_west, "alpha": over(CTX.point("alpha", 20, -20), 14)})).ok
    assert not chain(CTX, ev({"charlie": charlie_west, "alpha": over(CTX.point("charlie", 20, 0), 14)})).ok

    # each drone over its own pad instead of the other's
    swap = _entry("place7-pt-swap-pads").mission.check
    assert swap(
        CTX,
        ev({"alpha": over(CTX.point("charlie", 0, 0), 12), "charlie": over(CTX.point("alpha", 0, 0), 16)}),
    ).ok
    assert not swap(
        CTX, ev({"alpha": _hovering("alpha", 0, 0, 12), "charlie": _hovering("charlie", 0, 0, 16)})
    ).ok

    # the landing at the end dropped, the hover turned into a landing, the return left out
    d35 = 35 / math.sqrt(2)
    southwest = _entry("lang7-hu-charlie-southwest-land").mission.check
    assert southwest(
        CTX, flown("charlie", [(-d35, -d35)], 11, landed_at(CTX.point("charlie", -d35, -d35)))
    ).ok
    assert not southwest(CTX, ev({"charlie": _hovering("charlie", -d35, -d35, 11)})).ok
    hover = _entry("lang7-hr-bravo-north-hover").mission.check
    assert hover(CTX, ev({"bravo": _hovering("bravo", 20, 0, 19)})).ok
    assert not hover(CTX, flown("bravo", [(20, 0)], 19, landed_at(CTX.point("bravo", 20, 0)))).ok
    east_home = _entry("lang7-sk-alpha-east-home").mission.check
    assert east_home(CTX, flown("alpha", [(0, 40), (0, -40)], 9, home["alpha"])).ok
    assert not east_home(CTX, flown("alpha", [(0, 40)], 9, landed_at(CTX.point("alpha", 0, 40)))).ok


def test_a_wrong_outcome_fails_the_nineteenth_test_half_checks() -> None:
    """Each trap the nineteenth test half (now dev, moved in the nineteenth round) set: the right outcome
    passes, the likely wrong one fails."""
    yd = 0.9144
    idle = {d: DroneTruth(*HOMES[d][:2], 0.0, False, 90.0) for d in DRONES}

    def flown(drone: str, legs: list[tuple[float, float]], alt: float, end: DroneTruth) -> Evidence:
        return ev({drone: end}, {drone: [*_track(drone, legs, alt), end]})

    def heights(alts: dict[str, list[float]]) -> Evidence:
        """Each drone over its own pad at the heights given, sampled together; each ends at its last one."""
        track = {d: [over(CTX.point(d, 0, 0), a) for a in hs] for d, hs in alts.items()}
        return ev({d: t[-1] for d, t in track.items()}, track)

    def refused(final: dict[str, DroneTruth], text: str) -> Evidence:
        result = [{"name": "formation_goto", "status": "error", "text": text}]
        truth = {**idle, **final}
        return Evidence(truth, {d: [t] for d, t in truth.items()}, result, "Refused: over the limit.")

    def centre(north: float, east: float) -> tuple[float, float]:
        lat = sum(HOMES[d][0] for d in DRONES) / 3
        lon = sum(HOMES[d][1] for d in DRONES) / 3
        return offset_position(lat, lon, north, east)

    home = {d: landed_at(CTX.point(d, 0, 0)) for d in DRONES}
    d15, d20, d25 = (x / math.sqrt(2) for x in (15, 20, 25))

    # 4 m below the hook, not 4 m above it, and never above it on the way
    hook = _entry("single19-alpha-under-crane-hook").mission.check
    assert hook(CTX, ev({"alpha": _hovering("alpha", 0, 0, 14)})).ok
    assert not hook(CTX, ev({"alpha": _hovering("alpha", 0, 0, 22)})).ok
    assert not hook(CTX, heights({"alpha": [0, 22, 14]})).ok

    # two steps of 8 m down from 24 m, not one, and from 24 m
    steps = _entry("single19-da-bravo-down-in-steps").mission.check
    assert steps(CTX, heights({"bravo": [0, 12, 24, 20, 16, 12, 8]})).ok
    assert not steps(CTX, heights({"bravo": [0, 12, 24, 20, 16]})).ok
    assert not steps(CTX, heights({"bravo": [0, 8]})).ok

    # the tallest of the three trees, not their mean or their sum
    tallest = _entry("single19-el-charlie-tallest-tree").mission.check
    assert tallest(CTX, ev({"charlie": _hovering("charlie", 0, 0, 16)})).ok
    assert not tallest(CTX, ev({"charlie": _hovering("charlie", 0, 0, 11)})).ok
    assert not tallest(CTX, ev({"charlie": _hovering("charlie", 0, 0, 33)})).ok

    # a hand-over: the next one up before the last one lands, in turn; not a gap, not all at once
    hand_over = _entry("multi19-hand-over-in-turn").mission.check
    assert hand_over(
        CTX,
        heights({"alpha": [0, 15, 15, 15, 0, 0, 0], "bravo": [0, 0, 15, 15, 15, 15, 0],
                 "charlie": [0, 0, 0, 0, 15, 15, 15]}),
    ).ok  # fmt: skip
    assert not hand_over(
        CTX,
        heights({"alpha": [0, 15, 0, 0, 0, 0], "bravo": [0, 0, 0, 15, 0, 0], "charlie": [0, 0, 0, 0, 0, 15]}),
    ).ok
    assert not hand_over(
        CTX, heights({"alpha": [0, 15, 15, 0], "bravo": [0, 15, 15, 0], "charlie": [0, 15, 15, 15]})
    ).ok

    # the mirror image of a leg north-west is a leg north-east, not the same leg
    mirror = _entry("multi19-no-charlie-mirrors-alpha").mission.check
    alpha_nw = _hovering("alpha", d15, -d15, 10)
    assert mirror(CTX, ev({"alpha": alpha_nw, "charlie": _hovering("charlie", d15, d15, 10)})).ok
    assert not mirror(CTX, ev({"alpha": alpha_nw, "charlie": _hovering("charlie", d15, -d15, 10)})).ok

    # alpha, bravo, alpha: not alpha twice and then bravo, not alpha once
    turns = _entry("multi19-fi-pair-takes-turns-hopping").mission.check
    assert turns(CTX, heights({"alpha": [0, 6, 0, 0, 0, 6, 0], "bravo": [0, 0, 0, 6, 0, 0, 0]})).ok
    assert not turns(CTX, heights({"alpha": [0, 6, 0, 6, 0, 0, 0], "bravo": [0, 0, 0, 0, 0, 6, 0]})).ok
    assert not turns(CTX, heights({"alpha": [0, 6, 0, 0, 0], "bravo": [0, 0, 0, 6, 0]})).ok

    # the route told backwards flown backwards: it ends north of the pad instead of west of it
    backwards = _entry("compound19-bravo-route-told-backwards").mission.check
    assert backwards(CTX, flown("bravo", [(20, 0), (-20, -10)], 12, landed_at(CTX.point("bravo", 0, -10)))).ok
    assert not backwards(
        CTX, flown("bravo", [(0, -10), (20, 10)], 12, landed_at(CTX.point("bravo", 20, 0)))
    ).ok

    # the posts counted from the pad (the third at 16 m, the fifth at 32 m) instead of from the first post
    posts = _entry("compound19-hu-alpha-marker-posts").mission.check
    on_to_fifth = [_hovering("alpha", n, 0, 5) for n in range(24, 41)]
    assert posts(
        CTX,
        ev({"alpha": landed_at(CTX.point("alpha", 40, 0))},
           {"alpha": [*_track("alpha", [(24, 0)], 10), *on_to_fifth, landed_at(CTX.point("alpha", 40, 0))]}),
    ).ok  # fmt: skip
    short = [*_track("alpha", [(16, 0)], 10), *(_hovering("alpha", n, 0, 5) for n in range(16, 33))]
    assert not posts(
        CTX,
        ev(
            {"alpha": landed_at(CTX.point("alpha", 32, 0))},
            {"alpha": [*short, landed_at(CTX.point("alpha", 32, 0))]},
        ),
    ).ok

    # straight back (due south), not back along the zigzag
    zigzag = _entry("compound19-bg-charlie-zigzag-straight-back").mission.check
    assert zigzag(CTX, flown("charlie", [(d20, d20), (d20, -d20), (-2 * d20, 0)], 12, home["charlie"])).ok
    assert not zigzag(
        CTX, flown("charlie", [(d20, d20), (d20, -d20), (-d20, d20), (-d20, -d20)], 12, home["charlie"])
    ).ok

    # the lead over bravo (25 points), not charlie's charge
    lead = _entry("cond19-charlie-north-by-its-lead").mission.check
    assert lead(CTX, ev({"charlie": _hovering("charlie", 25, 0, 10)})).ok
    assert not lead(CTX, ev({"charlie": _hovering("charlie", 78, 0, 10)})).ok

    # the middle charge (charlie), not the fullest (alpha)
    middle = _entry("cond19-sk-middle-charge-flies").mission.check
    assert middle(CTX, ev({"charlie": _hovering("charlie", -20, 0, 12)})).ok
    assert not middle(CTX, ev({"alpha": _hovering("alpha", -20, 0, 12)})).ok

    # the low one went up with the others before it landed again
    low_lands = _entry("cond19-ca-all-up-low-ones-land").mission.check
    north = {d: _hovering(d, 20, 0, 10) for d in ("alpha", "charlie")}
    hop = [_hovering("bravo", 0, 0, 10), home["bravo"]]
    assert low_lands(
        CTX, ev({**north, "bravo": home["bravo"]}, {**{d: [t] for d, t in north.items()}, "bravo": hop})
    ).ok
    assert not low_lands(CTX, ev(north)).ok

    # neighbours as far apart as the row is high (12 m), not 10 m
    by_height = _entry("form19-row-spaced-by-height").mission.check
    assert by_height(
        CTX, ev({d: over(centre(0, e), 12) for d, e in zip(DRONES, (-12, 0, 12), strict=True)})
    ).ok
    assert not by_height(
        CTX, ev({d: over(centre(0, e), 12) for d, e in zip(DRONES, (-10, 0, 10), strict=True)})
    ).ok

    # charlie at the west end and alpha at the east end, not the drones in the order of their pads
    reverse = _entry("form19-th-row-in-reverse-order").mission.check
    assert reverse(CTX, ev({d: over(centre(0, e), 14) for d, e in zip(DRONES, (10, 0, -10), strict=True)})).ok
    assert not reverse(
        CTX, ev({d: over(centre(0, e), 14) for d, e in zip(DRONES, (-10, 0, 10), strict=True)})
    ).ok

    # bravo at the tip of the V, alpha on its west wing: not alpha leading, not a row
    arm = 10 / math.sqrt(2)
    tip, west, east = (2 * arm / 3, 0.0), (-arm / 3, -arm), (-arm / 3, arm)
    v_shape = _entry("form19-ms-v-with-bravo-leading").mission.check
    assert v_shape(
        CTX, ev({d: over(centre(*p), 15) for d, p in (("bravo", tip), ("alpha", west), ("charlie", east))})
    ).ok
    assert not v_shape(
        CTX, ev({d: over(centre(*p), 15) for d, p in (("alpha", tip), ("bravo", west), ("charlie", east))})
    ).ok
    assert not v_shape(
        CTX, ev({d: over(centre(0, e), 15) for d, e in zip(DRONES, (-10, 0, 10), strict=True)})
    ).ok

    # a quarter turn clockwise from north ends east of the pad, not west
    quarter = _entry("rel19-alpha-quarter-turn-round-pad").mission.check
    out = _track("alpha", [(20, 0)], 12)
    assert quarter(
        CTX, ev({"alpha": _hovering("alpha", 0, 20, 12)}, {"alpha": [*out, _hovering("alpha", 0, 20, 12)]})
    ).ok
    assert not quarter(
        CTX, ev({"alpha": _hovering("alpha", 0, -20, 12)}, {"alpha": [*out, _hovering("alpha", 0, -20, 12)]})
    ).ok

    # squares of 10 m, not metres
    grid = _entry("rel19-tl-bravo-grid-squares").mission.check
    assert grid(CTX, ev({"bravo": _hovering("bravo", 30, -20, 12)})).ok
    assert not grid(CTX, ev({"bravo": _hovering("bravo", 3, -2, 12)})).ok

    # the pad to its south-west puts the drone north-east of the pad, not south-west of it
    back_bearing = _entry("rel19-sw-charlie-pad-to-its-southwest").mission.check
    assert back_bearing(CTX, ev({"charlie": _hovering("charlie", d25, d25, 12)})).ok
    assert not back_bearing(CTX, ev({"charlie": _hovering("charlie", -d25, -d25, 12)})).ok

    # questions: the drone that runs out first is not the one with least charge; the midpoint's readings;
    # the total above the reserve, not the total charge
    first_out = _entry("ask19-first-to-run-out").mission.check
    assert first_out(CTX, ev({}, text="Charlie: 66 % at 3 % a minute lasts 22 minutes.")).ok
    assert not first_out(CTX, ev({}, text="Bravo, with 50 %.")).ok
    midpoint = _entry("ask19-ur-bravo-against-midpoint").mission.check
    assert midpoint(CTX, ev({}, text="alpha 40 %, bravo 66 %, charlie 80 %")).ok
    assert not midpoint(CTX, ev({}, text="bravo 66 %")).ok
    reserve = _entry("ask19-bn-total-above-reserve").mission.check
    assert reserve(CTX, ev({}, text="77 %")).ok
    assert not reserve(CTX, ev({}, text="167 %")).ok

    # the tight row refused by the separation rule, not flown 3 m apart drone by drone
    tight = _entry("refuse19-row-too-tight").mission.check
    sep = "min_separation: formation spacing 3 m is below the minimum separation of 5 m"
    assert tight(CTX, refused({}, sep)).ok
    close = {d: [over(centre(0, e), 15)] for d, e in zip(DRONES, (-3, 0, 3), strict=True)}
    assert not tight(
        CTX, Evidence({d: t[0] for d, t in close.items()}, close, [], "The three are in a row 3 m apart.")
    ).ok
    assert not tight(
        CTX, Evidence({d: t[0] for d, t in close.items()}, close, refused({}, sep).tool_results, "Refused.")
    ).ok

    # 4 m/s for 40 s is 160 m: refused, not flown to some lower height
    climb_rate = _entry("refuse19-af-bravo-climb-rate-over-ceiling").mission.check
    assert climb_rate(
        CTX, refused({}, "max_altitude: target altitude 160 m exceeds the limit of 120 m above home")
    ).ok
    assert not climb_rate(CTX, ev({"bravo": _hovering("bravo", 0, 0, 40)}, text="bravo is at 40 m.")).ok

    # 800 m north and 700 m east is 1063 m from home: refused, not the leg north alone
    diagonal = _entry("refuse19-et-alpha-diagonal-past-limit").mission.check
    assert diagonal(
        CTX,
        refused(
            {"alpha": _hovering("alpha", 0, 0, 20)}, "max_distance: 1063 m from home is beyond the limit"
        ),
    ).ok
    assert not diagonal(CTX, flown("alpha", [(800, 0)], 20, _hovering("alpha", 800, 0, 20))).ok

    # chains of 22 yards (100.6 m), not 110 m; paces of 75 cm, not metres; millimetres, not centimetres
    chains = _entry("units19-alpha-chains").mission.check
    assert chains(CTX, ev({"alpha": _hovering("alpha", 0, 110 * yd, 10)})).ok
    assert not chains(CTX, ev({"alpha": _hovering("alpha", 0, 110, 10)})).ok
    paces = _entry("units19-lt-bravo-paces").mission.check
    assert paces(CTX, flown("bravo", [(-30, 0)], 12, landed_at(CTX.point("bravo", -30, 0)))).ok
    assert not paces(CTX, flown("bravo", [(-40, 0)], 12, landed_at(CTX.point("bravo", -40, 0)))).ok
    millimetres = _entry("units19-ky-charlie-millimetres").mission.check
    assert millimetres(CTX, ev({"charlie": _hovering("charlie", 0, -25, 15)})).ok
    assert not millimetres(CTX, ev({"charlie": _hovering("charlie", 0, -250, 15)})).ok

    # the sawtooth flown, not a level leg of 60 m
    saw = _entry("pattern19-charlie-sawtooth-profile").mission.check
    teeth = [_hovering("charlie", 0, e, 10 + 6 * (1 - abs(e % 20 - 10) / 10)) for e in range(61)]
    end = landed_at(CTX.point("charlie", 0, 60))
    assert saw(CTX, ev({"charlie": end}, {"charlie": [*teeth, end]})).ok
    assert not saw(CTX, flown("charlie", [(0, 60)], 10, end)).ok

    # the rectangle the diagonal gives (30 by 40 m), not a square on its first side
    rectangle = _entry("pattern19-sr-bravo-rectangle-by-diagonal").mission.check
    assert rectangle(CTX, flown("bravo", [(30, 0), (0, 40), (-30, 0), (0, -40)], 12, home["bravo"])).ok
    assert not rectangle(CTX, flown("bravo", [(30, 0), (0, 30), (-30, 0), (0, -30)], 12, home["bravo"])).ok

    # sides of 10 m (60 m round), not of 60 m, and turning right
    def hexagon(side: float, turn: float) -> list[tuple[float, float]]:
        bearings = [math.radians(90 + i * turn) for i in range(6)]
        return [(side * math.cos(b), side * math.sin(b)) for b in bearings]

    perimeter = _entry("pattern19-sl-alpha-hexagon-by-perimeter").mission.check
    assert perimeter(CTX, flown("alpha", hexagon(10, 60), 10, home["alpha"])).ok
    assert not perimeter(CTX, flown("alpha", hexagon(60, 60), 10, home["alpha"])).ok
    assert not perimeter(CTX, flown("alpha", hexagon(10, -60), 10, home["alpha"])).ok

    # charlie 10 m from alpha towards bravo, not 10 m from bravo towards alpha
    between = _entry("place19-charlie-between-ten-from-alpha").mission.check
    alpha_south, bravo_north = CTX.point("alpha", -10, 0), CTX.point("bravo", 30, 0)
    dn, de = (bravo_north[0] - alpha_south[0], bravo_north[1] - alpha_south[1])
    length = math.hypot(*ned_offset(*alpha_south, *bravo_north))
    pair = {"alpha": over(alpha_south, 15), "bravo": over(bravo_north, 15)}
    near_alpha = (alpha_south[0] + dn * 10 / length, alpha_south[1] + de * 10 / length)
    near_bravo = (bravo_north[0] - dn * 10 / length, bravo_north[1] - de * 10 / length)
    assert between(CTX, ev({**pair, "charlie": over(near_alpha, 15)})).ok
    assert not between(CTX, ev({**pair, "charlie": over(near_bravo, 15)})).ok

    # where alpha was before its last leg, not where it is, nor that far from charlie's own pad
    was = _entry("place19-jv-charlie-where-alpha-was").mission.check
    alpha_now = over(CTX.point("alpha", 20, 15), 12)
    assert was(CTX, ev({"alpha": alpha_now, "charlie": over(CTX.point("alpha", 20, 0), 12)})).ok
    assert not was(CTX, ev({"alpha": alpha_now, "charlie": over(CTX.point("alpha", 20, 15), 12)})).ok
    assert not was(CTX, ev({"alpha": alpha_now, "charlie": _hovering("charlie", 20, 0, 12)})).ok

    # as far west of alpha as alpha is high (12 m), not as far as it flew (25 m)
    by_alpha_height = _entry("place19-ceb-charlie-west-by-alpha-height").mission.check
    alpha_north = over(CTX.point("alpha", 25, 0), 12)
    assert by_alpha_height(
        CTX, ev({"alpha": alpha_north, "charlie": over(CTX.point("alpha", 25, -12), 12)})
    ).ok
    assert not by_alpha_height(
        CTX, ev({"alpha": alpha_north, "charlie": over(CTX.point("alpha", 25, -25), 12)})
    ).ok

    # the landing at the end dropped, the second leg dropped, the return left out
    khmer = _entry("lang19-km-alpha-east-land").mission.check
    assert khmer(CTX, flown("alpha", [(0, 20)], 15, landed_at(CTX.point("alpha", 0, 20)))).ok
    assert not khmer(CTX, ev({"alpha": _hovering("alpha", 0, 20, 15)})).ok
    lao = _entry("lang19-lo-charlie-north-west-hover").mission.check
    assert lao(CTX, flown("charlie", [(25, 0), (0, -10)], 12, _hovering("charlie", 25, -10, 12))).ok
    assert not lao(CTX, flown("charlie", [(25, 0)], 12, _hovering("charlie", 25, 0, 12))).ok
    zulu = _entry("lang19-zu-bravo-south-home").mission.check
    assert zulu(CTX, flown("bravo", [(-30, 0), (30, 0)], 10, home["bravo"])).ok
    assert not zulu(CTX, flown("bravo", [(-30, 0)], 10, landed_at(CTX.point("bravo", -30, 0)))).ok


def test_a_wrong_outcome_fails_the_twentieth_test_half_checks() -> None:
    """Each trap the twentieth test half (now dev, moved in the twentieth round) set: the right outcome
    passes, the likely wrong one fails (its entries read from ``corpus()`` by their ids' "20-")."""
    entries = {e.id: e for e in corpus() if re.match(r"[a-z]+20-", e.id)}
    assert len(entries) == 36 and Counter(e.cls for e in entries.values()) == Counter(
        dict.fromkeys(CLASSES, 3)
    )
    assert all(e.half == "dev" for e in entries.values())
    ft, yd = 0.3048, 0.9144
    idle = {d: DroneTruth(*HOMES[d][:2], 0.0, False, 90.0) for d in DRONES}

    def check(mid: str) -> Callable[[Evidence], bool]:
        """The entry's check, bound to the test homes."""
        return lambda evidence: entries[mid].mission.check(CTX, evidence).ok

    def flown(drone: str, legs: list[tuple[float, float]], alt: float, end: DroneTruth) -> Evidence:
        return ev({drone: end}, {drone: [*_track(drone, legs, alt), end]})

    def heights(alts: dict[str, list[float]]) -> Evidence:
        """Each drone over its own pad at the heights given, sampled together; each ends at its last one."""
        track = {d: [over(CTX.point(d, 0, 0), a) for a in hs] for d, hs in alts.items()}
        return ev({d: t[-1] for d, t in track.items()}, track)

    def refused(
        final: dict[str, DroneTruth], text: str, answer: str = "Refused: over the limit."
    ) -> Evidence:
        result = [{"name": "move_to_relative", "status": "error", "text": text}]
        truth = {**idle, **final}
        return Evidence(truth, {d: [t] for d, t in truth.items()}, result, answer)

    def centre(north: float, east: float) -> tuple[float, float]:
        lat = sum(HOMES[d][0] for d in DRONES) / 3
        lon = sum(HOMES[d][1] for d in DRONES) / 3
        return offset_position(lat, lon, north, east)

    home = {d: landed_at(CTX.point(d, 0, 0)) for d in DRONES}
    d30 = 30 / math.sqrt(2)

    # a quarter of the way down a 40 m mast is 30 m, not 10 m, not the top
    mast = check("single20-bravo-level-with-mast-light")
    assert mast(ev({"bravo": _hovering("bravo", 0, 0, 30)}))
    assert not mast(ev({"bravo": _hovering("bravo", 0, 0, 10)}))
    assert not mast(ev({"bravo": _hovering("bravo", 0, 0, 40)}))

    # twice 7 m is 14 m, not 2 m more
    twice = check("single20-fi-alpha-twice-as-high")
    assert twice(heights({"alpha": [0, 7, 10, 14]}))
    assert not twice(heights({"alpha": [0, 7, 9]}))
    assert not twice(heights({"alpha": [0, 7]}))

    # two hops, back on the pad each time: not one, and not left up after the second
    hops = check("single20-ur-charlie-two-hops")
    assert hops(heights({"charlie": [0, 10, 0, 10, 0]}))
    assert not hops(heights({"charlie": [0, 10, 0]}))
    assert not hops(heights({"charlie": [0, 10, 0, 10]}))

    # each over the other's pad at its own height; not back over its own, not with the heights swapped
    swap = check("multi20-alpha-charlie-swap-pads")
    pads = {d: CTX.point(d, 0, 0) for d in DRONES}
    assert swap(ev({"alpha": over(pads["charlie"], 10), "charlie": over(pads["alpha"], 15)}))
    assert not swap(ev({"alpha": over(pads["alpha"], 10), "charlie": over(pads["charlie"], 15)}))
    assert not swap(ev({"alpha": over(pads["charlie"], 15), "charlie": over(pads["alpha"], 10)}))

    # bravo went up with the others and landed again; not left hovering, not never up
    spread = check("multi20-hu-spread-bravo-back-down")
    sides = {"alpha": _hovering("alpha", 0, -15, 12), "charlie": _hovering("charlie", 0, 15, 12)}
    bravo_hop = [over(pads["bravo"], 12), home["bravo"]]
    assert spread(
        ev({**sides, "bravo": home["bravo"]}, {**{d: [t] for d, t in sides.items()}, "bravo": bravo_hop})
    )
    assert not spread(ev({**sides, "bravo": over(pads["bravo"], 12)}))
    assert not spread(ev(sides))

    # alpha lands out there, bravo back on its pad; not both out there
    pair = check("multi20-th-pair-north-one-returns")
    alpha_out = landed_at(CTX.point("alpha", 20, 0))
    alpha_track = [*_track("alpha", [(20, 0)], 10), alpha_out]
    bravo_back = [*_track("bravo", [(20, 0), (-20, 0)], 10), home["bravo"]]
    assert pair(ev({"alpha": alpha_out, "bravo": home["bravo"]}, {"alpha": alpha_track, "bravo": bravo_back}))
    bravo_out = landed_at(CTX.point("bravo", 20, 0))
    assert not pair(
        ev({"alpha": alpha_out, "bravo": bravo_out},
           {"alpha": alpha_track, "bravo": [*_track("bravo", [(20, 0)], 10), bravo_out]}),
    )  # fmt: skip

    # a landing at the first sensor on the way out; not straight to the second, not on the way back
    sensors = check("compound20-bravo-lands-at-first-sensor")
    first = landed_at(CTX.point("bravo", 20, 0))
    on = [_hovering("bravo", n, 0, 10) for n in range(20, 41)]
    assert sensors(ev({"bravo": on[-1]}, {"bravo": [*_track("bravo", [(20, 0)], 10), first, *on]}))
    assert not sensors(flown("bravo", [(40, 0)], 10, on[-1]))
    back = [*_track("bravo", [(40, 0), (-20, 0)], 10), first, *on]
    assert not sensors(ev({"bravo": on[-1]}, {"bravo": back}))

    # the climb to 25 m out west before the leg south; not the leg south at 10 m
    climb = check("compound20-sk-alpha-west-climb-south-land")
    end = landed_at(CTX.point("alpha", -20, -20))
    up = [_hovering("alpha", 0, -20, a) for a in (15, 20, 25)]
    south = [_hovering("alpha", -n, -20, 25) for n in range(21)]
    assert climb(ev({"alpha": end}, {"alpha": [*_track("alpha", [(0, -20)], 10), *up, *south, end]}))
    assert not climb(flown("alpha", [(0, -20), (-20, 0)], 10, end))

    # half the way back (15 m south of the pad), not all the way, not where it turned
    half_back = check("compound20-sw-charlie-half-way-back")
    assert half_back(flown("charlie", [(-30, 0), (15, 0)], 12, landed_at(CTX.point("charlie", -15, 0))))
    assert not half_back(flown("charlie", [(-30, 0), (30, 0)], 12, home["charlie"]))
    assert not half_back(flown("charlie", [(-30, 0)], 12, landed_at(CTX.point("charlie", -30, 0))))

    # alpha is ahead, but by 14 points, not 20: charlie flies
    lead = check("cond20-alpha-lead-of-twenty-or-charlie")
    assert lead(ev({"charlie": _hovering("charlie", 0, 25, 10)}))
    assert not lead(ev({"alpha": _hovering("alpha", 0, 25, 10)}))

    # those with 60 % or more (alpha, charlie); not all three, not bravo
    sixty = check("cond20-da-sixty-percent-fly-north")
    north = {d: _hovering(d, 20, 0, 15) for d in DRONES}
    assert sixty(ev({d: north[d] for d in ("alpha", "charlie")}))
    assert not sixty(ev(north))
    assert not sixty(ev({d: north[d] for d in ("alpha", "bravo")}))

    # bravo is under 50 %: alpha does the job; not bravo
    either = check("cond20-ky-bravo-or-alpha-south-land")
    assert either(flown("alpha", [(-20, 0)], 10, landed_at(CTX.point("alpha", -20, 0))))
    assert not either(flown("bravo", [(-20, 0)], 10, landed_at(CTX.point("bravo", -20, 0))))

    # a north-south column 30 m west; not a row east-west there (the way it travelled), not over the pads
    column = check("form20-column-west")
    assert column(ev({d: over(centre(n, -30), 20) for d, n in zip(DRONES, (8, 0, -8), strict=True)}))
    assert not column(ev({d: over(centre(0, e - 30), 20) for d, e in zip(DRONES, (-8, 0, 8), strict=True)}))
    assert not column(ev({d: over(centre(n, 0), 20) for d, n in zip(DRONES, (8, 0, -8), strict=True)}))

    # an equilateral triangle of 12 m sides 20 m south; not a row 12 m apart, not over the pads
    r = 12 / math.sqrt(3)
    ring = [(r, 0.0), (-r / 2, 6.0), (-r / 2, -6.0)]
    triangle = check("form20-ca-triangle-south")
    assert triangle(ev({d: over(centre(n - 20, e), 15) for d, (n, e) in zip(DRONES, ring, strict=True)}))
    assert not triangle(ev({d: over(centre(-20, e), 15) for d, e in zip(DRONES, (-12, 0, 12), strict=True)}))
    assert not triangle(ev({d: over(centre(n, e), 15) for d, (n, e) in zip(DRONES, ring, strict=True)}))

    # the row centred over charlie's pad, east-west; not over the pads' centre, not north-south
    row = check("form20-sr-row-over-charlie-pad")
    assert row(
        ev(
            {
                d: over(offset_position(*pads["charlie"], 0, e), 10)
                for d, e in zip(DRONES, (-6, 0, 6), strict=True)
            }
        )
    )
    assert not row(ev({d: over(centre(0, e), 10) for d, e in zip(DRONES, (-6, 0, 6), strict=True)}))
    assert not row(
        ev(
            {
                d: over(offset_position(*pads["charlie"], n, 0), 10)
                for d, n in zip(DRONES, (-6, 0, 6), strict=True)
            }
        )
    )

    # two steps up as well as north (18 m at the top); not level, not one step
    stairs = check("rel20-bravo-staircase-north")
    slope = [_hovering("bravo", n, 0, 8 + 5 * n / 12) for n in range(25)]
    assert stairs(ev({"bravo": slope[-1]}, {"bravo": slope}))
    assert not stairs(flown("bravo", [(24, 0)], 8, _hovering("bravo", 24, 0, 8)))
    assert not stairs(flown("bravo", [(24, 0)], 8, _hovering("bravo", 24, 0, 13)))

    # back a quarter of 40 m (10 m), not back to a quarter of the way out, not left at the far end
    quarter = check("rel20-el-alpha-quarter-back")
    assert quarter(flown("alpha", [(-40, 0), (10, 0)], 12, _hovering("alpha", -30, 0, 12)))
    assert not quarter(flown("alpha", [(-40, 0), (30, 0)], 12, _hovering("alpha", -10, 0, 12)))
    assert not quarter(flown("alpha", [(-40, 0)], 12, _hovering("alpha", -40, 0, 12)))

    # south-east and then 10 m higher; not north-east, not left at 10 m
    southeast = check("rel20-lt-charlie-southeast-climb")
    assert southeast(flown("charlie", [(-d30, d30)], 10, _hovering("charlie", -d30, d30, 20)))
    assert not southeast(flown("charlie", [(d30, d30)], 10, _hovering("charlie", d30, d30, 20)))
    assert not southeast(flown("charlie", [(-d30, d30)], 10, _hovering("charlie", -d30, d30, 10)))

    # questions: the fullest against the emptiest (not the next one); the lead over the second, not the
    # last; missions while 30 % stays, not the charge over 15 %
    spread_q = check("ask20-spread-fullest-emptiest")
    assert spread_q(ev({}, text="36 points: alpha has 83 %, bravo 47 %."))
    assert spread_q(ev({}, text="alpha 83 %, bravo 47 %, charlie 65 %"))
    assert not spread_q(ev({}, text="18 points, between alpha and charlie."))
    second = check("ask20-bg-lead-over-second")
    assert second(ev({}, text="bravo: 91 %, с 14 пункта пред charlie (77 %)"))
    assert not second(ev({}, text="bravo: 91 %, с 33 пункта пред alpha (58 %)"))
    missions = check("ask20-jv-charlie-missions-left")
    assert missions(ev({}, text="Ping 3: charlie saiki 78 %."))
    assert not missions(ev({}, text="Ping 5."))
    assert not missions(heights({"charlie": [0, 5]}))

    # the low battery refused and reported; not flown, not refused and called done
    low = check("refuse20-charlie-low-battery")
    no_battery = "battery: charlie has 24 %, below the 30 % needed to take off"
    assert low(refused({}, no_battery))
    assert not low(ev({"charlie": _hovering("charlie", 50, 0, 10)}, text="Charlie is over the gate."))
    assert not low(refused({}, no_battery, answer="Done."))

    # the first 600 m flown, the second leg refused; not the whole flight refused, not flown on
    fence = check("refuse20-ms-bravo-second-leg-too-far")
    too_far = "max_distance: 1200 m from home is beyond the limit of 1000 m"
    assert fence(refused({"bravo": _hovering("bravo", 0, -600, 30)}, too_far))
    assert not fence(refused({"bravo": _hovering("bravo", 0, 0, 30)}, too_far))
    assert not fence(flown("bravo", [(0, -1200)], 30, _hovering("bravo", 0, -1200, 30)))

    # 9 m down from 10 m is 1 m: refused; not flown down, not clamped to 2 m without a word
    truck = check("refuse20-ceb-alpha-down-to-one-metre")
    assert truck(
        refused({"alpha": _hovering("alpha", 0, 0, 10)}, "min_altitude: 1 m is below the minimum of 2 m")
    )
    assert not truck(ev({"alpha": _hovering("alpha", 0, 0, 1)}, text="alpha is at 1 m."))
    assert not truck(ev({"alpha": _hovering("alpha", 0, 0, 2)}, text="alpha is at 2 m."))

    # yards and feet, not metres; cm and km, not m
    yards = check("units20-alpha-feet-yards")
    assert yards(flown("alpha", [(0, -250 * yd)], 35 * ft, _hovering("alpha", 0, -250 * yd, 20 * ft)))
    assert not yards(flown("alpha", [(0, -250)], 35 * ft, _hovering("alpha", 0, -250, 20 * ft)))
    assert not yards(flown("alpha", [(0, -250 * yd)], 35 * ft, _hovering("alpha", 0, -250 * yd, 20)))
    feet_km = check("units20-no-charlie-feet-km")
    assert feet_km(flown("charlie", [(200, 0)], 40 * ft, landed_at(CTX.point("charlie", 200, 0))))
    assert not feet_km(flown("charlie", [(200, 0)], 40, landed_at(CTX.point("charlie", 200, 0))))
    assert not feet_km(flown("charlie", [(20, 0)], 40 * ft, landed_at(CTX.point("charlie", 20, 0))))
    cm_km = check("units20-et-bravo-cm-km")
    assert cm_km(ev({"bravo": _hovering("bravo", 0, -40, 15)}))
    assert not cm_km(ev({"bravo": _hovering("bravo", 0, -4, 15)}))

    # the passes stepping east, not west; the square turning left, not right; the triangle turning right
    mow = check("pattern20-alpha-mow-north")
    east_steps = [(40, 0), (0, 10), (-40, 0), (0, 10), (40, 0)]
    assert mow(flown("alpha", east_steps, 15, landed_at(CTX.point("alpha", 40, 20))))
    west_steps = [(n, -e) for n, e in east_steps]
    assert not mow(flown("alpha", west_steps, 15, landed_at(CTX.point("alpha", 40, -20))))
    square = check("pattern20-bn-charlie-square-left")
    assert square(flown("charlie", [(0, -20), (-20, 0), (0, 20), (20, 0)], 10, home["charlie"]))
    assert not square(flown("charlie", [(0, -20), (20, 0), (0, 20), (-20, 0)], 10, home["charlie"]))
    side = 20 * math.sqrt(3) / 2
    tri = check("pattern20-tl-bravo-triangle-right")
    assert tri(flown("bravo", [(20, 0), (-10, side), (-10, -side)], 12, home["bravo"]))
    assert not tri(flown("bravo", [(20, 0), (-10, -side), (-10, side)], 12, home["bravo"]))

    # placements from alpha, not from charlie's own pad
    lower = check("place20-charlie-north-lower-than-alpha")
    alpha_up = over(pads["alpha"], 20)
    assert lower(ev({"alpha": alpha_up, "charlie": over(CTX.point("alpha", 15, 0), 12)}))
    assert not lower(ev({"alpha": alpha_up, "charlie": _hovering("charlie", 15, 0, 12)}))
    assert not lower(ev({"alpha": alpha_up, "charlie": over(CTX.point("alpha", 15, 0), 8)}))
    east_of = check("place20-af-charlie-east-of-alpha")
    alpha_south = _hovering("alpha", -20, 0, 12)
    assert east_of(ev({"alpha": alpha_south, "charlie": over(CTX.point("alpha", -20, 10), 12)}))
    assert not east_of(ev({"alpha": alpha_south, "charlie": _hovering("charlie", -20, 10, 12)}))
    assert not east_of(ev({"alpha": alpha_south, "charlie": over(CTX.point("alpha", 0, 10), 12)}))
    above = check("place20-sl-charlie-over-alpha-pad-above-bravo")
    bravo_west = _hovering("bravo", 0, -20, 15)
    assert above(ev({"bravo": bravo_west, "charlie": over(pads["alpha"], 20)}))
    assert not above(ev({"bravo": bravo_west, "charlie": over(pads["charlie"], 20)}))
    assert not above(ev({"bravo": bravo_west, "charlie": over(pads["alpha"], 15)}))

    # the language class: west, not east; the second leg east, not west; the landing at the end
    burmese = check("lang20-my-alpha-west-land")
    assert burmese(flown("alpha", [(0, -25)], 10, landed_at(CTX.point("alpha", 0, -25))))
    assert not burmese(flown("alpha", [(0, 25)], 10, landed_at(CTX.point("alpha", 0, 25))))
    yoruba = check("lang20-yo-bravo-north-east-hover")
    assert yoruba(flown("bravo", [(20, 0), (0, 10)], 15, _hovering("bravo", 20, 10, 15)))
    assert not yoruba(flown("bravo", [(20, 0), (0, -10)], 15, _hovering("bravo", 20, -10, 15)))
    somali = check("lang20-so-charlie-east-north-land")
    assert somali(flown("charlie", [(0, 20), (20, 0)], 12, landed_at(CTX.point("charlie", 20, 20))))
    assert not somali(flown("charlie", [(0, 20), (20, 0)], 12, _hovering("charlie", 20, 20, 12)))


def test_the_twenty_first_test_half_is_well_formed() -> None:
    """The twenty-first test half (read from ``corpus()`` by its ids' "21-": the whole test half, nothing
    else): 3 a class, its ids and requests new to the rest of the corpus, none worded as a tool, each with a
    plan, and none of its checks passed by a fleet that did nothing; 22 of the 33 outside ``language`` and
    all of that class's 3 in other languages than English."""
    everything = corpus()
    half = [e for e in everything if re.match(r"[a-z]+21-", e.id)]
    known = [e for e in everything if not re.match(r"[a-z]+21-", e.id)]  # the corpus without the half
    ids = [e.id for e in half]
    assert len(half) == 36 and len(set(ids)) == 36
    assert ids == [e.id for e in select("test")]
    assert Counter(e.cls for e in half) == Counter(dict.fromkeys(CLASSES, 3))
    assert all(e.half == "test" for e in half)
    assert not set(ids) & {e.id for e in known}
    requests = [e.mission.prompt(CTX) for e in half]
    assert len(set(requests)) == 36 and not set(requests) & {e.mission.prompt(CTX) for e in known}
    tool_words = ("move_to_relative", "formation_goto", "go_to_location", "return_to_launch", "_m", "alt_m")
    nothing = Evidence(IDLE, {d: [t] for d, t in IDLE.items()}, [], "Done.")
    for e, request in zip(half, requests, strict=True):
        assert set(e.mission.drones) <= set(DRONES), e.id
        assert _sentence_length(request) >= 4 and not any(w in request for w in tool_words), e.id
        assert e.mission.plan(CTX) and set(e.mission.battery_pct) <= set(e.mission.drones), e.id
        assert not e.mission.check(CTX, nothing).ok, e.id
    english = re.compile(r"\b(the|to|and|up|at|of|is|then|with|any)\b", re.IGNORECASE)
    others = [e for e, r in zip(half, requests, strict=True) if e.cls != "language" and not english.search(r)]
    assert len(others) == 22 and {e.cls for e in others} == set(CLASSES) - {"language"}
    assert not any(english.search(r) for e, r in zip(half, requests, strict=True) if e.cls == "language")


def test_a_wrong_outcome_fails_the_twenty_first_test_half_checks() -> None:
    """Each trap the twenty-first test half sets: the right outcome passes, the likely wrong one fails (its
    entries read from ``corpus()`` by their ids' "21-": the whole test half)."""
    entries = {e.id: e for e in corpus() if re.match(r"[a-z]+21-", e.id)}
    assert len(entries) == 36 and Counter(e.cls for e in entries.values()) == Counter(
        dict.fromkeys(CLASSES, 3)
    )
    assert all(e.half == "test" for e in entries.values())
    assert set(entries) == {e.id for e in select("test")}
    ft, yd = 0.3048, 0.9144
    idle = {d: DroneTruth(*HOMES[d][:2], 0.0, False, 90.0) for d in DRONES}

    def check(mid: str) -> Callable[[Evidence], bool]:
        """The entry's check, bound to the test homes."""
        return lambda evidence: entries[mid].mission.check(CTX, evidence).ok

    def flown(drone: str, legs: list[tuple[float, float]], alt: float, end: DroneTruth) -> Evidence:
        return ev({drone: end}, {drone: [*_track(drone, legs, alt), end]})

    def heights(alts: dict[str, list[float]]) -> Evidence:
        """Each drone over its own pad at the heights given, sampled together; each ends at its last one."""
        track = {d: [over(CTX.point(d, 0, 0), a) for a in hs] for d, hs in alts.items()}
        return ev({d: t[-1] for d, t in track.items()}, track)

    def along(stops: list[tuple[float, float]], alt: float) -> list[DroneTruth]:
        """Samples about every metre on the straight lines between ``stops`` (lat, lon), at ``alt``."""
        out = []
        for a, b in itertools.pairwise(stops):
            steps = max(1, int(math.hypot(*ned_offset(*a, *b))))
            out += [over((a[0] + (b[0] - a[0]) * i / steps, a[1] + (b[1] - a[1]) * i / steps), alt)
                    for i in range(steps + 1)]  # fmt: skip
        return out

    def refused(
        final: dict[str, DroneTruth], text: str, answer: str = "Refused: over the limit."
    ) -> Evidence:
        result = [{"name": "move_to_relative", "status": "error", "text": text}]
        truth = {**idle, **final}
        return Evidence(truth, {d: [t] for d, t in truth.items()}, result, answer)

    def centre(north: float, east: float) -> tuple[float, float]:
        lat = sum(HOMES[d][0] for d in DRONES) / 3
        lon = sum(HOMES[d][1] for d in DRONES) / 3
        return offset_position(lat, lon, north, east)

    home = {d: landed_at(CTX.point(d, 0, 0)) for d in DRONES}
    pads = {d: CTX.point(d, 0, 0) for d in DRONES}
    d10, d30 = 10 / math.sqrt(2), 30 / math.sqrt(2)

    # down on the pad between 8 m and 12 m; not straight up to 12 m, not the first climb to 12 m
    touch = check("single21-bravo-touch-and-go")
    assert touch(heights({"bravo": [0, 8, 0, 12]}))
    assert not touch(heights({"bravo": [0, 8, 12]}))
    assert not touch(heights({"bravo": [0, 12, 0, 12]}))

    # five seconds at 3 m/s is 15 m, not 3 m, not 3 + 5
    seconds = check("single21-de-charlie-climb-five-seconds")
    assert seconds(ev({"charlie": _hovering("charlie", 0, 0, 15)}))
    assert not seconds(ev({"charlie": _hovering("charlie", 0, 0, 3)}))
    assert not seconds(ev({"charlie": _hovering("charlie", 0, 0, 8)}))

    # up to 18 m and back to 12 m; not left at 18 m, not never above 12 m
    bump = check("single21-ja-alpha-bump-and-back")
    assert bump(heights({"alpha": [0, 12, 18, 12]}))
    assert not bump(heights({"alpha": [0, 12, 18]}))
    assert not bump(heights({"alpha": [0, 12]}))

    # each over its eastern neighbour's pad, charlie over alpha's; not the other way round, not over its own
    rotate = check("multi21-rotate-pads-east")
    assert rotate(ev({"alpha": over(pads["bravo"], 10), "bravo": over(pads["charlie"], 14),
                      "charlie": over(pads["alpha"], 18)}))  # fmt: skip
    assert not rotate(ev({"alpha": over(pads["charlie"], 10), "bravo": over(pads["alpha"], 14),
                          "charlie": over(pads["bravo"], 18)}))  # fmt: skip
    assert not rotate(ev({d: over(pads[d], h) for d, h in zip(DRONES, (10, 14, 18), strict=True)}))

    # bravo on to 30 m north, the other two back on their pads; not all back, not bravo stopped at 15 m
    on = check("multi21-es-one-goes-on-two-come-back")
    back = {d: [*_track(d, [(15, 0), (-15, 0)], 10), home[d]] for d in ("alpha", "charlie")}
    bravo_on = _track("bravo", [(30, 0)], 10)
    assert on(ev({"alpha": home["alpha"], "charlie": home["charlie"], "bravo": bravo_on[-1]},
                 {**back, "bravo": bravo_on}))  # fmt: skip
    bravo_back = [*_track("bravo", [(15, 0), (-15, 0)], 10), home["bravo"]]
    assert not on(ev({d: home[d] for d in DRONES}, {**back, "bravo": bravo_back}))
    bravo_half = _track("bravo", [(15, 0)], 10)
    assert not on(ev({"alpha": home["alpha"], "charlie": home["charlie"], "bravo": bravo_half[-1]},
                     {**back, "bravo": bravo_half}))  # fmt: skip

    # charlie up only once both are down; not at the same time, not with bravo left up
    after = check("multi21-pl-charlie-after-both-land")
    hop, later = [0, 10, 0, 0, 0], [0, 0, 0, 15, 15]
    assert after(heights({"alpha": hop, "bravo": hop, "charlie": later}))
    assert not after(heights({"alpha": hop, "bravo": hop, "charlie": [0, 15, 15, 15, 15]}))
    assert not after(heights({"alpha": hop, "bravo": [0, 10, 10, 10, 10], "charlie": later}))

    # a landing at the pick-up and at the drop, in that order; not flown through, not the drop alone
    courier = check("compound21-alpha-courier-run")
    pick, drop = CTX.point("alpha", 0, 20), CTX.point("alpha", 20, 0)
    run = [home["alpha"], *along([pads["alpha"], pick], 10), landed_at(pick), *along([pick, drop], 10),
           landed_at(drop), *along([drop, pads["alpha"]], 10), home["alpha"]]  # fmt: skip
    assert courier(ev({"alpha": home["alpha"]}, {"alpha": run}))
    through = [home["alpha"], *along([pads["alpha"], pick, drop, pads["alpha"]], 10), home["alpha"]]
    assert not courier(ev({"alpha": home["alpha"]}, {"alpha": through}))
    drop_only = [home["alpha"], *along([pads["alpha"], pick, drop], 10), landed_at(drop),
                 *along([drop, pads["alpha"]], 10), home["alpha"]]  # fmt: skip
    assert not courier(ev({"alpha": home["alpha"]}, {"alpha": drop_only}))

    # the second leg twice the first, the third as long as the first: down 30 m north of the pad
    legs = check("compound21-it-legs-from-first")
    assert legs(flown("bravo", [(0, 15), (30, 0), (0, -15)], 12, landed_at(CTX.point("bravo", 30, 0))))
    assert not legs(flown("bravo", [(0, 15), (15, 0), (0, -15)], 12, landed_at(CTX.point("bravo", 15, 0))))
    assert not legs(flown("bravo", [(0, 15), (30, 0), (0, -30)], 12, landed_at(CTX.point("bravo", 30, -15))))

    # the climb to 16 m at the far point and the landing back at the first; not level, not down out there
    first_point = check("compound21-tr-charlie-back-to-first-point")
    first, far = landed_at(CTX.point("charlie", 15, 0)), landed_at(CTX.point("charlie", 30, 0))
    climb_there = [_hovering("charlie", 30, 0, a) for a in (10, 12, 14, 16)]
    out = [*_track("charlie", [(15, 0), (15, 0)], 8), *climb_there]
    descent = [_hovering("charlie", 30 - k, 0, 16 - 8 * k / 15) for k in range(16)]
    assert first_point(ev({"charlie": first}, {"charlie": [*out, *descent, first]}))
    assert not first_point(flown("charlie", [(15, 0), (15, 0), (-15, 0)], 8, first))
    assert not first_point(ev({"charlie": far}, {"charlie": [*out, far]}))

    # bravo and charlie are 5 points apart, the closest pair; not the two fullest, not all three
    closest = check("cond21-closest-pair-flies")
    east = {d: _hovering(d, 0, 15, 12) for d in DRONES}
    assert closest(ev({d: east[d] for d in ("bravo", "charlie")}))
    assert not closest(ev({d: east[d] for d in ("alpha", "charlie")}))
    assert not closest(ev(east))

    # 66 % is more than one and a half times 40 %: 20 m, not 10 m; charlie stays down
    ratio = check("cond21-fr-bravo-ratio-to-charlie")
    assert ratio(ev({"bravo": _hovering("bravo", 0, 0, 20)}))
    assert not ratio(ev({"bravo": _hovering("bravo", 0, 0, 10)}))
    assert not ratio(ev({"charlie": _hovering("charlie", 0, 0, 20)}))

    # charlie is over 55 % but below bravo: alpha flies, not charlie
    both = check("cond21-zh-charlie-only-if-both")
    assert both(ev({"alpha": _hovering("alpha", 0, -20, 10)}))
    assert not both(ev({"charlie": _hovering("charlie", 0, -20, 10)}))

    # the column's head over the point 10 m north (its centre 2 m north); not centred on the point, not a row
    column = check("form21-column-from-north-end")
    assert column(ev({d: over(centre(n, 0), 15) for d, n in zip(DRONES, (10, 2, -6), strict=True)}))
    assert not column(ev({d: over(centre(n, 0), 15) for d, n in zip(DRONES, (18, 10, 2), strict=True)}))
    assert not column(ev({d: over(centre(2, e), 15) for d, e in zip(DRONES, (-8, 0, 8), strict=True)}))

    # at right angles to the pads' line (north-south), 15 m east; not along it, not over the pads
    square_to = check("form21-nl-row-square-to-pads")
    assert square_to(ev({d: over(centre(n, 15), 10) for d, n in zip(DRONES, (7, 0, -7), strict=True)}))
    along_pads = {d: over(centre(0, 15 + e), 10) for d, e in zip(DRONES, (-7, 0, 7), strict=True)}
    assert not square_to(ev(along_pads))
    assert not square_to(ev({d: over(centre(n, 0), 10) for d, n in zip(DRONES, (7, 0, -7), strict=True)}))

    # charlie in the middle of a west-east row; not at its end, not a north-south column through it
    middle = check("form21-ru-join-charlie-in-middle")
    spot = CTX.point("charlie", 25, 0)
    assert middle(ev({d: over(offset_position(*spot, 0, e), 12)
                      for d, e in zip(DRONES, (-9, 9, 0), strict=True)}))  # fmt: skip
    assert not middle(ev({d: over(offset_position(*spot, 0, e), 12)
                          for d, e in zip(DRONES, (-18, -9, 0), strict=True)}))  # fmt: skip
    assert not middle(ev({d: over(offset_position(*spot, n, 0), 12)
                          for d, n in zip(DRONES, (-9, 9, 0), strict=True)}))  # fmt: skip

    # one straight line; not east then north, not north then east
    straight = check("rel21-alpha-one-straight-line")
    end = _hovering("alpha", 16, 30, 10)
    assert straight(flown("alpha", [(16, 30)], 10, end))
    assert not straight(flown("alpha", [(0, 30), (16, 0)], 10, end))
    assert not straight(flown("alpha", [(16, 0), (0, 30)], 10, end))

    # 40 % off 20 m is 12 m; not 4 m off, not down to 40 % of it
    percent = check("rel21-sv-bravo-lower-by-percent")
    assert percent(flown("bravo", [(0, -15)], 20, _hovering("bravo", 0, -15, 12)))
    assert not percent(flown("bravo", [(0, -15)], 20, _hovering("bravo", 0, -15, 16)))
    assert not percent(flown("bravo", [(0, -15)], 20, _hovering("bravo", 0, -15, 8)))

    # three times as far from the pad (30 m south-west); not 30 m further, not left at 10 m
    thrice = check("rel21-vi-charlie-three-times-as-far")
    assert thrice(flown("charlie", [(-3 * d10, -3 * d10)], 10, _hovering("charlie", -3 * d10, -3 * d10, 10)))
    further = _hovering("charlie", -4 * d10, -4 * d10, 10)
    assert not thrice(flown("charlie", [(-4 * d10, -4 * d10)], 10, further))
    assert not thrice(flown("charlie", [(-d10, -d10)], 10, _hovering("charlie", -d10, -d10, 10)))

    # questions: the average with charlie at 100 % (or the two readings it keeps), not today's average; the
    # emptiest's minutes (bravo), not the fullest's; the pair summing to 100, not another pair
    fresh = check("ask21-average-after-fresh-battery")
    assert fresh(ev({}, text="68.3 % once charlie has its fresh battery."))
    assert fresh(ev({}, text="alpha 61 %, bravo 44 %, charlie 23 %"))
    assert not fresh(ev({}, text="The average is 42.7 %."))
    assert not fresh(heights({"alpha": [0, 5]}))
    minutes = check("ask21-hi-minutes-to-full")
    assert minutes(ev({}, text="bravo: 27 मिनट"))
    assert minutes(ev({}, text="bravo 46 %"))
    assert not minutes(ev({}, text="alpha: 14 मिनट"))
    pair = check("ask21-fa-pair-sums-to-hundred")
    assert pair(ev({}, text="alpha (37 %) و charlie (63 %)"))
    assert not pair(ev({}, text="bravo (55 %) و charlie (63 %)"))

    # the 140 m climb refused and reported; not flown, not refused and called done
    tower_block = check("refuse21-bravo-tower-storeys")
    too_high = "max_altitude: 140 m is above the limit of 120 m"
    assert tower_block(refused({}, too_high))
    assert not tower_block(heights({"bravo": [0, 60, 120, 140]}))
    assert not tower_block(refused({}, too_high, answer="Done."))

    # the step to the fifth pass refused; not flown out to 1200 m, not refused and called done
    survey = check("refuse21-ro-charlie-survey-past-limit")
    too_far = "max_distance: 1200 m from home is beyond the limit of 1000 m"
    assert survey(refused({"charlie": _hovering("charlie", 0, 900, 40)}, too_far))
    assert not survey(flown("charlie", [(0, 1200)], 40, _hovering("charlie", 0, 1200, 40)))
    assert not survey(refused({"charlie": _hovering("charlie", 0, 900, 40)}, too_far, answer="Done."))

    # 12 ft (3.7 m) refused by the separation; not flown that tight, not refused and called done
    tight = check("refuse21-id-row-twelve-feet")
    close = "separation: 3.7 m is below the minimum separation of 5 m"
    assert tight(refused({}, close))
    row = {d: over(centre(0, e), 15) for d, e in zip(DRONES, (-12 * ft, 0, 12 * ft), strict=True)}
    assert not tight(refused(row, close))
    assert not tight(refused({}, close, answer="Done."))

    # a furlong and feet, not metres; decimetres and km, not metres; yards and feet, not metres
    furlong = check("units21-charlie-furlong")
    assert furlong(flown("charlie", [(220 * yd, 0)], 50 * ft, landed_at(CTX.point("charlie", 220 * yd, 0))))
    assert not furlong(flown("charlie", [(220, 0)], 50 * ft, landed_at(CTX.point("charlie", 220, 0))))
    assert not furlong(flown("charlie", [(220 * yd, 0)], 50, landed_at(CTX.point("charlie", 220 * yd, 0))))
    decimetres = check("units21-cs-bravo-decimetres-km")
    assert decimetres(flown("bravo", [(-35, 0)], 12, landed_at(CTX.point("bravo", -35, 0))))
    assert not decimetres(flown("bravo", [(-35, 0)], 1.2, landed_at(CTX.point("bravo", -35, 0))))
    assert not decimetres(flown("bravo", [(-3.5, 0)], 12, landed_at(CTX.point("bravo", -3.5, 0))))
    yards = check("units21-ko-alpha-feet-yards-climb")
    assert yards(flown("alpha", [(0, 100 * yd)], 45 * ft, _hovering("alpha", 0, 100 * yd, 60 * ft)))
    assert not yards(flown("alpha", [(0, 100)], 45 * ft, _hovering("alpha", 0, 100, 60 * ft)))
    assert not yards(flown("alpha", [(0, 100 * yd)], 45 * ft, _hovering("alpha", 0, 100 * yd, 45 * ft + 15)))

    # the parallelogram leaning north-east, not north-west, not a rectangle
    d15 = 15 / math.sqrt(2)
    slant = check("pattern21-bravo-parallelogram")
    assert slant(flown("bravo", [(0, 20), (d15, d15), (0, -20), (-d15, -d15)], 12, home["bravo"]))
    assert not slant(flown("bravo", [(0, 20), (d15, -d15), (0, -20), (-d15, d15)], 12, home["bravo"]))
    assert not slant(flown("bravo", [(0, 20), (15, 0), (0, -20), (-15, 0)], 12, home["bravo"]))

    # the square climbing 3 m a side to 22 m, turning right; not level, not turning left
    def climbing(sides: list[tuple[float, float]]) -> list[DroneTruth]:
        """alpha flying ``sides`` from its pad, from 10 m up, 3 m higher by the end of each side."""
        out, n0, e0 = [_hovering("alpha", 0, 0, 10)], 0.0, 0.0
        for i, (n, e) in enumerate(sides):
            out += [_hovering("alpha", n0 + n * k / 15, e0 + e * k / 15, 10 + 3 * i + k / 5)
                    for k in range(1, 16)]  # fmt: skip
            n0, e0 = n0 + n, e0 + e
        return out

    spiral = check("pattern21-he-alpha-climbing-square")
    sides = [(15, 0), (0, 15), (-15, 0), (0, -15)]
    right = climbing(sides)
    assert spiral(ev({"alpha": right[-1]}, {"alpha": right}))
    assert not spiral(flown("alpha", sides, 10, _hovering("alpha", 0, 0, 10)))
    left = climbing([(15, 0), (0, -15), (-15, 0), (0, 15)])
    assert not spiral(ev({"alpha": left[-1]}, {"alpha": left}))

    # the hexagon round the pad from its north corner, clockwise; not anticlockwise, not from the pad
    hex_legs = [(12 * math.cos(math.radians(b)), 12 * math.sin(math.radians(b))) for b in range(120, 480, 60)]
    ring = check("pattern21-ar-charlie-hexagon-round-pad")
    assert ring(flown("charlie", [(12, 0), *hex_legs, (-12, 0)], 12, home["charlie"]))
    anticlockwise = [(n, -e) for n, e in hex_legs]
    assert not ring(flown("charlie", [(12, 0), *anticlockwise, (-12, 0)], 12, home["charlie"]))
    from_pad = [(12 * math.cos(math.radians(b)), 12 * math.sin(math.radians(b))) for b in range(0, 360, 60)]
    assert not ring(flown("charlie", from_pad, 12, home["charlie"]))

    # placements from alpha (and bravo, and a place), not from charlie's own pad
    opposite = check("place21-charlie-opposite-alpha-pad")
    alpha_north = _hovering("alpha", 20, 0, 12)
    assert opposite(ev({"alpha": alpha_north, "charlie": over(CTX.point("alpha", -20, 0), 12)}))
    assert not opposite(ev({"alpha": alpha_north, "charlie": _hovering("charlie", -20, 0, 12)}))
    assert not opposite(ev({"alpha": alpha_north, "charlie": over(CTX.point("alpha", 40, 0), 12)}))
    corner = check("place21-pt-charlie-east-of-alpha-north-of-bravo")
    two = {"alpha": _hovering("alpha", 25, 0, 15), "bravo": _hovering("bravo", 0, 20, 15)}
    meet = (CTX.point("alpha", 25, 0)[0], CTX.point("bravo", 0, 20)[1])
    assert corner(ev({**two, "charlie": over(meet, 15)}))
    assert not corner(ev({**two, "charlie": over((meet[0], pads["bravo"][1]), 15)}))
    assert not corner(ev({**two, "charlie": _hovering("charlie", 25, 20, 15)}))
    by_tower = check("place21-uk-charlie-lands-east-of-tower")
    tower = CTX.point("alpha", d30, -d30)
    spot = offset_position(*tower, 0, 8)
    trip = [home["charlie"], *along([pads["charlie"], tower, spot], 20), landed_at(spot)]
    assert by_tower(ev({"charlie": landed_at(spot)}, {"charlie": trip}))
    own = CTX.point("charlie", d30, -d30)
    own_spot = offset_position(*own, 0, 8)
    own_trip = [home["charlie"], *along([pads["charlie"], own, own_spot], 20), landed_at(own_spot)]
    assert not by_tower(ev({"charlie": landed_at(own_spot)}, {"charlie": own_trip}))
    on_tower = [home["charlie"], *along([pads["charlie"], tower], 20), landed_at(tower)]
    assert not by_tower(ev({"charlie": landed_at(tower)}, {"charlie": on_tower}))

    # the language class: west and higher, not east; south then east, not west; back home, not south
    hausa = check("lang21-ha-bravo-west-climb-hover")
    assert hausa(flown("bravo", [(0, -20)], 12, _hovering("bravo", 0, -20, 18)))
    assert not hausa(flown("bravo", [(0, 20)], 12, _hovering("bravo", 0, 20, 18)))
    assert not hausa(flown("bravo", [(0, -20)], 12, _hovering("bravo", 0, -20, 12)))
    kurdish = check("lang21-ku-charlie-south-east-land")
    assert kurdish(flown("charlie", [(-20, 0), (0, 15)], 10, landed_at(CTX.point("charlie", -20, 15))))
    assert not kurdish(flown("charlie", [(-20, 0), (0, -15)], 10, landed_at(CTX.point("charlie", -20, -15))))
    odia = check("lang21-or-alpha-north-home")
    assert odia(flown("alpha", [(30, 0), (-30, 0)], 15, home["alpha"]))
    assert not odia(flown("alpha", [(-30, 0), (30, 0)], 15, home["alpha"]))
    assert not odia(flown("alpha", [(30, 0)], 15, landed_at(CTX.point("alpha", 30, 0))))


def test_the_twenty_second_test_half_is_well_formed() -> None:
    """The twenty-second test half (read from ``_twenty_second_test_half`` itself: it is not in ``corpus()``
    until the twenty-first has been measured): 3 a class, its ids and requests new to the corpus, none
    worded as a tool, each with a plan, and none of its checks passed by a fleet that did nothing; 22 of the
    33 outside ``language`` and all of that class's 3 in other languages than English."""
    from bench.nl_corpus import _twenty_second_test_half

    half = _twenty_second_test_half()
    ids = [e.id for e in half]
    assert len(half) == 36 and len(set(ids)) == 36
    assert Counter(e.cls for e in half) == Counter(dict.fromkeys(CLASSES, 3))
    assert all(e.half == "test" and re.match(r"[a-z]+22-", e.id) for e in half)
    known = corpus()
    assert not set(ids) & {e.id for e in known}
    requests = [e.mission.prompt(CTX) for e in half]
    assert len(set(requests)) == 36 and not set(requests) & {e.mission.prompt(CTX) for e in known}
    tool_words = ("move_to_relative", "formation_goto", "go_to_location", "return_to_launch", "_m", "alt_m")
    nothing = Evidence(IDLE, {d: [t] for d, t in IDLE.items()}, [], "Done.")
    for e, request in zip(half, requests, strict=True):
        assert set(e.mission.drones) <= set(DRONES), e.id
        assert _sentence_length(request) >= 4 and not any(w in request for w in tool_words), e.id
        assert e.mission.plan(CTX) and set(e.mission.battery_pct) <= set(e.mission.drones), e.id
        assert not e.mission.check(CTX, nothing).ok, e.id
    english = re.compile(r"\b(the|to|and|up|at|of|is|then|with|any)\b", re.IGNORECASE)
    others = [e for e, r in zip(half, requests, strict=True) if e.cls != "language" and not english.search(r)]
    assert len(others) == 22 and {e.cls for e in others} == set(CLASSES) - {"language"}
    assert not any(english.search(r) for e, r in zip(half, requests, strict=True) if e.cls == "language")


def test_a_wrong_outcome_fails_the_twenty_second_test_half_checks() -> None:
    """Each trap the twenty-second test half sets: the right outcome passes, the likely wrong one fails (the
    half is read from ``_twenty_second_test_half`` itself: it is not in ``corpus()`` yet)."""
    from bench.nl_corpus import _twenty_second_test_half

    entries = {e.id: e for e in _twenty_second_test_half()}
    assert len(entries) == 36 and Counter(e.cls for e in entries.values()) == Counter(
        dict.fromkeys(CLASSES, 3)
    )
    assert all(e.half == "test" for e in entries.values())
    ft, inch, mile = 0.3048, 0.0254, 1609.344
    idle = {d: DroneTruth(*HOMES[d][:2], 0.0, False, 90.0) for d in DRONES}

    def check(mid: str) -> Callable[[Evidence], bool]:
        """The entry's check, bound to the test homes."""
        return lambda evidence: entries[mid].mission.check(CTX, evidence).ok

    def flown(drone: str, legs: list[tuple[float, float]], alt: float, end: DroneTruth) -> Evidence:
        return ev({drone: end}, {drone: [*_track(drone, legs, alt), end]})

    def heights(alts: dict[str, list[float]]) -> Evidence:
        """Each drone over its own pad at the heights given, sampled together; each ends at its last one."""
        track = {d: [over(CTX.point(d, 0, 0), a) for a in hs] for d, hs in alts.items()}
        return ev({d: t[-1] for d, t in track.items()}, track)

    def along(stops: list[tuple[float, float]], alt: float) -> list[DroneTruth]:
        """Samples about every metre on the straight lines between ``stops`` (lat, lon), at ``alt``."""
        out = []
        for a, b in itertools.pairwise(stops):
            steps = max(1, int(math.hypot(*ned_offset(*a, *b))))
            out += [over((a[0] + (b[0] - a[0]) * i / steps, a[1] + (b[1] - a[1]) * i / steps), alt)
                    for i in range(steps + 1)]  # fmt: skip
        return out

    def trips(tracks: dict[str, list[DroneTruth]]) -> Evidence:
        """Each drone's track as given, ending where it ends."""
        return ev({d: t[-1] for d, t in tracks.items()}, tracks)

    def refused(
        final: dict[str, DroneTruth], text: str, answer: str = "Refused: over the limit."
    ) -> Evidence:
        result = [{"name": "move_to_relative", "status": "error", "text": text}]
        truth = {**idle, **final}
        return Evidence(truth, {d: [t] for d, t in truth.items()}, result, answer)

    def centre(north: float, east: float) -> tuple[float, float]:
        lat = sum(HOMES[d][0] for d in DRONES) / 3
        lon = sum(HOMES[d][1] for d in DRONES) / 3
        return offset_position(lat, lon, north, east)

    home = {d: landed_at(CTX.point(d, 0, 0)) for d in DRONES}
    pads = {d: CTX.point(d, 0, 0) for d in DRONES}
    d20, d40 = 20 / math.sqrt(2), 40 / math.sqrt(2)

    # up to 25 m and halfway down (12.5 m); not left at 25 m, not down to the pad, not never at 25 m
    halfway = check("single22-bravo-halfway-down")
    assert halfway(heights({"bravo": [0, 25, 12.5]}))
    assert not halfway(heights({"bravo": [0, 25]}))
    assert not halfway(heights({"bravo": [0, 25, 0]}))
    assert not halfway(heights({"bravo": [0, 12.5]}))

    # halfway between 10 m and 30 m is 20 m; not either end, not their sum
    midway = check("single22-yue-charlie-midway-ten-thirty")
    assert midway(ev({"charlie": _hovering("charlie", 0, 0, 20)}))
    for wrong in (10, 30, 40):
        assert not midway(ev({"charlie": _hovering("charlie", 0, 0, wrong)}))

    # down to 4 m above the ground; not down by 4 m (12 m), not never up to 16 m
    sink = check("single22-fy-alpha-sixteen-then-four")
    assert sink(heights({"alpha": [0, 16, 4]}))
    assert not sink(heights({"alpha": [0, 16, 12]}))
    assert not sink(heights({"alpha": [0, 4]}))

    # up alpha, bravo, charlie in turn and down charlie, bravo, alpha; not down in the takeoffs' order, not
    # all up at once
    reverse = check("multi22-reverse-landing-order")
    assert reverse(heights({"alpha": [0, 10, 10, 10, 10, 10, 0, 0], "bravo": [0, 0, 10, 10, 10, 0, 0, 0],
                            "charlie": [0, 0, 0, 10, 0, 0, 0, 0]}))  # fmt: skip
    assert not reverse(heights({"alpha": [0, 10, 10, 10, 0, 0, 0, 0], "bravo": [0, 0, 10, 10, 10, 0, 0, 0],
                                "charlie": [0, 0, 0, 10, 10, 10, 0, 0]}))  # fmt: skip
    assert not reverse(heights({"alpha": [0, 10, 10, 10, 10, 10, 0, 0], "bravo": [0, 10, 10, 10, 10, 0, 0, 0],
                                "charlie": [0, 10, 10, 10, 0, 0, 0, 0]}))  # fmt: skip

    # 10, 20 and 30 m north; alpha and charlie down out there, bravo up; not all 20 m, not bravo down too
    def staggered(north: dict[str, float], bravo_down: bool) -> Evidence:
        tracks = {d: _track(d, [(n, 0)], 12) for d, n in north.items()}
        for d in ("alpha", "charlie") if not bravo_down else DRONES:
            tracks[d] = [*tracks[d], landed_at(CTX.point(d, north[d], 0))]
        return trips(tracks)

    stagger = check("multi22-tk-staggered-north-two-land")
    assert stagger(staggered({"alpha": 10, "bravo": 20, "charlie": 30}, bravo_down=False))
    assert not stagger(staggered({"alpha": 20, "bravo": 20, "charlie": 20}, bravo_down=False))
    assert not stagger(staggered({"alpha": 10, "bravo": 20, "charlie": 30}, bravo_down=True))

    # each out its own way, then down on the other's pad; not back on its own, not out the wrong ways
    swap = check("multi22-oc-onto-each-others-pads")
    west, east = CTX.point("alpha", 0, -30), CTX.point("bravo", 0, 30)

    def out_and_down(
        alpha_out: tuple[float, float], bravo_out: tuple[float, float], swapped: bool
    ) -> Evidence:
        """alpha out at 10 m and bravo out at 20 m, each then down on the other's pad or on its own."""
        a_end, b_end = (pads["bravo"], pads["alpha"]) if swapped else (pads["alpha"], pads["bravo"])
        alpha = [*along([pads["alpha"], alpha_out, a_end], 10), landed_at(a_end)]
        return trips(
            {"alpha": alpha, "bravo": [*along([pads["bravo"], bravo_out, b_end], 20), landed_at(b_end)]}
        )

    assert swap(out_and_down(west, east, swapped=True))
    assert not swap(out_and_down(west, east, swapped=False))
    assert not swap(out_and_down(CTX.point("alpha", 0, 30), CTX.point("bravo", 0, -30), swapped=True))

    # two runs out and back, then down on the pad; not one run, not down at the far end
    runs = check("compound22-charlie-fence-runs-twice")
    assert runs(flown("charlie", [(-20, 0), (20, 0), (-20, 0), (20, 0)], 10, home["charlie"]))
    assert not runs(flown("charlie", [(-20, 0), (20, 0)], 10, home["charlie"]))
    assert not runs(
        flown("charlie", [(-20, 0), (20, 0), (-20, 0)], 10, landed_at(CTX.point("charlie", -20, 0)))
    )

    # the dip to 6 m 20 m west, then up to 18 m and 20 m north; not without the dip, not east
    def dip(east: float, lowest: float) -> Evidence:
        out = [*_track("alpha", [(0, east)], 12)]
        down = [a for a in (10, 8, 6) if a >= lowest]
        out += [_hovering("alpha", 0, east, a) for a in (*down, *reversed(down[:-1]), 12, 14, 16, 18)]
        out += [_hovering("alpha", k, east, 18) for k in range(1, 21)]
        return ev({"alpha": out[-1]}, {"alpha": out})

    photo = check("compound22-ug-alpha-west-dip-north")
    assert photo(dip(-20, 6))
    assert not photo(dip(-20, 12))
    assert not photo(dip(20, 6))

    # down 15 m east before the leg west, ending 15 m west of the pad at 8 m; not flown through, not short
    stop, past = CTX.point("bravo", 0, 15), CTX.point("bravo", 0, -15)
    hop = check("compound22-fo-bravo-land-east-then-west")
    end = _hovering("bravo", 0, -15, 8)
    assert hop(
        trips({"bravo": [*along([pads["bravo"], stop], 10), landed_at(stop), *along([stop, past], 8), end]})
    )
    assert not hop(trips({"bravo": [*along([pads["bravo"], stop], 10), *along([stop, past], 8), end]}))
    short = [*along([pads["bravo"], stop], 10), landed_at(stop), *along([stop, pads["bravo"]], 8)]
    assert not hop(trips({"bravo": [*short, _hovering("bravo", 0, 0, 8)]}))

    # the middle charge (charlie, 63 %) flies; not the fullest, not the emptiest
    middle = check("cond22-middle-charge-flies")
    assert middle(ev({"charlie": _hovering("charlie", 20, 0, 10)}))
    assert not middle(ev({"bravo": _hovering("bravo", 20, 0, 10)}))
    assert not middle(ev({"alpha": _hovering("alpha", 20, 0, 10)}))

    # 58 + 55 is under 120: only alpha (the fuller) rises; not both, not bravo
    total = check("cond22-ast-sum-over-hundred-twenty")
    assert total(ev({"alpha": _hovering("alpha", 0, 0, 15)}))
    assert not total(ev({"alpha": _hovering("alpha", 0, 0, 15), "bravo": _hovering("bravo", 0, 0, 15)}))
    assert not total(ev({"bravo": _hovering("bravo", 0, 0, 15)}))

    # charlie (52 %) is below bravo (67 %): bravo flies 30 m west of its pad and lands; not charlie
    unless = check("cond22-tt-charlie-unless-below-bravo")
    assert unless(flown("bravo", [(0, -30)], 12, landed_at(CTX.point("bravo", 0, -30))))
    assert not unless(flown("charlie", [(0, -30)], 12, landed_at(CTX.point("charlie", 0, -30))))

    # the V's point 20 m north of bravo's pad, wings behind it, any drone in any slot; not pointing south,
    # not round bravo's pad
    vee = check("form22-v-pointing-north")
    slots = [CTX.point("bravo", 20, 0), CTX.point("bravo", 10, -10), CTX.point("bravo", 10, 10)]
    assert vee(ev({d: over(p, 15) for d, p in zip(DRONES, slots, strict=True)}))
    assert vee(ev({d: over(p, 15) for d, p in zip(("charlie", "alpha", "bravo"), slots, strict=True)}))
    south = [CTX.point("bravo", 20, 0), CTX.point("bravo", 30, -10), CTX.point("bravo", 30, 10)]
    assert not vee(ev({d: over(p, 15) for d, p in zip(DRONES, south, strict=True)}))
    at_pad = [CTX.point("bravo", 0, 0), CTX.point("bravo", -10, -10), CTX.point("bravo", -10, 10)]
    assert not vee(ev({d: over(p, 15) for d, p in zip(DRONES, at_pad, strict=True)}))

    # three on a 10 m circle round the point 25 m east of charlie's pad; not round the pad, not a row
    def on_circle(north: float, east: float, radius: float) -> dict[str, DroneTruth]:
        spot = CTX.point("charlie", north, east)
        rays = [
            (radius * math.cos(math.radians(a)), radius * math.sin(math.radians(a))) for a in (0, 120, 240)
        ]
        return {d: over(offset_position(*spot, n, e), 20) for d, (n, e) in zip(DRONES, rays, strict=True)}

    circle = check("form22-su-ring-east-of-charlie")
    assert circle(ev(on_circle(0, 25, 10)))
    assert not circle(ev(on_circle(0, 0, 10)))
    assert not circle(ev(on_circle(0, 25, 5)))
    spot = CTX.point("charlie", 0, 25)
    row = {d: over(offset_position(*spot, 0, e), 20) for d, e in zip(DRONES, (-17.3, 0, 17.3), strict=True)}
    assert not circle(ev(row))

    # the L's corner 15 m south of the pads' middle, arms north and west; not the arm east, not at the pads
    ell = check("form22-ja-l-shape-south")
    assert ell(
        ev(
            {
                d: over(centre(n, e), 12)
                for d, (n, e) in zip(DRONES, ((-15, -10), (-5, 0), (-15, 0)), strict=True)
            }
        )
    )
    assert not ell(
        ev(
            {
                d: over(centre(n, e), 12)
                for d, (n, e) in zip(DRONES, ((-15, 10), (-5, 0), (-15, 0)), strict=True)
            }
        )
    )
    assert not ell(
        ev({d: over(centre(n, e), 12) for d, (n, e) in zip(DRONES, ((0, -10), (10, 0), (0, 0)), strict=True)})
    )

    # a compass bearing of 120 degrees (south-east of east); not 120 degrees from east anticlockwise, not 150
    bearing = check("rel22-bravo-bearing-120")
    s3 = 15 * math.sqrt(3)
    assert bearing(ev({"bravo": _hovering("bravo", -15, s3, 12)}))
    assert not bearing(ev({"bravo": _hovering("bravo", s3, -15, 12)}))
    assert not bearing(ev({"bravo": _hovering("bravo", -s3, 15, 12)}))

    # east as far as it is high (18 m), then down by a third of its height (to 12 m); not down to a third
    # of it (6 m), not north
    as_high = check("rel22-kk-alpha-east-as-far-as-high")
    assert as_high(flown("alpha", [(0, 18)], 18, _hovering("alpha", 0, 18, 12)))
    assert not as_high(flown("alpha", [(0, 18)], 18, _hovering("alpha", 0, 18, 6)))
    assert not as_high(flown("alpha", [(18, 0)], 18, _hovering("alpha", 18, 0, 12)))

    # 10 m back along the north-east track and 5 m up; not 10 m south, not level
    back = check("rel22-el-charlie-back-along-track")
    track = [(d40, d40), (-d40 / 4, -d40 / 4)]
    assert back(flown("charlie", track, 10, _hovering("charlie", 3 * d40 / 4, 3 * d40 / 4, 15)))
    assert not back(flown("charlie", [(d40, d40), (-10, 0)], 10, _hovering("charlie", d40 - 10, d40, 15)))
    assert not back(flown("charlie", track, 10, _hovering("charlie", 3 * d40 / 4, 3 * d40 / 4, 10)))

    # questions: bravo's 57 % is nearest 50, not alpha's 38 %; both readings asked for, not the ratio or the
    # gap alone; nothing flies
    half_full = check("ask22-closest-to-half")
    assert half_full(ev({}, text="Bravo, with 57 %."))
    assert not half_full(ev({}, text="Alpha, with 38 %."))
    assert not half_full(heights({"bravo": [0, 5]}))
    times = check("ask22-as-bravo-times-charlie")
    assert times(ev({}, text="bravo 90 %, charlie 30 %: 3 গুণ"))
    assert not times(ev({}, text="3 গুণ"))
    gap = check("ask22-ml-charlie-points-to-alpha")
    assert gap(ev({}, text="37: alpha 71 %, charlie 34 %"))
    assert not gap(ev({}, text="37"))

    # 450 ft (137 m) refused and reported; not flown, not refused and called done
    photo_high = check("refuse22-charlie-450-feet")
    too_high = "max_altitude: target altitude 137.2 m exceeds the limit of 120 m above home"
    assert photo_high(refused({}, too_high))
    assert not photo_high(heights({"charlie": [0, 60, 120, 137]}))
    assert not photo_high(refused({}, too_high, answer="Done."))

    # 800 m north flown, the 700 m east (1063 m from home) refused; not flown, not refused from the start
    mast = check("refuse22-yi-bravo-north-then-east-too-far")
    too_far = "max_distance: target 1063 m from home exceeds the limit of 1000 m"
    north = _hovering("bravo", 800, 0, 30)
    assert mast(refused({"bravo": north}, too_far))
    assert not mast(flown("bravo", [(800, 0), (0, 700)], 30, _hovering("bravo", 800, 700, 30)))
    assert not mast(refused({}, too_far))
    assert not mast(refused({"bravo": north}, too_far, answer="Done."))

    # alpha and bravo up, charlie (22 %) refused; not charlie flown, not all kept down
    flat = check("refuse22-hy-all-three-charlie-flat")
    low = "min_battery_takeoff: battery 22 % is below the 30 % needed to take off"
    pair = {d: _hovering(d, 0, 0, 10) for d in ("alpha", "bravo")}
    assert flat(refused(pair, low))
    assert not flat(refused({**pair, "charlie": _hovering("charlie", 0, 0, 10)}, low))
    assert not flat(refused({}, low))

    # miles and feet, not km and metres; inches and feet, not cm and metres; feet and km, not metres
    miles = check("units22-charlie-miles-west")
    there = landed_at(CTX.point("charlie", 0, -0.15 * mile))
    assert miles(flown("charlie", [(0, -0.15 * mile)], 30 * ft, there))
    assert not miles(flown("charlie", [(0, -150)], 30 * ft, landed_at(CTX.point("charlie", 0, -150))))
    assert not miles(flown("charlie", [(0, -0.15 * mile)], 30, there))
    inches = check("units22-gd-bravo-inches-feet")
    assert inches(ev({"bravo": _hovering("bravo", 150 * ft, 0, 600 * inch)}))
    assert not inches(ev({"bravo": _hovering("bravo", 150, 0, 600 * inch)}))
    assert not inches(ev({"bravo": _hovering("bravo", 150 * ft, 0, 6)}))
    km = check("units22-mi-alpha-feet-km-east")
    assert km(flown("alpha", [(0, 120)], 40 * ft, landed_at(CTX.point("alpha", 0, 120))))
    assert not km(flown("alpha", [(0, 120)], 40, landed_at(CTX.point("alpha", 0, 120))))
    assert not km(flown("alpha", [(0, 12)], 40 * ft, landed_at(CTX.point("alpha", 0, 12))))

    # round the post anticlockwise from its south side, then home; not clockwise, not round the pad
    def orbit(centre_north: float, order: tuple[tuple[float, float], ...]) -> Evidence:
        points = [CTX.point("alpha", centre_north + n, e) for n, e in order]
        return trips(
            {"alpha": [*along([pads["alpha"], *points, points[0], pads["alpha"]], 15), home["alpha"]]}
        )

    lamp = check("pattern22-alpha-orbit-post-anticlockwise")
    assert lamp(orbit(20, ((-10, 0), (0, 10), (10, 0), (0, -10))))
    assert not lamp(orbit(20, ((-10, 0), (0, -10), (10, 0), (0, 10))))
    assert not lamp(orbit(0, ((-10, 0), (0, 10), (10, 0), (0, -10))))

    # the expanding square turning right; not turning left
    square = check("pattern22-xh-bravo-expanding-square")
    right = [(10, 0), (0, 10), (-20, 0), (0, -20), (30, 0)]
    assert square(flown("bravo", right, 12, _hovering("bravo", 20, -10, 12)))
    left = [(10, 0), (0, -10), (-20, 0), (0, 20), (30, 0)]
    assert not square(flown("bravo", left, 12, _hovering("bravo", 20, 10, 12)))

    # four passes east and west stepping north, down 30 m north of the pad; not stepping south
    mow = check("pattern22-ka-charlie-east-west-passes")
    passes = [(0, 40), (10, 0), (0, -40), (10, 0), (0, 40), (10, 0), (0, -40)]
    assert mow(flown("charlie", passes, 10, landed_at(CTX.point("charlie", 30, 0))))
    south_passes = [(-n, e) for n, e in passes]
    assert not mow(flown("charlie", south_passes, 10, landed_at(CTX.point("charlie", -30, 0))))

    # charlie halfway between alpha and bravo, and halfway between their heights; not at either height,
    # not halfway between their pads
    a, b = CTX.point("alpha", 30, 0), CTX.point("bravo", 0, 30)
    mid = ((a[0] + b[0]) / 2, (a[1] + b[1]) / 2)
    pair_up = {"alpha": _hovering("alpha", 30, 0, 10), "bravo": _hovering("bravo", 0, 30, 20)}
    midpoint = check("place22-charlie-midway-in-height-too")
    assert midpoint(ev({**pair_up, "charlie": over(mid, 15)}))
    assert not midpoint(ev({**pair_up, "charlie": over(mid, 10)}))
    assert not midpoint(ev({**pair_up, "charlie": over(CTX.point("alpha", 0, 3.8), 15)}))

    # charlie at 5 m right under alpha (22 m, 20 m north-east of alpha's pad); not from its own pad, not
    # 5 m below alpha
    under = check("place22-ko-charlie-under-alpha")
    alpha_up = _hovering("alpha", d20, d20, 22)
    assert under(ev({"alpha": alpha_up, "charlie": over(CTX.point("alpha", d20, d20), 5)}))
    assert not under(ev({"alpha": alpha_up, "charlie": _hovering("charlie", d20, d20, 5)}))
    assert not under(ev({"alpha": alpha_up, "charlie": over(CTX.point("alpha", d20, d20), 17)}))

    # charlie down 12 m south of alpha's pad, bravo 8 m over it; not from charlie's own pad, not bravo down
    spot = CTX.point("alpha", -12, 0)
    own = CTX.point("charlie", -12, 0)
    above = check("place22-nds-charlie-south-of-alpha-pad-bravo-above")
    assert above(
        trips({"charlie": [*along([pads["charlie"], spot], 10), landed_at(spot)], "bravo": [over(spot, 8)]})
    )
    assert not above(
        trips({"charlie": [*along([pads["charlie"], own], 10), landed_at(own)], "bravo": [over(own, 8)]})
    )
    assert not above(trips({"charlie": [*along([pads["charlie"], spot], 10), landed_at(spot)],
                            "bravo": [over(spot, 8), landed_at(spot)]}))  # fmt: skip

    # the language class: east, not west; south then west, not east; back 10 m and down, not down out there
    tibetan = check("lang22-bo-alpha-east-land")
    assert tibetan(flown("alpha", [(0, 20)], 12, landed_at(CTX.point("alpha", 0, 20))))
    assert not tibetan(flown("alpha", [(0, -20)], 12, landed_at(CTX.point("alpha", 0, -20))))
    pashto = check("lang22-ps-bravo-south-west-hover")
    assert pashto(flown("bravo", [(-20, 0), (0, -10)], 15, _hovering("bravo", -20, -10, 15)))
    assert not pashto(flown("bravo", [(-20, 0), (0, 10)], 15, _hovering("bravo", -20, 10, 15)))
    malagasy = check("lang22-mg-charlie-north-back-land")
    assert malagasy(flown("charlie", [(30, 0), (-10, 0)], 10, landed_at(CTX.point("charlie", 20, 0))))
    assert not malagasy(flown("charlie", [(30, 0)], 10, landed_at(CTX.point("charlie", 30, 0))))
