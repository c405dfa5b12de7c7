"""A signal that the test suite is near its end, for CI to start its compose tests beside the last files.

CI (``.ci/run``) runs the two compose tests after ``make test``, about two minutes of mostly waiting on
containers. Where ``FLEET_SUITE_TAIL_FILE`` names a path, the suite's controlling process creates that
file once the files it has not finished are expected to take at most ``FLEET_SUITE_TAIL_SECONDS`` more of
wall time (their seconds in tests/durations.json over the number of workers), and CI starts the compose
tests then instead of after the last file. Running files count as not finished; a file the table does not
name counts as ``UNKNOWN_FILE_S``. The signal only moves a start: every test still runs and is judged."""

from __future__ import annotations

import os
from collections import Counter
from collections.abc import Iterable
from pathlib import Path

#: the expected seconds of a test file tests/durations.json does not name (new files are short, mostly)
UNKNOWN_FILE_S = 10.0
DEFAULT_TAIL_S = 150.0


class SuiteTail:
    """Counts each file's tests still to report and creates ``signal`` once the expected wall time of
    the unfinished files falls to ``tail_s`` or below."""

    def __init__(self, signal: Path, tail_s: float, workers: int, seconds: dict[str, float]) -> None:
        self.signal = signal
        self.tail_s = tail_s
        self.workers = max(1, workers)
        self.seconds = seconds
        self.left: Counter[str] = Counter()

    def collected(self, nodeids: Iterable[str]) -> None:
        """The suite's tests (one worker's collection: every worker collects the same)."""
        if not self.left:
            self.left.update(nodeid.split("::", 1)[0] for nodeid in nodeids)
            self._check()

    def finished(self, nodeid: str) -> None:
        """One test reported its teardown."""
        name = nodeid.split("::", 1)[0]
        if self.left[name] > 0:
            self.left[name] -= 1
            self._check()

    def expected_wall_s(self) -> float:
        """The unfinished files' expected seconds shared by the workers."""
        unfinished = (name for name, count in self.left.items() if count > 0)
        return sum(self.seconds.get(name, UNKNOWN_FILE_S) for name in unfinished) / self.workers

    def _check(self) -> None:
        if self.left and not self.signal.exists() and self.expected_wall_s() <= self.tail_s:
            self.signal.write_text(f"{self.expected_wall_s():.0f} s of test files expected to be left\n")


def from_environment(workers: int, seconds: dict[str, float]) -> SuiteTail | None:
    """A SuiteTail when FLEET_SUITE_TAIL_FILE names a path, else None (the suite's usual run). Both
    variables leave the environment, so that a pytest a test starts cannot signal for the suite."""
    path = os.environ.pop("FLEET_SUITE_TAIL_FILE", "")
    raw = os.environ.pop("FLEET_SUITE_TAIL_SECONDS", str(DEFAULT_TAIL_S))
    if not path:
        return None
    try:
        tail_s = float(raw)
    except ValueError:
        raise ValueError(
            f"FLEET_SUITE_TAIL_SECONDS: {raw!r} is not a number of seconds (accepted: a number, e.g. 150)"
        ) from None
    return SuiteTail(Path(path), tail_s, workers, seconds)
