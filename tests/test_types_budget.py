"""The budget of ``Any`` in gateway/: counted as ``grep -rw Any gateway --include=*.py | grep -v import``
counts it, on the code of each line (a line's ``# Any: <library> ...`` comment, which says why the library
forces it, is not counted), and every ``Any`` left carries that comment on its line or just above: the
project types what it owns (its JSON bodies, kept writes, results), and ``Any`` is left only where a
library's own signature leaves no other type."""

from __future__ import annotations

import re
from pathlib import Path

GATEWAY = Path(__file__).resolve().parents[1] / "gateway"

#: the most ``Any`` gateway/ may hold (lower it when you type one away); 37 since the cluster's forwarded
#: calls carry JSON (arguments and results) and a pymavlink link's options are a TypedDict; 36 since the
#: link to mavsdk_server holds one for protobuf's untyped messages instead of mavsdk_grpc's wrappers
MAX_ANY = 36

_ANY = re.compile(r"\bAny\b")
_WHY = "# Any:"


def _code(line: str) -> str:
    """The line without its ``# Any:`` comment."""
    return line.split(_WHY, 1)[0]


def _lines() -> list[tuple[str, int, str, str]]:
    """(module, line number, line, line above) of every line of gateway/ the count reads."""
    found = []
    for path in sorted(GATEWAY.rglob("*.py")):
        module = path.relative_to(GATEWAY).as_posix()
        lines = path.read_text(encoding="utf-8").splitlines()
        for number, line in enumerate(lines, start=1):
            if "import" not in line:
                found.append((module, number, line, lines[number - 2] if number > 1 else ""))
    return found


def test_gateway_holds_no_more_any_than_its_budget() -> None:
    count = sum(len(_ANY.findall(_code(line))) for _module, _number, line, _above in _lines())
    assert count <= MAX_ANY, f"gateway/ holds {count} Any (budget {MAX_ANY}): type the new ones"


def test_every_any_left_says_which_library_forces_it() -> None:
    bare = [
        f"gateway/{module}:{number}: {line.strip()}"
        for module, number, line, above in _lines()
        if _ANY.search(_code(line)) and _WHY not in line and _WHY not in above
    ]
    assert bare == [], "an Any without its '# Any: <library> ...' comment:\n" + "\n".join(bare)
