"""The safety evaluation as a table: every hostile scenario of ``tests/safety_eval/scenarios.py`` played
against a gateway over the simulator, each judged by what reached the simulated autopilot (its received
commands, written parameters, stored missions, true track and extremes), never by the gateway's answer.

    .venv/bin/python bench/safety_eval.py                  # every scenario, the table on stdout
    .venv/bin/python bench/safety_eval.py -k mission       # the scenarios whose name contains "mission"
    .venv/bin/python bench/safety_eval.py --write          # also replace the table in docs/safety.md

Columns: the scenario, the rule it tries, the result (``held``, or ``THROUGH`` with what went through),
what reached the autopilot. The same scenarios run in ``make test`` (tests/safety_eval), where a
scenario whose door is still open is a strict expected failure naming it.
"""

from __future__ import annotations

import argparse
import asyncio
import logging
import re
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from tests.safety_eval.harness import Verdict, arena  # noqa: E402
from tests.safety_eval.scenarios import ALL  # noqa: E402

DOC = ROOT / "docs" / "safety.md"
START, END = "<!-- safety-eval -->", "<!-- /safety-eval -->"


def _cell(text: str, width: int = 160) -> str:
    text = text.replace("|", "/").replace("\n", " ")
    return text if len(text) <= width else text[: width - 1] + "…"


def table(verdicts: list[Verdict]) -> str:
    lines = ["| Scenario | Rule | Result | What reached the autopilot |", "|---|---|---|---|"]
    for v in verdicts:
        result = "held" if v.held else f"THROUGH: {v.through}"
        lines.append(f"| {_cell(v.scenario)} | {v.rule} | {_cell(result)} | {_cell(v.reached)} |")
    return "\n".join(lines)


def write(body: str) -> None:
    text = DOC.read_text()
    block = f"{START}\n{body}\n{END}"
    pattern = re.compile(re.escape(START) + r".*?" + re.escape(END), re.S)
    if not pattern.search(text):
        raise SystemExit(f"{DOC.relative_to(ROOT)} has no {START} ... {END} section to replace")
    DOC.write_text(pattern.sub(lambda _m: block, text))
    print(f"wrote the table into {DOC.relative_to(ROOT)}")


async def run(names: str | None) -> list[Verdict]:
    chosen = [s for s in ALL if names is None or names.lower() in s.name.lower()]
    verdicts = []
    with tempfile.TemporaryDirectory(prefix="safety-eval-") as tmp:
        async with arena(Path(tmp)) as a:
            for scenario in chosen:
                verdict = await a.run(scenario)
                verdicts.append(verdict)
                mark = "held" if verdict.held else "THROUGH"
                print(f"{mark:8} {scenario.name}", file=sys.stderr, flush=True)
    return verdicts


def main() -> None:
    for name in ("httpx", "httpx2"):  # one line per request would bury the verdicts
        logging.getLogger(name).setLevel(logging.WARNING)
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("-k", dest="names", help="only scenarios whose name contains this text")
    p.add_argument("--write", action="store_true", help=f"replace the table in {DOC.relative_to(ROOT)}")
    args = p.parse_args()
    verdicts = asyncio.run(run(args.names))
    through = [v for v in verdicts if not v.held]
    body = table(verdicts) + f"\n\n{len(verdicts)} scenarios, {len(through)} through."
    print(body)
    if args.write:
        write(body)


if __name__ == "__main__":
    main()
