"""MAVSDK's plugins over grpclib: the calls mavsdk_grpc's wrappers offer, made from its ``*_pb2`` modules.

mavsdk_grpc's plugin wrappers (``action.py``, ``telemetry.py``, ...) import their ``*_pb2_grpc`` modules,
which import grpcio: its core library is the larger part of a link's memory (``bench/grpc_link.py``:
grpcio with the wrappers 52 MiB RSS, grpclib with the ``*_pb2`` messages 37 MiB, same streams). Here a
plugin is read from its service's descriptor instead, under the wrapper's names: the unary RPC
``GetVersion`` is ``get_version(...)``, the stream ``SubscribePosition`` is ``position(...)``; positional
arguments fill the request's fields in their order, as the wrapper's do.

What a call gives back follows the wrapper: a reply's ``<plugin>_result`` other than SUCCESS raises
`MavsdkError` (the result's name as the wrapper names it, and its text); else the one other field of
the reply (``None`` when there is none, the reply itself when there are several). Stream items are the
reply's one field. Messages are the ``*_pb2`` ones (their fields are the wrappers' snake_case names);
an enum comes as `Named` (``.name`` as the wrapper's enum names it: ``FIX_3D``, not ``FIX_TYPE_FIX_3D``),
also inside a message (`Reply` wraps messages that hold enums; the others come as they are).
"""

from __future__ import annotations

import re
import types
from collections.abc import AsyncIterator, Awaitable, Callable, Sequence
from functools import cache
from typing import Any, NamedTuple

from grpclib.client import Channel, UnaryStreamMethod, UnaryUnaryMethod
from grpclib.exceptions import StreamTerminatedError

#: a protobuf message, message class, descriptor or field value
Message = Any  # Any: protobuf, its generated classes and descriptors are untyped


class MavsdkError(Exception):
    """A MAVSDK call answered with a result other than SUCCESS (the wrappers' ``ActionError``,
    ``ParamError`` ...): ``result`` is its name (``WRONG_TYPE``), ``result_str`` MAVSDK's words."""

    def __init__(self, result: str, result_str: str, origin: str) -> None:
        super().__init__(result, result_str, origin)
        self.result = result
        self.result_str = result_str
        self.origin = origin

    def __str__(self) -> str:
        return f"{self.result}: '{self.result_str}'; origin: {self.origin}"


class Named(NamedTuple):
    """An enum value, named as mavsdk_grpc's wrapper enums name it."""

    name: str
    value: int

    def __str__(self) -> str:
        return self.name


class ChannelClosed(ConnectionError):
    """A call on a session whose channel is closed or whose connection was lost (never reconnected)."""


def camel(name: str) -> str:
    """``gps_info`` -> ``GpsInfo``."""
    return "".join(part[:1].upper() + part[1:] for part in name.split("_"))


def _upper_snake(name: str) -> str:
    return re.sub(r"(?<!^)(?=[A-Z])", "_", name).upper()


@cache
def _enum_names(enum: Message) -> dict[int, Named]:
    """An enum's values by number, named without the prefix protobuf's style puts before them (the
    enum's own name: ``FIX_TYPE_``), as the wrappers name them."""
    prefix = _upper_snake(enum.name) + "_"
    return {v.number: Named(v.name.removeprefix(prefix), v.number) for v in enum.values}


def named(enum: Message, number: int) -> Named:
    """The `Named` value ``number`` of the enum descriptor ``enum`` (an unknown number: its digits)."""
    found = _enum_names(enum).get(number)
    return found if found is not None else Named(str(number), number)


@cache
def _holds_enum(message: Message) -> bool:
    """Whether a message type has an enum field, at any depth."""
    return any(
        f.enum_type is not None or (f.message_type is not None and _holds_enum(f.message_type))
        for f in message.fields
    )


def _is_repeated(field: Message) -> bool:
    return bool(field.is_repeated)


def convert(field: Message, value: Message) -> Message:
    """A field's value as the gateway reads it: enums `Named`, messages holding enums as `Reply`,
    repeated fields as lists; everything else as protobuf gives it."""
    if field.enum_type is not None:
        enum = field.enum_type
        return [named(enum, v) for v in value] if _is_repeated(field) else named(enum, value)
    if field.message_type is not None and _holds_enum(field.message_type):
        return [Reply(v) for v in value] if _is_repeated(field) else Reply(value)
    return list(value) if _is_repeated(field) else value


class Reply:
    """A ``*_pb2`` message whose enum fields read as `Named` (its other fields as they are). Its one
    attribute of its own, ``_pb_message``, has a name no MAVSDK field has (events' Event has a field
    named ``message``)."""

    __slots__ = ("_pb_message",)

    def __init__(self, message: Message) -> None:
        self._pb_message = message

    def __getattr__(self, name: str) -> Message:
        message = self._pb_message
        field = message.DESCRIPTOR.fields_by_name.get(name)
        if field is None:
            raise AttributeError(f"{type(message).__name__} has no field {name!r}")
        return convert(field, getattr(message, name))

    def __repr__(self) -> str:
        return f"Reply({self._pb_message!r})"


