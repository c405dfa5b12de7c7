"""Autopilot parameters through MAVSDK's param plugin, with ArduPilot's quirks handled.

* An unknown name gets no reply at all from older ArduPilot (MAVSDK times out after ~3 s) and a
  PARAM_ERROR "does not exist" from newer ones and PX4; both are reported as "unknown parameter", after
  trying the name's other spelling (ArduPilot 4.7 renamed SYSID_THISMAV -> MAV_SYSID,
  SYSID_MYGCS -> MAV_GCS_SYSID, SRn_* -> MAV(n+1)_*).
* Each parameter has its own type; reading with the wrong getter gives WRONG_TYPE, so the type is
  detected once and remembered, and writes use it.
* The full list (~1000+ names) is fetched once, as the vehicle's first session starts (`prefetch`, as a
  ground station does when it connects; else on the first read), and cached with its time; a name not
  in it is refused at once, without asking the autopilot (older ArduPilot does not answer an unknown
  name: MAVSDK would wait ~3 s for nothing). One fetch at a time: a read during the fetch waits for it.
* Neither autopilot refuses a value outside a parameter's range: ArduPilot clamps an integer to its
  type (FENCE_ENABLE is 8-bit: 1000 is stored as 127; through MAVSDK, which casts to the type it
  learnt, as -24) and says nothing. Integers are read back after a
  write; a value that did not stick is put back and refused.
"""

from __future__ import annotations

import asyncio
import logging
import math
import re
import time
from collections.abc import Awaitable, Callable
from typing import Protocol, TypeVar

from gateway.errors import CommandFailed, InvalidArgument
from gateway.link.mavsdk_system import System

log = logging.getLogger(__name__)

PARAM_TIMEOUT_S = 6.0  # MAVSDK gives up on a param after ~3 s
PARAM_LIST_TIMEOUT_S = 60.0
LIST_RETRY_AFTER_S = 60.0  # a vehicle that did not give its list is not asked again before this

INT32_RANGE = (-(2**31), 2**31 - 1)  # MAVSDK's set_param_int carries an int32
#: what the autopilot answers for a name it does not have: nothing (ArduPilot up to 4.6, MAVSDK times
#: out) or PARAM_ERROR (newer ArduPilot)
_NO_SUCH_PARAMETER = ("TIMEOUT", "DOES_NOT_EXIST")

PARAM_NAME = re.compile(r"^[A-Za-z0-9_]{1,16}$")
_RENAMES = {"SYSID_THISMAV": "MAV_SYSID", "SYSID_MYGCS": "MAV_GCS_SYSID"}
_RENAMES.update({new: old for old, new in _RENAMES.items()})

Value = float | int
T = TypeVar("T")


class Call(Protocol):
    """The link's call: ``aw`` awaited within ``timeout_s``, its errors mapped (``what`` names it)."""

    def __call__(self, what: str, aw: Awaitable[T], timeout_s: float, /) -> Awaitable[T]: ...


def param_aliases(name: str) -> list[str]:
    """Other names the same parameter has in other ArduPilot versions (SRn_* <-> MAV(n+1)_*)."""
    out = []
    if name in _RENAMES:
        out.append(_RENAMES[name])
    m = re.match(r"^SR(\d)_(\w+)$", name)
    if m:
        out.append(f"MAV{int(m.group(1)) + 1}_{m.group(2)}")
    m = re.match(r"^MAV(\d)_(\w+)$", name)
    if m and int(m.group(1)) >= 1:
        out.append(f"SR{int(m.group(1)) - 1}_{m.group(2)}")
    return out


def check_param_name(name: object) -> str:
    if not isinstance(name, str) or not PARAM_NAME.match(name):
        raise InvalidArgument(f"parameter name must be 1-16 of A-Z, 0-9, '_'; got {str(name)[:40]!r}")
    return name.upper()


