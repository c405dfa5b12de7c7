"""Fixtures of the agent host tests: a real toy MCP server and a scripted OpenAI-compatible endpoint."""

from __future__ import annotations

from collections.abc import Callable, Iterator

import pytest

from bench.agent_harness.scripted import Reply, ScriptedModelServer
from tests.agent.toy_mcp import ToyServer


@pytest.fixture
def toy() -> Iterator[ToyServer]:
    with ToyServer() as server:
        yield server


@pytest.fixture
def scripted() -> Iterator[Callable[..., ScriptedModelServer]]:
    """Factory: ``scripted([replies...], repeat_last=False)`` starts a scripted endpoint; all are stopped."""
    started: list[ScriptedModelServer] = []

    def make(replies: list[Reply], *, repeat_last: bool = False) -> ScriptedModelServer:
        server = ScriptedModelServer(list(replies), repeat_last=repeat_last).start()
        started.append(server)
        return server

    try:
        yield make
    finally:
        for server in started:
            server.stop()