def positional(cls: Message) -> Callable[..., Message]:
    """A constructor of the message ``cls`` taking its fields in their order, as the wrapper's class
    does (``MavlinkMessage("COMMAND_LONG", 245, 190, 1, 1, "{...}")``)."""
    names = [f.name for f in cls.DESCRIPTOR.fields]

    def make(*args: object) -> Message:
        if len(args) > len(names):
            raise TypeError(
                f"{cls.__name__} takes {len(names)} fields ({', '.join(names)}), given {len(args)}"
            )
        return cls(**dict(zip(names, args, strict=False)))

    make.__name__ = cls.__name__
    return make


class _Rpc(NamedTuple):
    path: str
    request: Message
    reply: Message
    streaming: bool
    fields: tuple[str, ...]  # the request's, in order
    result: str | None  # the reply's <plugin>_result field
    success: int  # its SUCCESS number
    values: tuple[Message, ...]  # the reply's other fields


@cache
def _rpcs(module: types.ModuleType, plugin: str) -> dict[str, _Rpc]:
    """A plugin's RPCs by the wrapper's method name, read from its ``*_pb2`` module."""
    service = module.DESCRIPTOR.services_by_name[camel(plugin) + "Service"]
    out: dict[str, _Rpc] = {}
    for method in service.methods:
        reply_type = method.output_type
        result_field = next((f for f in reply_type.fields if f.name == f"{plugin}_result"), None)
        success = 0
        if result_field is not None:
            result_enum = result_field.message_type.fields_by_name["result"].enum_type
            success = result_enum.values_by_name["RESULT_SUCCESS"].number
        name = method.name
        if method.server_streaming:
            name = name.removeprefix("Subscribe")
        out[_upper_snake(name).lower()] = _Rpc(
            f"/{service.full_name}/{method.name}",
            getattr(module, method.input_type.name),
            getattr(module, reply_type.name),
            bool(method.server_streaming),
            tuple(f.name for f in method.input_type.fields),
            None if result_field is None else result_field.name,
            success,
            tuple(f for f in reply_type.fields if f is not result_field),
        )
    return out


def _request(rpc: _Rpc, name: str, args: Sequence[object]) -> Message:
    if len(args) > len(rpc.fields):
        raise TypeError(
            f"{name}() takes {len(rpc.fields)} arguments ({', '.join(rpc.fields)}), given {len(args)}"
        )
    return rpc.request(**dict(zip(rpc.fields, args, strict=False)))


def _value(rpc: _Rpc, reply: Message) -> Message:
    if not rpc.values:
        return None
    if len(rpc.values) == 1:
        field = rpc.values[0]
        return convert(field, getattr(reply, field.name))
    return Reply(reply) if _holds_enum(reply.DESCRIPTOR) else reply


class Plugin:
    """One MAVSDK plugin of a session: its RPCs as coroutine functions (unary) and async iterators
    (streams) under the wrapper's names."""

    def __init__(
        self, channel: Channel, module: types.ModuleType, plugin: str, closed: Callable[[], bool]
    ) -> None:
        self._channel = channel
        self._plugin = plugin
        self._rpcs = _rpcs(module, plugin)
        self._closed = closed

    def __getattr__(self, name: str) -> Callable[..., Message]:
        rpc = self._rpcs.get(name)
        if rpc is None:
            raise AttributeError(f"the MAVSDK {self._plugin} plugin has no call {name!r}")
        made = self._stream(rpc, name) if rpc.streaming else self._unary(rpc, name)
        setattr(self, name, made)  # resolved once per session
        return made

    def _check_open(self) -> None:
        if self._closed():
            raise ChannelClosed(f"the MAVSDK session's channel is closed ({self._plugin})")

    def _unary(self, rpc: _Rpc, name: str) -> Callable[..., Awaitable[Message]]:
        method = UnaryUnaryMethod(self._channel, rpc.path, rpc.request, rpc.reply)
        origin = f"{name}()"

        async def call(*args: object) -> Message:
            request = _request(rpc, name, args)
            self._check_open()
            reply = await method(request)
            if rpc.result is not None:
                result = getattr(reply, rpc.result)
                if result.result != rpc.success:
                    enum = result.DESCRIPTOR.fields_by_name["result"].enum_type
                    raise MavsdkError(named(enum, result.result).name, str(result.result_str), origin)
            return _value(rpc, reply)

        call.__name__ = name
        return call

    def _stream(self, rpc: _Rpc, name: str) -> Callable[..., AsyncIterator[Message]]:
        method = UnaryStreamMethod(self._channel, rpc.path, rpc.request, rpc.reply)

        async def items(*args: object) -> AsyncIterator[Message]:
            request = _request(rpc, name, args)
            self._check_open()
            try:
                async with method.open() as stream:
                    await stream.send_message(request, end=True)
                    while (reply := await stream.recv_message()) is not None:
                        yield _value(rpc, reply)
            except (StreamTerminatedError, OSError):
                if not self._closed():
                    raise
                # the session closed its channel: the stream ends (no error for its reader)

        items.__name__ = name
        return items
