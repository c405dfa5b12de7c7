"""Replaying a model's recorded replies through the current host, with no model running.

A run of ``bench/nl_missions.py --json`` keeps the model's replies of every run (``replies``: each plan,
and the second plan of a repair round). ``--replay <that JSON>`` serves them back in order from a
scripted endpoint, so a change of the host's checking and compiling (not of its prompt or schema, which
the recorded model never saw) is judged on what the model really wrote, in minutes instead of the hours
a CPU-only model takes. When the host asks more than it asked when recorded (a repair round the recorded
turn did not have), the replay has no reply to give: the run is marked as diverged, not as the model's.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from bench.agent_harness.scripted import ScriptedReply

DIVERGED = "replay diverged: the host asked the model more often than when it was recorded"


@dataclass
class ReplayPilot:
    """Reply source for ``ScriptedModelServer``: the recorded replies of one (mission, run) at a time."""

    model: str
    recorded: dict[tuple[str, int], list[str]]
    _queue: list[str] = field(default_factory=list)
    diverged: bool = False

    @classmethod
    def from_json(cls, path: str | Path) -> ReplayPilot:
        """The replies of every run of a results JSON; one line naming the file when it has none."""
        data: dict[str, Any] = json.loads(Path(path).read_text())
        recorded = {
            (r["mission"], int(r.get("run", 1))): list(r["replies"])
            for r in data.get("runs", [])
            if r.get("replies")
        }
        if not recorded:
            raise SystemExit(
                f"--replay {path}: no run there records the model's replies (a results JSON of "
                "bench/nl_missions.py --json with a model, written since replies are recorded)"
            )
        if data.get("self_check"):
            raise SystemExit(f"--replay {path}: a harness self-check's replies are not a model's")
        return cls(model=str(data.get("model")), recorded=recorded)

    def runs(self) -> list[tuple[int, str]]:
        """(run, mission) of every recorded run, in run order."""
        return sorted((run, mission) for mission, run in self.recorded)

    def load(self, mission: str, run: int) -> None:
        self._queue, self.diverged = list(self.recorded[(mission, run)]), False

    def __call__(self, request: dict[str, Any]) -> ScriptedReply:
        if not self._queue:
            self.diverged = True
            return ScriptedReply(content="")
        return ScriptedReply(content=self._queue.pop(0))
