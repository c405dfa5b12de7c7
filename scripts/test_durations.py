"""Write tests/durations.json (seconds per test file) from a pytest JUnit XML report.

``make test`` hands the test files to its workers longest first (tests/conftest.py reads this file), so
that no long file starts last while the other worker idles. Refresh it after a full run::

    .venv/bin/python -m pytest -n 2 --dist loadfile --junitxml=/tmp/junit.xml
    .venv/bin/python scripts/test_durations.py /tmp/junit.xml

A stale table only makes the order less good; files it does not name run after the ones it does. After
running some files only, ``--merge`` replaces their entries and keeps every other file's::

    .venv/bin/python scripts/test_durations.py --merge /tmp/junit-some-files.xml
"""

from __future__ import annotations

import json
import sys
import xml.etree.ElementTree as ET
from collections import defaultdict
from pathlib import Path

TABLE = Path(__file__).resolve().parent.parent / "tests" / "durations.json"


def seconds_per_file(report: Path) -> dict[str, float]:
    """Each test file's summed test time (setup, call and teardown), from a JUnit XML report."""
    totals: dict[str, float] = defaultdict(float)
    for case in ET.parse(report).getroot().iter("testcase"):
        module = case.get("classname", "").split(".")
        # pytest names a test's class path "tests.real.test_x" or "tests.real.test_x.TestClass"
        while module and not module[-1].startswith("test_"):
            module.pop()
        if module:
            totals["/".join(module) + ".py"] += float(case.get("time", "0"))
    return {name: round(total, 1) for name, total in sorted(totals.items())}


def main(argv: list[str]) -> int:
    args = argv[1:]
    merge = "--merge" in args
    reports = [a for a in args if a != "--merge"]
    if len(reports) != 1:
        print("usage: scripts/test_durations.py [--merge] JUNIT_XML", file=sys.stderr)
        return 2
    measured = seconds_per_file(Path(reports[0]))
    table = json.loads(TABLE.read_text()) if merge and TABLE.exists() else {}
    table = dict(sorted({**table, **measured}.items()))
    TABLE.write_text(json.dumps(table, indent=1) + "\n")
    print(f"{TABLE}: {len(table)} files ({len(measured)} measured), {sum(table.values()):.0f} s in all")
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv))
