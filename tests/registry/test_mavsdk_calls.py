"""One gRPC call to mavsdk_server and its errors in words (pure asyncio; no sidecar)."""

from __future__ import annotations

import asyncio
from types import SimpleNamespace

import pytest
from grpclib.const import Status
from grpclib.exceptions import GRPCError, StreamTerminatedError

from gateway.errors import CommandFailed
from gateway.link.contract import ConnectionState
from gateway.link.mavsdk_calls import MavsdkCalls
from gateway.link.mavsdk_rpc import ChannelClosed, MavsdkError


def calls() -> MavsdkCalls:
    host = SimpleNamespace(id="px2", state=ConnectionState.CONNECTING)
    return MavsdkCalls(host, gcs_sysid=245)  # type: ignore[arg-type]


async def test_a_call_cancelled_by_its_closing_channel_is_a_command_failure() -> None:
    """A call whose session was closed under it (the sidecar went down mid-call) is cancelled: the
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


ENDED = (
    "arm on drone 'px2': its mavsdk_server session ended during the call (the gateway restarts it); "
    "the drone is connecting; check it and call again"
)


@pytest.mark.parametrize(
    "error",
    [
        StreamTerminatedError("Connection lost"),
        ChannelClosed("the connection to mavsdk_server was lost (the session ends with it)"),
        ConnectionRefusedError(111, "Connection refused"),
        FileNotFoundError(2, "No such file or directory"),  # the sealed socket's path, gone
    ],
    ids=type,
)
async def test_a_connection_lost_or_refused_mid_call_is_a_command_failure_in_words(error: Exception) -> None:
    async def lost() -> None:
        raise error

    with pytest.raises(CommandFailed) as failed:
        await calls().call("arm", lost())
    assert failed.value.message == ENDED


async def test_a_grpc_status_names_itself() -> None:
    async def unavailable() -> None:
        raise GRPCError(Status.UNAVAILABLE, "down")

    with pytest.raises(CommandFailed) as failed:
        await calls().call("arm", unavailable())
    assert (
        failed.value.message
        == "arm on drone 'px2': mavsdk_server unreachable (UNAVAILABLE); the drone is connecting"
    )


async def test_a_refused_result_carries_its_name_and_text() -> None:
    host = SimpleNamespace(
        id="px2",
        state=ConnectionState.CONNECTED,
        telemetry=SimpleNamespace(status_texts=[], fresh=lambda _name: None),
        rules=SimpleNamespace(on_ground=lambda _telemetry: True),
        initialising=lambda: None,
    )
    mavsdk = MavsdkCalls(host, gcs_sysid=245)  # type: ignore[arg-type]

    async def denied() -> None:
        raise MavsdkError("COMMAND_DENIED", "Command denied", "arm()")

    with pytest.raises(CommandFailed) as failed:
        await mavsdk.call("arm", denied())
    assert failed.value.details["result"] == "COMMAND_DENIED"
    assert failed.value.message.startswith("arm on drone 'px2' failed: Command denied (COMMAND_DENIED)")


async def test_a_slow_call_times_out_in_words() -> None:
    async def never() -> None:
        await asyncio.Event().wait()

    with pytest.raises(CommandFailed, match=r"no answer from its mavsdk_server within 0\.05 s"):
        await calls().call("arm", never(), 0.05)
