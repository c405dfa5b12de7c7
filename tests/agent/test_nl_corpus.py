"""The generalisation corpus (bench/nl_corpus.py) and how bench/nl_missions.py selects it (no model)."""

from __future__ import annotations

import importlib.util
import sys
from collections import Counter
from collections.abc import Iterator
from pathlib import Path
from types import ModuleType

import pytest

from bench.agent_harness.missions import DroneTruth, Evidence, MissionContext
from bench.nl_corpus import CLASSES, DRONES, HALVES, corpus, farthest_apart, formation_at, select

BENCH = Path(__file__).resolve().parents[2] / "bench" / "nl_missions.py"
HOMES = {
    "alpha": (47.397742, 8.545494, 488.0),
    "bravo": (47.397742, 8.545594, 488.0),
    "charlie": (47.397742, 8.545694, 488.0),
}
CTX = MissionContext(homes=HOMES)


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


def test_every_entry_has_a_class_a_half_a_request_a_check_and_a_plan() -> None:
    entries = corpus()
    assert len(entries) >= 40
    assert len({e.id for e in entries}) == len(entries), "ids are unique"
    assert {e.cls for e in entries} == set(CLASSES), "every class is present"
    for e in entries:
        assert e.cls in CLASSES and e.half in HALVES, e.id
        assert set(e.mission.drones) <= set(DRONES), e.id
        request = e.mission.prompt(CTX)
        assert isinstance(request, str) and len(request.split()) >= 4, e.id
        assert callable(e.mission.check), e.id
        assert e.mission.plan(CTX), e.id
        assert set(e.mission.battery_pct) <= set(e.mission.drones), e.id


def test_requests_are_not_worded_as_tool_names() -> None:
    tool_words = ("move_to_relative", "formation_goto", "go_to_location", "return_to_launch", "_m", "alt_m")
    for e in corpus():
        request = e.mission.prompt(CTX)
        assert not any(w in request for w in tool_words), (e.id, request)
    assert len({e.mission.prompt(CTX) for e in corpus()}) == len(corpus()), "no request twice"


def test_halves_are_disjoint_and_stratified_by_class() -> None:
    """The first 40 entries are split evenly by class (2 or 3 a class in each half); the 48 added later
    are all dev (two a class, then eight more in the four classes the test half measured weakest, then
    eight more in the kinds of request the test half still failed, twice, then eight more in varied kinds);
    the four classes added with the typed plan (units, pattern, placement, language) have 3 + 3. The test
    entries of conditional, formation and placement, seen while tuning, moved to dev, and new test entries
    took their place, one more a class."""
    dev, test = select("dev"), select("test")
    assert not {e.id for e in dev} & {e.id for e in test}
    assert len(dev) + len(test) == len(corpus()) == len(select("all"))
    assert len(test) == 35 and len(dev) == 88
    per_dev, per_test = Counter(e.cls for e in dev), Counter(e.cls for e in test)
    moved = Counter({"conditional": 3, "formation": 2, "placement": 3})  # test to dev
    for cls in ("units", "pattern", "placement", "language"):
        assert per_dev[cls] - moved[cls] == 3, cls
    second_day = Counter({"compound": 3, "multi": 2, "conditional": 2, "question": 1})
    third_day = Counter({"compound": 2, "multi": 1, "conditional": 3, "relative": 2})
    fourth_day = Counter({"question": 2, "compound": 2, "multi": 2, "relative": 2})
    fifth_day = Counter({"multi": 2, "compound": 2, "relative": 2, "single": 1, "formation": 1})
    for cls in CLASSES[:8]:
        assert per_test[cls] >= 2, cls
        added = second_day[cls] + third_day[cls] + fourth_day[cls] + fifth_day[cls]
        first_test = moved[cls] or per_test[cls]  # the first 40's test entries of the class
        assert abs((per_dev[cls] - moved[cls] - 2 - added) - first_test) <= 1, cls
    for cls in CLASSES[8:]:
        assert per_test[cls] == (4 if cls == "placement" else 3), cls


def test_the_test_entries_seen_while_tuning_are_dev_and_replaced_by_new_ones() -> None:
    seen = {
        "cond-half-battery-go",
        "cond-fullest-flies",
        "cond-weaker-flies",
        "form-column-north",
        "form-wedge-east",
        "place-charlie-south-of-alpha",
        "place-alpha-west-of-flying-bravo",
        "place-alpha-northeast-of-charlie",
    }
    by_id = {e.id: e for e in corpus()}
    assert all(by_id[i].half == "dev" for i in seen)
    renewed = [e for e in select("test") if e.cls in ("conditional", "formation", "placement")]
    assert Counter(e.cls for e in renewed) == Counter({"conditional": 4, "formation": 3, "placement": 4})
    assert not {e.id for e in renewed} & seen


def test_select_refuses_an_unknown_half() -> None:
    with pytest.raises(ValueError, match=r"half must be one of \['dev', 'test', 'all'\]; got 'train'"):
        select("train")


@pytest.mark.parametrize("half", ["dev", "test", "all"])
def test_the_bench_half_option_selects_that_half(bench: ModuleType, half: str) -> None:
    args = bench.parse_args(["--half", half])
    missions, where = bench.chosen_missions(args)
    assert [m.id for m in missions] == [e.id for e in select(half)]
    assert all(where[m.id][1] in ((half,) if half != "all" else HALVES) for m in missions)


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
