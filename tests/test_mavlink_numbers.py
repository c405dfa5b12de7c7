"""MAVLink numbers written in gateway/ are pymavlink's. A module the plain start loads cannot import
pymavlink (tests/test_lean_start.py: its dialect costs memory on every gateway), so it writes the few
numbers it sends as constants named as pymavlink names them (``MAV_CMD_DO_SET_MODE = 176``); this test
reads every such constant and checks it against pymavlink's value of that name. Modules that may load
pymavlink (the cluster's stop link) use its names directly."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

GATEWAY = Path(__file__).resolve().parents[1] / "gateway"
#: ``MAV_... = <number>`` at the start of a line (a module's constant)
_CONSTANT = re.compile(r"^(MAV_[A-Z0-9_]+)\s*=\s*(\d+)\s*(?:#.*)?$", re.MULTILINE)


def _constants() -> list[tuple[str, str, int]]:
    found = []
    for path in sorted(GATEWAY.rglob("*.py")):
        module = path.relative_to(GATEWAY).as_posix()
        for match in _CONSTANT.finditer(path.read_text(encoding="utf-8")):
            found.append((module, match.group(1), int(match.group(2))))
    return found


def test_the_scan_finds_the_constants_it_checks() -> None:
    names = {name for _module, name, _value in _constants()}
    assert {"MAV_CMD_DO_SET_MODE", "MAV_CMD_NAV_WAYPOINT", "MAV_FRAME_GLOBAL_RELATIVE_ALT"} <= names


@pytest.mark.parametrize(("module", "name", "value"), _constants())
def test_a_mavlink_constant_is_pymavlinks_value_of_its_name(module: str, name: str, value: int) -> None:
    from pymavlink.dialects.v20 import ardupilotmega as mavlink

    assert hasattr(mavlink, name), f"gateway/{module}: {name} is not a name pymavlink knows"
    assert getattr(mavlink, name) == value, (
        f"gateway/{module}: {name} = {value}, but pymavlink's {name} is {getattr(mavlink, name)}"
    )
