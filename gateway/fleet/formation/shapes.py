"""The formations a plan can lay out and the tolerance its checks share, below both the planner
(`formation.py`) and its numpy geometry (`formation_geometry.py`) so neither imports the other for them."""

from __future__ import annotations

FORMATIONS = ("line", "column", "wedge", "grid", "circle")
TOL_M = 1e-6