class Parameters:
    """The parameters of one vehicle. ``call(what, awaitable, timeout_s)`` maps MAVSDK errors to
    CommandFailed (with ``result`` in the details); ``system()`` returns the current MAVSDK System."""

    def __init__(self, vehicle_id: str, call: Call, system: Callable[[], System]) -> None:
        self.vehicle_id = vehicle_id
        self._call = call
        self._system = system
        self._cache: dict[str, Value] | None = None
        self._cached_at: float | None = None
        self._list_failed_at: float | None = None
        self._types: dict[str, str] = {}
        self._names: dict[str, str] = {}  # requested name -> the name the vehicle knows
        self._fetching = asyncio.Lock()

    @property
    def list_age_s(self) -> float | None:
        return None if self._cached_at is None else time.monotonic() - self._cached_at

    async def _read(self, system: System, name: str) -> tuple[Value, str] | None:
        """(value, type) or None when the vehicle does not answer (unknown name)."""
        kind = self._types.get(name, "int")
        for k in (kind, "float" if kind == "int" else "int"):
            getter = system.param.get_param_int if k == "int" else system.param.get_param_float
            try:
                value = await self._call(f"read parameter {name}", getter(name), PARAM_TIMEOUT_S)
            except CommandFailed as exc:
                result = exc.details.get("result")
                if result == "WRONG_TYPE":
                    continue
                if result in _NO_SUCH_PARAMETER:
                    return None
                raise
            self._types[name] = k
            return (int(value) if k == "int" else float(value)), k
        return None

    async def get(self, name: str) -> tuple[Value, str]:
        """Value and type ('int' | 'float'); the other ArduPilot spelling is tried when there is one."""
        name = check_param_name(name)
        candidates = [self._names.get(name, name), *param_aliases(name)]
        listed = await self._listed()
        if listed is not None:
            if not any(c in listed for c in candidates):  # the autopilot's own list: no need to ask it
                raise self._unknown(name, f"not among the {len(listed)} parameters it lists")
            candidates.sort(key=lambda c: c not in listed)  # names known to be on the vehicle first
        system = self._system()
        for candidate in dict.fromkeys(candidates):
            got = await self._read(system, candidate)
            if got is not None:
                self._names[name] = candidate
                return got
        raise self._unknown(name, "the vehicle did not answer or said it does not exist")

    def _unknown(self, name: str, why: str) -> CommandFailed:
        alias = param_aliases(name)
        return CommandFailed(
            f"unknown parameter '{name}' on drone '{self.vehicle_id}': {why}"
            + (f"; also tried {', '.join(alias)}" if alias else ""),
            vehicle_id=self.vehicle_id,
            result="UNKNOWN_PARAMETER",
        )

    async def _listed(self) -> dict[str, Value] | None:
        """The autopilot's parameter list, fetched on the first read and kept (an unknown name is then
        refused at once: older ArduPilot does not answer one, and MAVSDK waits ~3 s for nothing); None
        when the list cannot be had (the name is then asked for itself)."""
        if self._cache is None:
            failed = self._list_failed_at
            if failed is not None and time.monotonic() - failed < LIST_RETRY_AFTER_S:
                return None
            try:
                await self.all()
            except CommandFailed:
                self._list_failed_at = time.monotonic()
                return None
        return self._cache

    async def set(self, name: str, value: Value) -> tuple[Value, str]:
        """Write with the vehicle's own type for the parameter; returns (stored value, type)."""
        name = check_param_name(name)
        if not isinstance(value, int | float) or isinstance(value, bool) or not math.isfinite(value):
            raise InvalidArgument(f"parameter value must be a finite number; got {value!r}")
        current, kind = await self.get(name)
        real = self._names.get(name, name)
        system = self._system()
        stored: Value
        if kind == "int":
            if float(value) != int(value):
                raise InvalidArgument(f"parameter {real} is an integer; got {value!r}")
            if not INT32_RANGE[0] <= int(value) <= INT32_RANGE[1]:
                low, high = INT32_RANGE
                raise InvalidArgument(f"parameter {real} is a 32-bit integer ({low}..{high}); got {value!r}")
            stored = int(value)
            await self._write_int(system, real, stored)
            got, _kind = await self._read(system, real) or (stored, kind)
            if got != stored:  # clamped to the parameter's type: put the old value back
                await self._write_int(system, real, int(current))
                raise InvalidArgument(
                    f"parameter {real} cannot hold {stored}: drone '{self.vehicle_id}' stored {got} (the "
                    f"value does not fit its type), so it was set back to {current}; give a value that fits"
                )
        else:
            stored = float(value)
            await self._call(
                f"write parameter {real}", system.param.set_param_float(real, stored), PARAM_TIMEOUT_S
            )
        if self._cache is not None:
            self._cache[real] = stored
        return stored, kind

    async def _write_int(self, system: System, name: str, value: int) -> None:
        await self._call(f"write parameter {name}", system.param.set_param_int(name, value), PARAM_TIMEOUT_S)

    async def prefetch(self) -> None:
        """Fetch the list now if it is not held yet (a vehicle's session starting): a failure is left
        for the first read to meet again."""
        try:
            await self.all()
        except CommandFailed as exc:
            log.info("%s: the parameter list was not fetched at connect: %s", self.vehicle_id, exc.message)

    async def not_fetching(self) -> None:
        """Return once no list is being fetched. MAVSDK's param client answers one request at a time: a
        call that sets a parameter inside MAVSDK (the takeoff altitude) would wait behind a whole list
        (~1000 names, long on a loaded autopilot) and past its own timeout."""
        async with self._fetching:
            return

    async def all(self, max_age_s: float | None = None) -> dict[str, Value]:
        """Every parameter, fetched once and cached; ``max_age_s`` refetches an older copy."""
        async with self._fetching:
            return await self._all(max_age_s)

    async def _all(self, max_age_s: float | None) -> dict[str, Value]:
        age = self.list_age_s
        if self._cache is not None and (max_age_s is None or (age is not None and age <= max_age_s)):
            return dict(self._cache)
        system = self._system()
        allp = await self._call("list parameters", system.param.get_all_params(), PARAM_LIST_TIMEOUT_S)
        params: dict[str, Value] = {}
        for p in allp.int_params:
            params[p.name] = int(p.value)
            self._types[p.name] = "int"
        for p in allp.float_params:
            params[p.name] = float(p.value)
            self._types[p.name] = "float"
        self._cache = params
        self._cached_at = time.monotonic()
        return dict(params)
