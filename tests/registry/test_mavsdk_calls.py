"""One gRPC call to mavsdk_server and its errors in words (pure asyncio; no sidecar)."""

from __future__ import annotations

import asyncio
from types import SimpleNamespace

import pytest

from gateway.errors import CommandFailed
from gateway.link.contract import ConnectionState
from gateway.link.mavsdk_calls import MavsdkCalls


def calls() -> MavsdkCalls:
    host = SimpleNamespace(id="px2", state=ConnectionState.CONNECTING)
    return MavsdkCalls(host, gcs_sysid=245)  # type: ignore[arg-type]


async def test_a_call_cancelled_by_its_closing_channel_is_a_command_failure() -> None:
    """grpc.aio cancels a call whose channel closed under it (the sidecar went down mid-call): the
    caller hears that in words, never a bare CancelledError that would end its request."""

    async def cut_off() -> None:
        raise asyncio.CancelledError()

    with pytest.raises(CommandFailed) as failed:
        await calls().call("arm", cut_off())
    assert failed.value.message == (
        "arm on drone 'px2': its mavsdk_server session ended during the call (the gateway restarts it); "
        "the drone is connecting; check it and call again"
    )


async def test_cancelling_the_caller_still_cancels_it() -> None:
    started = asyncio.Event()

    async def slow() -> None:
        started.set()
        await asyncio.sleep(60)

    task = asyncio.create_task(calls().call("arm", slow()))
    await started.wait()
    task.cancel()
    with pytest.raises(asyncio.CancelledError):
        await task
