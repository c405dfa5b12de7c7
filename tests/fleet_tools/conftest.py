"""A real gateway (REST + /mcp, SQLite file, one mavsdk_server per drone) over simulated drones on
loopback, for the fleet tools' integration tests; the MCP area's stack, with operator locks the tests set."""

from __future__ import annotations

from collections.abc import AsyncIterator

import pytest
import pytest_asyncio

from gateway.fleet.policy.operator_locks import LockBook
from tests.mcp.conftest import Stack, gateway_stack


@pytest_asyncio.fixture(scope="module", loop_scope="module")
async def fleet_stack(
    request: pytest.FixtureRequest, tmp_path_factory: pytest.TempPathFactory
) -> AsyncIterator[tuple[Stack, LockBook]]:
    """``DRONES`` (module constant) simulated drones 5 m apart behind one gateway, and its lock book."""
    count = getattr(request.module, "DRONES", 4)
    async with gateway_stack(tmp_path_factory.mktemp("fleet"), count=count) as stack:
        gateway = stack.app.state.gateway
        if not isinstance(gateway.locks, LockBook):
            assert getattr(gateway, "safety", None) is None, "the policy was built before the locks were set"
            gateway.locks = LockBook()
        yield stack, gateway.locks
        if stack.figures:
            print(f"\nfleet figures ({request.module.__name__}): {stack.figures}")
