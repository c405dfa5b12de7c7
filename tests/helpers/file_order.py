"""The order in which ``make test`` hands test files to its workers: the longest first.

pytest-xdist's ``--dist loadfile`` gives each worker one whole file at a time in collection order
(``--no-loadscope-reorder`` keeps that order instead of sorting by test count). Longest first is the
classic greedy schedule: the files left for the end are short, so the two workers finish together
instead of one idling while a long real-autopilot flight starts last. The seconds per file come from
tests/durations.json (scripts/test_durations.py writes it from a full run); files it does not name keep
their collection order after the ones it does."""

from __future__ import annotations

import json
from collections.abc import Sequence
from pathlib import Path
from typing import Protocol

TABLE = Path(__file__).resolve().parent.parent / "durations.json"


class _Item(Protocol):
    @property
    def nodeid(self) -> str: ...


def seconds_per_file(table: Path = TABLE) -> dict[str, float]:
    """The recorded seconds per test file, or nothing when the table is missing or unreadable."""
    try:
        loaded = json.loads(table.read_text())
    except (OSError, ValueError):
        return {}
    if not isinstance(loaded, dict):
        return {}
    return {str(name): float(value) for name, value in loaded.items() if isinstance(value, int | float)}


def longest_files_first(items: Sequence[_Item], seconds: dict[str, float]) -> list[int]:
    """The items' indexes reordered so that files run longest first, each file's tests kept together
    and in their own order (a stable sort on the file's recorded seconds)."""
    return sorted(range(len(items)), key=lambda i: -seconds.get(items[i].nodeid.split("::", 1)[0], 0.0))
