"""The order make test hands files to its workers: longest recorded first, each file's tests together."""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path

from tests.helpers.file_order import TABLE, longest_files_first, seconds_per_file


@dataclass
class Item:
    nodeid: str


def test_files_run_longest_first_and_unknown_files_keep_their_order() -> None:
    items = [Item("tests/a.py::t1"), Item("tests/b.py::t1"), Item("tests/c.py::t1"), Item("tests/b.py::t2"),
             Item("tests/d.py::t1")]  # fmt: skip
    seconds = {"tests/b.py": 300.0, "tests/c.py": 20.0}
    order = [items[i].nodeid for i in longest_files_first(items, seconds)]
    assert order == ["tests/b.py::t1", "tests/b.py::t2", "tests/c.py::t1", "tests/a.py::t1", "tests/d.py::t1"]


def test_a_missing_or_broken_table_changes_nothing(tmp_path: Path) -> None:
    assert seconds_per_file(tmp_path / "absent.json") == {}
    broken = tmp_path / "broken.json"
    broken.write_text("[1, 2")
    assert seconds_per_file(broken) == {}


def test_the_recorded_table_names_test_files_that_exist() -> None:
    table = json.loads(TABLE.read_text())
    root = TABLE.parent.parent
    missing = [name for name in table if not (root / name).is_file()]
    assert not missing, f"tests/durations.json names files that are gone: {missing}"
