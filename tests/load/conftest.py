"""The load tests' integration stack: a simulator, real sidecars and the gateway in its own
``fleet-gateway serve`` process, as in production (many clients in the test's process must not share the
gateway's interpreter lock: starved of it, the gateway misses the drones' heartbeats)."""

from collections.abc import AsyncIterator

import pytest
import pytest_asyncio

from tests.mcp.conftest import Stack, gateway_stack


@pytest_asyncio.fixture(scope="module", loop_scope="module")
async def stack(
    request: pytest.FixtureRequest, tmp_path_factory: pytest.TempPathFactory
) -> AsyncIterator[Stack]:
    """The module's gateway process over ``DRONES`` simulated drones (a module-level constant, default 4)."""
    count = getattr(request.module, "DRONES", 4)
    async with gateway_stack(tmp_path_factory.mktemp("load"), count=count, own_process=True) as s:
        yield s
