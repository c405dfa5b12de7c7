"""CI's signal that the suite is near its end (tests/helpers/suite_tail.py): created once the unfinished
files' expected time falls to the threshold, never before; and wired into a real pytest-xdist run."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from tests.helpers.suite_tail import UNKNOWN_FILE_S, SuiteTail, from_environment
from tests.helpers.timing import scaled

ROOT = Path(__file__).resolve().parent.parent


def test_the_signal_comes_when_the_unfinished_files_fit_in_the_tail(tmp_path: Path) -> None:
    signal = tmp_path / "tail"
    tail = SuiteTail(signal, 60.0, 2, {"a.py": 200.0, "b.py": 90.0, "c.py": 30.0})
    tail.collected(["a.py::x", "a.py::y", "b.py::z", "c.py::w", "new.py::v"])
    assert tail.expected_wall_s() == (200 + 90 + 30 + UNKNOWN_FILE_S) / 2
    tail.finished("a.py::x")
    assert not signal.exists(), "a.py still has a test to report"
    tail.finished("a.py::y")
    assert tail.expected_wall_s() == (90 + 30 + UNKNOWN_FILE_S) / 2 and not signal.exists()
    tail.finished("b.py::z")
    assert signal.read_text() == "20 s of test files expected to be left\n"
    tail.collected(["a.py::x"])  # another worker's collection changes nothing
    assert tail.left["a.py"] == 0


def test_no_signal_without_the_variable_and_a_clear_line_for_a_bad_threshold(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    monkeypatch.delenv("FLEET_SUITE_TAIL_FILE", raising=False)
    assert from_environment(2, {}) is None
    monkeypatch.setenv("FLEET_SUITE_TAIL_FILE", str(tmp_path / "tail"))
    monkeypatch.setenv("FLEET_SUITE_TAIL_SECONDS", "soon")
    with pytest.raises(ValueError, match="FLEET_SUITE_TAIL_SECONDS: 'soon' is not a number of seconds"):
        from_environment(2, {})


def test_a_real_xdist_run_signals_at_the_end_of_its_last_file_at_threshold_0(tmp_path: Path) -> None:
    signal = tmp_path / "tail"
    env = {**os.environ, "FLEET_SUITE_TAIL_FILE": str(signal), "FLEET_SUITE_TAIL_SECONDS": "0"}
    files = ["tests/test_file_order.py", "tests/test_time_scale.py"]
    command = [sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "-n2", "--dist=loadfile"]
    run = subprocess.run(
        [*command, *files], cwd=ROOT, env=env, capture_output=True, text=True, timeout=scaled(120)
    )
    assert run.returncode == 0, run.stdout[-2000:] + run.stderr[-2000:]
    # at threshold 0 only the end of the last file fits: the signal says nothing is left
    assert signal.exists(), run.stdout[-500:]
    assert signal.read_text() == "0 s of test files expected to be left\n"


def test_the_variables_leave_the_environment_so_a_nested_pytest_cannot_signal(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    monkeypatch.setenv("FLEET_SUITE_TAIL_FILE", str(tmp_path / "tail"))
    monkeypatch.setenv("FLEET_SUITE_TAIL_SECONDS", "30")
    tail = from_environment(2, {})
    assert tail is not None and tail.tail_s == 30.0 and tail.signal == tmp_path / "tail"
    assert "FLEET_SUITE_TAIL_FILE" not in os.environ and "FLEET_SUITE_TAIL_SECONDS" not in os.environ
