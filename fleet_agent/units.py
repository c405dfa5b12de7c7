"""Lengths with their unit: the model writes the unit the request used, the host converts."""

from __future__ import annotations

from enum import StrEnum


class Unit(StrEnum):
    m, ft, km, mi, yd, nmi, cm = "m", "ft", "km", "mi", "yd", "nmi", "cm"


METRES_PER = {Unit.m: 1.0, Unit.ft: 0.3048, Unit.km: 1000.0, Unit.mi: 1609.344, Unit.yd: 0.9144,
              Unit.nmi: 1852.0, Unit.cm: 0.01}  # fmt: skip


def to_metres(value: float, unit: Unit | str) -> float:
    """``value`` in ``unit`` as metres (rounded to the centimetre)."""
    return round(value * METRES_PER[Unit(unit)], 2)
