"""A model's recorded replies replayed through the current host (bench/nl_missions.py --replay): the
reply source on its own, and one request flown for real (simulator, gateway, MCP) from recorded plans."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
from pathlib import Path

import pytest

from bench.agent_harness.replay import DIVERGED, ReplayPilot
from tests.helpers.timing import scaled

ROOT = Path(__file__).resolve().parents[2]
MISSION = "single-charlie-hover"  # a dev request: charlie up to 12 m, left there


def _plan(after: str, drone: str = "charlie") -> str:
    step = {"action": "takeoff", "drone": drone, "altitude": {"value": 12, "unit": "m"}, "after": after}
    return json.dumps({"steps": [step]})


def _twice_up() -> str:
    """A wrong plan the host flies as written: up to 12 m, then 12 m higher."""
    leg = {"distance": {"value": 12, "unit": "m"}, "direction": "up"}
    move = {
        "action": "move",
        "drone": "charlie",
        "origin": "here",
        "legs": [leg],
        "altitude": None,
        "after": "stay",
    }
    return json.dumps({"steps": [json.loads(_plan("stay"))["steps"][0], move]})


def _recorded(path: Path, runs: list[tuple[int, list[str]]], **extra: object) -> Path:
    data = {"model": "recorded", "self_check": False, **extra}
    data["runs"] = [{"mission": MISSION, "run": n, "replies": replies} for n, replies in runs]
    path.write_text(json.dumps(data))
    return path


def test_replies_come_back_in_order_then_the_replay_says_it_diverged(tmp_path: Path) -> None:
    pilot = ReplayPilot.from_json(_recorded(tmp_path / "r.json", [(2, ["a", "b"]), (1, ["c"])]))
    assert pilot.runs() == [(1, MISSION), (2, MISSION)]
    pilot.load(MISSION, 2)
    assert [pilot({}).content, pilot({}).content] == ["a", "b"] and not pilot.diverged
    assert pilot({}).content == "" and pilot.diverged
    pilot.load(MISSION, 1)
    assert pilot({}).content == "c" and not pilot.diverged


def test_a_file_without_replies_or_of_a_self_check_is_refused_in_one_line(tmp_path: Path) -> None:
    with pytest.raises(SystemExit, match="no run there records the model's replies"):
        ReplayPilot.from_json(_recorded(tmp_path / "none.json", [(1, [])]))
    with pytest.raises(SystemExit, match="a harness self-check's replies are not a model's"):
        ReplayPilot.from_json(_recorded(tmp_path / "self.json", [(1, ["x"])], self_check=True))


def test_recorded_plans_are_flown_and_judged_by_the_current_host(tmp_path: Path) -> None:
    recorded = _recorded(
        tmp_path / "recorded.json",
        [(1, [_plan("stay")]), (2, [_twice_up()]), (3, [_plan("stay", drone="zulu")])],
    )
    out = tmp_path / "replayed.json"
    argv = [sys.executable, "bench/nl_missions.py", "--half", "dev", "--missions", MISSION]
    argv += ["--replay", str(recorded), "--json", str(out)]
    proc = subprocess.Popen(
        argv, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, start_new_session=True
    )
    try:
        log, _ = proc.communicate(timeout=scaled(240))
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGINT)
        log, _ = proc.communicate(timeout=60)
        pytest.fail(f"the replay did not finish: {log.decode(errors='replace')[-2000:]}")
    assert proc.returncode == 0, log.decode(errors="replace")[-2000:]
    runs = {r["run"]: r for r in json.loads(out.read_text())["runs"]}
    assert runs[1]["ok"], runs[1]
    assert not runs[2]["ok"] and "up_m=12" in str(runs[2]["calls"]), runs[2]
    # zulu is no drone of the fleet: the host asks once more, which the recording never answered
    assert not runs[3]["ok"] and runs[3]["detail"].startswith(DIVERGED), runs[3]
    assert runs[3]["replies"][0] == _plan("stay", drone="zulu")
