"""The emergency stop under each cluster fault, measured on this machine: two nodes, four simulated drones in
the air (two owned by each), one fault at a time (tests/cluster/fault_matrix.py: NATS killed and frozen,
PostgreSQL killed and frozen, a slow database, one node frozen, killed, cut from NATS, cut from
PostgreSQL), the stop sent through each node that survives the fault, one case each. Per case: how long
an agent's move forwarded to the other node's drone took to be answered (run or refused), how long after
the emergency stop (land) every drone was in LAND as the simulator has it, when the stop answered and
with what outcomes, and how long after recovery every drone was ready under exactly one sidecar. The
same checks as the test hold (a failed check stops the run).

Run: .venv/bin/python bench/cluster_matrix.py [--write] [fault ...]
"""

from __future__ import annotations

import asyncio
import os
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
sys.path.insert(0, str(Path(__file__).resolve().parent))

import common

from tests.cluster.fault_matrix import CASES, MATRIX, rig, run_case
from tests.cluster.harness import missing_engines
from tests.persist.pg import find_pg_bin


def _outcomes(figures: dict[str, Any]) -> str:
    counts: dict[str, int] = {}
    for outcome in figures.get("outcomes", {}).values():
        counts[outcome] = counts.get(outcome, 0) + 1
    return ", ".join(f"{n} {k}" for k, n in sorted(counts.items()))


async def run_all(workdir: Path, cases: list[tuple[str, str]]) -> dict[tuple[str, str], dict[str, Any]]:
    """The cases one after another on one cluster, as the test runs them."""
    measured = {}
    async with rig(workdir) as r:
        for fault, via in cases:
            began = time.monotonic()
            measured[fault, via] = figures = await run_case(r, fault, via)
            figures["case_s"] = round(time.monotonic() - began, 1)
            print(f"{fault} via {via}: {figures}, load {os.getloadavg()[0]:.1f}", flush=True)
    return measured


def main() -> int:
    p = common.parser(__doc__.splitlines()[0])
    p.add_argument("faults", nargs="*", help=f"the faults to run (default: all): {', '.join(MATRIX)}")
    args = p.parse_args()
    unknown = [f for f in args.faults if f not in MATRIX]
    if unknown:
        p.error(f"faults: each one of {', '.join(MATRIX)}; got {', '.join(unknown)}")
    why = missing_engines() or (
        None if find_pg_bin("postgres") else "PostgreSQL server binaries are not installed"
    )
    if why:
        print(f"skipped: {why}")
        return 0
    info = common.machine()
    print(common.machine_line(info))
    with tempfile.TemporaryDirectory(prefix="cluster-matrix-") as tmp:
        began = time.monotonic()
        measured = asyncio.run(run_all(Path(tmp), [c for c in CASES if c[0] in (args.faults or MATRIX)]))
        took = time.monotonic() - began
    rows = []
    for (fault, _via), figures in measured.items():
        late = figures.get("frozen_node_drones_land_after_thaw_s")
        rows.append(
            [
                fault,
                figures["via"],
                f"{figures['move_answer_s']:.2f} s ({figures['move']})",
                f"{figures['stop_to_land_s']:.2f} s"
                + (f" (node-a's: {late:.1f} s after it runs)" if late else ""),
                f"{figures['stop_answer_s']:.2f} s",
                _outcomes(figures),
                f"{figures['ready_after_recovery_s']:.1f} s",
            ]
        )
    body = common.table(
        [
            "fault",
            "stop through",
            "forwarded move answered",
            "stop -> every drone in LAND",
            "stop answered",
            "outcomes",
            "recovery -> every drone ready, one sidecar each",
        ],
        rows,
    )
    print(body)
    print(
        f"{len(measured)} cases in {took / 60:.1f} min (cluster start included); load average now "
        f"{os.getloadavg()[0]:.1f}"
    )
    if args.write:
        common.write_section("cluster-matrix", "Emergency stop under cluster faults", body, info)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
