"""bench/grpc_link.py's own logic, without a SITL: the streams it opens are the ones the telemetry feed
subscribes on ArduPilot, each is the RPC its mavsdk_grpc wrapper calls, the clients load the gateway's
plugins, and a bad option or a missing piece gets one line."""

from __future__ import annotations

import asyncio
import importlib
import inspect
import sys
from collections.abc import AsyncIterator, Callable
from pathlib import Path

import pytest

BENCH = Path(__file__).resolve().parents[1] / "bench"
sys.path.insert(0, str(BENCH))

import grpc_link  # noqa: E402

from gateway.link import mavsdk_system  # noqa: E402
from gateway.link.telemetry import TelemetryCache  # noqa: E402
from gateway.link.telemetry_feed import TelemetryFeed  # noqa: E402

ALL_STREAMS = grpc_link.STREAMS + grpc_link.SESSION_STREAMS


class _Plugin:
    """A plugin whose every stream is recorded when the feed looks it up, and never yields."""

    def __init__(self, name: str, seen: list[tuple[str, str, None]]) -> None:
        self._name, self._seen = name, seen

    def __getattr__(self, method: str) -> Callable[[], AsyncIterator[object]]:
        self._seen.append((self._name, method, None))

        async def silent() -> AsyncIterator[object]:
            await asyncio.Event().wait()
            yield None

        return silent


class _System:
    def __init__(self) -> None:
        self.seen: list[tuple[str, str, None]] = []

    def __getattr__(self, plugin: str) -> _Plugin:
        return _Plugin(plugin, self.seen)


async def test_the_streams_are_those_the_telemetry_feed_subscribes_on_ardupilot() -> None:
    system = _System()
    # ArduPilot: the link names the mode from the HEARTBEAT, so the feed never subscribes flight_mode
    feed = TelemetryFeed("d1", system, TelemetryCache(), use_mavsdk_flight_mode=lambda: False)  # type: ignore[arg-type]
    feed.start()
    try:
        await asyncio.sleep(0.05)  # the flight mode loop has asked and decided
    finally:
        await feed.stop()
    assert system.seen == list(grpc_link.STREAMS), (
        "gateway/link/telemetry_feed.py subscribes other streams than bench/grpc_link.py opens: "
        "change STREAMS there"
    )


@pytest.mark.parametrize("stream", ALL_STREAMS, ids=grpc_link.label)
def test_each_stream_is_the_streaming_rpc_its_wrapper_calls(stream: grpc_link.Stream) -> None:
    plugin, method, argument = stream
    module = importlib.import_module(f"mavsdk_grpc.{plugin}_pb2")
    rpc = grpc_link.stream_rpc(method)
    path, request, reply, streaming = grpc_link.resolve(module, plugin, rpc)
    assert streaming
    assert path == f"/mavsdk.rpc.{plugin}.{grpc_link.camel(plugin)}Service/{rpc}"
    wrapper = getattr(importlib.import_module(f"mavsdk_grpc.{plugin}"), grpc_link.camel(plugin))
    assert f"self._stub.{rpc}(" in inspect.getsource(getattr(wrapper, method))
    message = grpc_link.request_of(request, argument)
    assert isinstance(message, request)
    if argument is not None:
        assert [value for _field, value in message.ListFields()] == [argument]
    assert reply.__name__.endswith("Response")


def test_the_unary_call_answers_the_takeoff_altitude() -> None:
    plugin, method = grpc_link.UNARY
    module = importlib.import_module(f"mavsdk_grpc.{plugin}_pb2")
    path, _request, reply, streaming = grpc_link.resolve(module, plugin, grpc_link.camel(method))
    assert not streaming
    assert path == "/mavsdk.rpc.action.ActionService/GetTakeoffAltitude"
    assert "altitude" in reply.DESCRIPTOR.fields_by_name
    assert hasattr(getattr(importlib.import_module(f"mavsdk_grpc.{plugin}"), grpc_link.camel(plugin)), method)


def test_the_clients_load_the_gateways_plugins() -> None:
    assert grpc_link.PLUGINS == mavsdk_system.PLUGINS


def test_the_options_make_a_plan_and_bad_ones_get_one_line(capsys: pytest.CaptureFixture[str]) -> None:
    plan = grpc_link.parse([])
    assert plan == grpc_link.Plan(tuple(grpc_link.KINDS), 60.0, 1, False)
    assert plan.streams == grpc_link.STREAMS
    assert grpc_link.parse(["--full"]).seconds == 180.0
    assert grpc_link.parse(["--session"]).streams == ALL_STREAMS
    for argv, line in [
        (["--seconds", "0"], "--seconds: 0 is not a window"),
        (["--seconds", "nan"], "--seconds: nan is not a window"),
        (["--channels", "0"], "--channels: 0 is not a number of channels (accepted: 1 to 254)"),
        (["--channels", "255"], "--channels: 255 is not a number of channels"),
        (["--clients", "grpclib-pb2,grpcio"], "--clients: grpcio unknown (accepted: a comma-separated list"),
    ]:
        with pytest.raises(SystemExit):
            grpc_link.parse(argv)
        assert line in capsys.readouterr().err


def test_a_missing_grpclib_or_autopilot_is_said_in_one_line() -> None:
    no_sitl = lambda: "real autopilot not available: ARDUPILOT_SITL unset"  # noqa: E731
    said = grpc_link.missing_pieces(no_sitl, installed=lambda name: name != "grpclib")
    assert said is not None and "grpclib is not installed" in said and "make install" in said
    assert grpc_link.missing_pieces(no_sitl, installed=lambda _name: True) == no_sitl()
    assert grpc_link.missing_pieces(lambda: None, installed=lambda _name: True) is None
