"""The real Gateway (Commander, policy, operations, store) over two fake drones, for the Commander's
unit tests."""

from __future__ import annotations

from collections.abc import AsyncIterator
from pathlib import Path

import pytest

from gateway.runtime import Gateway
from tests.fakes import fake_gateway, spread, unit_settings


@pytest.fixture
async def gateway(tmp_path: Path) -> AsyncIterator[Gateway]:
    async with fake_gateway(unit_settings(tmp_path, mcp_wait_cap_s=10.0), spread(2)) as gw:
        yield gw
