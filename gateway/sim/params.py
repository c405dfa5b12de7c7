"""ArduCopter parameter table: the full default list of a fresh SITL copter, typed like ArduPilot's.

ArduPilot keeps every parameter in its own C type and answers with that type whatever type a GCS sent;
values travel as C-cast floats (no byte-wise encoding). Firmware 4.7 renamed a few parameters
(``SYSID_THISMAV`` -> ``MAV_SYSID``, ``SYSID_MYGCS`` -> ``MAV_GCS_SYSID``, ``SRn_*`` -> ``MAV(n+1)_*``);
with ``firmware="4.6"`` the table uses the old names.
"""

from __future__ import annotations

import json
import math
import re
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from importlib import resources

# MAV_PARAM_TYPE values used by ArduPilot.
INT8, INT16, INT32, REAL32 = 2, 4, 6, 9
_INT_RANGES = {INT8: (-128, 127), INT16: (-32768, 32767), INT32: (-(2**31), 2**31 - 1)}

FIRMWARES = ("4.6", "4.7")


@dataclass
class Param:
    name: str
    value: float
    type: int
    index: int


def _rename_for_46(name: str) -> str:
    if name == "MAV_SYSID":
        return "SYSID_THISMAV"
    if name == "MAV_GCS_SYSID":
        return "SYSID_MYGCS"
    match = re.fullmatch(r"MAV(\d)_(.+)", name)
    if match:
        return f"SR{int(match.group(1)) - 1}_{match.group(2)}"
    return name


def load_defaults() -> list[tuple[str, float, int]]:
    """The 1354 (name, value, type) of a fresh ArduCopter 4.7 SITL, in ArduPilot's index order."""
    raw = json.loads(resources.files("gateway.sim").joinpath("data/params_default.json").read_text())
    return [tuple(raw[str(i)]) for i in range(len(raw))]  # type: ignore[misc]


_DEFAULTS_CACHE: list[tuple[str, float, int]] | None = None


def _defaults() -> list[tuple[str, float, int]]:
    global _DEFAULTS_CACHE
    if _DEFAULTS_CACHE is None:
        _DEFAULTS_CACHE = load_defaults()
    return _DEFAULTS_CACHE


class ParamError(ValueError):
    """A parameter name or value the table refuses."""


class ParamTable:
    """All parameters of one vehicle; lookups by name (as the firmware spells it) or index."""

    def __init__(self, firmware: str = "4.7", overrides: dict[str, float] | None = None) -> None:
        if firmware not in FIRMWARES:
            raise ParamError(f"unknown firmware {firmware!r}; choose one of {', '.join(FIRMWARES)}")
        self.firmware = firmware
        self._by_index: list[Param] = []
        self._by_name: dict[str, Param] = {}
        for index, (name, value, ptype) in enumerate(_defaults()):
            shown = _rename_for_46(name) if firmware == "4.6" else name
            param = Param(shown, float(value), int(ptype), index)
            self._by_index.append(param)
            self._by_name[shown] = param
        self.on_change: list[Callable[[Param], None]] = []
        for name, value in (overrides or {}).items():
            self.set(self.canonical(name), value, notify=False)

    def __len__(self) -> int:
        return len(self._by_index)

    def __iter__(self) -> Iterator[Param]:
        return iter(self._by_index)

    def canonical(self, name_47: str) -> str:
        """The name this firmware uses for a parameter known by its 4.7 name."""
        return _rename_for_46(name_47) if self.firmware == "4.6" else name_47

    def find(self, name: str) -> Param | None:
        return self._by_name.get(name)

    def by_index(self, index: int) -> Param | None:
        if 0 <= index < len(self._by_index):
            return self._by_index[index]
        return None

    def get(self, name_47: str) -> float:
        """Value of a parameter given by its 4.7 name (translated for 4.6)."""
        return self._by_name[self.canonical(name_47)].value

    def set(self, name: str, value: float, *, notify: bool = True) -> Param:
        """Store a value as the parameter's own type would (C cast); raises ParamError if unknown/invalid."""
        param = self._by_name.get(name)
        if param is None:
            raise ParamError(f"unknown parameter {name!r}")
        if not math.isfinite(value):
            raise ParamError(f"parameter {name} must be finite, got {value!r}")
        if param.type in _INT_RANGES:
            lo, hi = _INT_RANGES[param.type]
            stored = float(max(lo, min(hi, round(value))))
        else:
            stored = _as_float32(value)
        param.value = stored
        if notify:
            for callback in self.on_change:
                callback(param)
        return param


def _as_float32(value: float) -> float:
    import struct

    return struct.unpack("<f", struct.pack("<f", value))[0]
