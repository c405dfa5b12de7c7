"""The emergency stop under each fault of the cluster's engines and nodes (tests/cluster/fault_matrix.py:
the cases, their checks, and what they measure): NATS killed and frozen, PostgreSQL killed and frozen, a
slow database, one node frozen, killed, cut from NATS and cut from PostgreSQL, the stop sent through each
node that survives the fault. One cluster for every case (module scope): each case leaves it recovered,
and the next one starts by starting a killed node again, unlocking the fleet and waiting until the drones
are on the ground and spread two and two."""

from __future__ import annotations

from collections.abc import AsyncIterator

import pytest
import pytest_asyncio

from tests.cluster.fault_matrix import CASES, Rig, rig, run_case
from tests.cluster.harness import missing_engines
from tests.helpers.timing import scaled
from tests.persist.pg import find_pg_bin

#: one case's bound: the cluster's start (the first case), the preparation (the drones on the ground, the
#: fleet unlocked, spread two and two), the case and the recovery each wait on deadlines of their own
CASE_LIMIT_S = 480

pytestmark = [
    pytest.mark.asyncio(loop_scope="module"),
    pytest.mark.timeout(scaled(CASE_LIMIT_S)),
    pytest.mark.skipif(missing_engines() is not None, reason=str(missing_engines())),
    pytest.mark.skipif(
        not (find_pg_bin("initdb") and find_pg_bin("postgres")),
        reason="the matrix stops and starts its own PostgreSQL server: its binaries are not installed",
    ),
]


@pytest_asyncio.fixture(scope="module", loop_scope="module")
async def matrix_rig(tmp_path_factory: pytest.TempPathFactory) -> AsyncIterator[Rig]:
    async with rig(tmp_path_factory.mktemp("matrix")) as r:
        yield r


@pytest.mark.parametrize(("fault", "via"), [pytest.param(f, v, id=f"{f}-via-{v}") for f, v in CASES])
async def test_the_emergency_stop_under_each_fault(matrix_rig: Rig, fault: str, via: str) -> None:
    figures = await run_case(matrix_rig, fault, via)
    print(f"{fault} via {via}: " + ", ".join(f"{k} {v}" for k, v in figures.items()))
