"""The gateway's MAVSDK plugins over grpclib (`gateway.link.mavsdk_rpc`) offer what mavsdk_grpc's
wrappers offer under the same names: each call the gateway makes exists with the wrapper's arguments,
every enum value reads as the wrapper's enum names it, a result other than SUCCESS raises one error
with the result's name and text. The wrappers (and grpcio) are imported here, by the test only."""

from __future__ import annotations

import enum
import importlib
import inspect

import pytest

from gateway.link import mavsdk_system
from gateway.link.mavsdk_rpc import MavsdkError, Named, Reply, _rpcs, camel, convert, named, positional

#: the calls the gateway makes (its call sites: grep "system\." in gateway/), by plugin
CALLED = {
    "action": [
        "arm", "disarm", "kill", "takeoff", "land", "return_to_launch", "goto_location",
        "set_takeoff_altitude", "set_current_speed", "get_takeoff_altitude",
    ],
    "core": ["connection_state", "set_heartbeat_watchdog_timeout", "feed_heartbeat_watchdog"],
    "events": ["events"],
    "info": ["get_version"],
    "mavlink_direct": ["message", "send_message"],
    "mission_raw": [
        "upload_mission", "download_mission", "clear_mission", "start_mission", "set_current_mission_item",
        "is_mission_finished", "mission_progress",
    ],
    "param": ["get_param_int", "get_param_float", "set_param_int", "set_param_float", "get_all_params"],
    "telemetry": [
        "position", "home", "attitude_euler", "velocity_ned", "battery", "gps_info", "flight_mode",
        "landed_state", "health", "rc_status", "imu", "raw_imu", "odometry", "status_text",
    ],
}  # fmt: skip


def wrapper(plugin: str) -> type:
    module = importlib.import_module(f"mavsdk_grpc.{plugin}")
    return getattr(module, camel(plugin))  # type: ignore[no-any-return]


@pytest.mark.parametrize("plugin", mavsdk_system.PLUGINS)
def test_every_call_of_the_wrapper_is_there_by_its_name_and_arguments(plugin: str) -> None:
    rpcs = _rpcs(mavsdk_system._MODULES[plugin], plugin)
    cls = wrapper(plugin)
    names = {
        n for n, f in vars(cls).items() if inspect.iscoroutinefunction(f) or inspect.isasyncgenfunction(f)
    }
    names -= {"_init_plugin"}
    assert set(CALLED.get(plugin, [])) <= names
    assert names - {n for n in names if not n.startswith("_")} == set()
    assert names <= set(rpcs), f"{plugin}: calls of the wrapper missing here: {sorted(names - set(rpcs))}"
    for name in names:
        params = [p for p in inspect.signature(getattr(cls, name)).parameters if p != "self"]
        assert len(params) == len(rpcs[name].fields), (plugin, name, params, rpcs[name].fields)
        assert rpcs[name].streaming == inspect.isasyncgenfunction(getattr(cls, name)), (plugin, name)


def _wrapper_enums(plugin: str) -> dict[str, set[str]]:
    """The wrapper module's enums (nested ones too) by their class name: their members' names."""
    module = importlib.import_module(f"mavsdk_grpc.{plugin}")
    found: dict[str, set[str]] = {}

    def walk(namespace: object) -> None:
        for value in vars(namespace).values():
            if isinstance(value, type) and value.__module__ == module.__name__:
                if issubclass(value, enum.Enum):
                    found.setdefault(value.__name__, set()).update(m.name for m in value)
                elif value is not namespace:
                    walk(value)

    walk(module)
    return found


@pytest.mark.parametrize("plugin", mavsdk_system.PLUGINS)
def test_every_enum_value_is_named_as_the_wrapper_names_it(plugin: str) -> None:
    module = mavsdk_system._MODULES[plugin]
    wrapped = _wrapper_enums(plugin)
    enums = list(module.DESCRIPTOR.enum_types_by_name.values())
    for message in module.DESCRIPTOR.message_types_by_name.values():
        enums += list(message.enum_types)
    for descriptor in enums:
        ours = {named(descriptor, v.number).name for v in descriptor.values}
        assert ours == wrapped[descriptor.name], (plugin, descriptor.full_name)


def test_enums_inside_messages_read_as_named_and_other_messages_as_they_are() -> None:
    telemetry = mavsdk_system.telemetry_pb2
    text = telemetry.StatusTextResponse(
        status_text=telemetry.StatusText(type=telemetry.STATUS_TEXT_TYPE_WARNING, text="PreArm: x")
    )
    item = convert(text.DESCRIPTOR.fields_by_name["status_text"], text.status_text)
    assert isinstance(item, Reply)
    assert (
        item.type == Named("WARNING", telemetry.STATUS_TEXT_TYPE_WARNING)
        and item.type.name == "WARNING"
        and str(item.type) == "WARNING"
    )
    assert item.text == "PreArm: x"
    position = telemetry.PositionResponse(position=telemetry.Position(latitude_deg=47.5))
    same = convert(position.DESCRIPTOR.fields_by_name["position"], position.position)
    assert same is position.position  # no enum in it: the message itself
    with pytest.raises(AttributeError, match="no field 'nope'"):
        _ = item.nope
    events = mavsdk_system.events_pb2
    event = events.Event(
        message="Mission rejected: takeoff is not the first waypoint item", log_level=events.LOG_LEVEL_ERROR
    )
    read = convert(events.EventsResponse.DESCRIPTOR.fields_by_name["event"], event)
    assert (
        read.message == "Mission rejected: takeoff is not the first waypoint item"
    )  # the field, not the wrapped
    assert read.log_level.name == "ERROR"


def test_messages_are_made_from_positional_fields_as_the_wrappers_classes() -> None:
    msg = mavsdk_system.MavlinkMessage("COMMAND_LONG", 245, 190, 1, 1, "{}")
    assert (msg.message_name, msg.system_id, msg.component_id, msg.target_system_id) == (
        "COMMAND_LONG",
        245,
        190,
        1,
    )
    item = mavsdk_system.MissionRawItem(0, 3, 16, 1, 1, 0.0, 0.0, 0.0, 0.0, 473977418, 85455939, 10.0, 0)
    assert (item.seq, item.frame, item.command, item.x, item.y, item.z) == (
        0,
        3,
        16,
        473977418,
        85455939,
        10.0,
    )
    with pytest.raises(TypeError, match="MavlinkMessage takes 6 fields"):
        positional(mavsdk_system.mavlink_direct_pb2.MavlinkMessage)(*range(7))


def test_a_failed_result_is_one_error_with_its_name_and_text() -> None:
    exc = MavsdkError("WRONG_TYPE", "Wrong type", "get_param_int()")
    assert (exc.result, exc.result_str) == ("WRONG_TYPE", "Wrong type")
    assert str(exc) == "WRONG_TYPE: 'Wrong type'; origin: get_param_int()"
