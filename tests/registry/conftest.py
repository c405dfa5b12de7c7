"""Fixtures of the registry tests: a real SQLite store per test, registries that are always stopped."""

from __future__ import annotations

import asyncio
from collections.abc import AsyncIterator, Callable

import pytest

from gateway.config import Settings
from gateway.fleet.vehicles.registry import Registry
from tests.helpers.timing import scaled
from tests.registry.procs import mavsdk_servers_of

WAIT_S = scaled(60.0)  # generous: waiting is not asserting a duration


def fast_settings(**overrides: object) -> Settings:
    base: dict[str, object] = {
        "sidecar_backoff_initial_s": 0.2,
        "sidecar_backoff_max_s": 1.0,
        "sidecar_max_restarts": 3,
        "link_lost_after_s": 2.0,
        "track_flush_s": 0.5,
    }
    base.update(overrides)
    return Settings(**base)  # type: ignore[arg-type]


@pytest.fixture
async def registries() -> AsyncIterator[list[Registry]]:
    """Append every Registry a test builds; all are stopped at the end, and no sidecar may remain."""
    made: list[Registry] = []
    try:
        yield made
    finally:
        for registry in made:
            await registry.stop()
    assert mavsdk_servers_of() == [], "a mavsdk_server survived Registry.stop()"


async def wait_until(
    predicate: Callable[[], bool], within_s: float = WAIT_S, what: str = "condition"
) -> None:
    loop = asyncio.get_running_loop()
    deadline = loop.time() + within_s
    while not predicate():
        if loop.time() > deadline:
            raise AssertionError(f"{what} not reached within {within_s:g} s")
        await asyncio.sleep(0.05)
