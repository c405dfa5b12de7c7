"""A command's MCP tool is part of its declaration (``@command(tool=Tool(...))``): the tool is generated
from the verb's own signature, and no tool is both declared and written by hand. In-process client, the
real gateway and fake drones."""

from __future__ import annotations

import importlib
import inspect
import re
from collections.abc import AsyncIterator, Iterator
from pathlib import Path
from typing import Annotated, Any

import pytest
from mcp import Client
from pydantic import Field

from gateway.config import ALL_TOOLSETS
from gateway.fleet.commands.arguments import DroneId
from gateway.fleet.commands.command_core import TOOLS, VERBS, Tool, command
from gateway.fleet.operations.views import ActionResult
from gateway.fleet.policy.caller import Caller
from gateway.mcp.confirmation import ANSWER
from gateway.mcp.declared import FILLED, complete
from gateway.mcp.presenters import PRESENTERS, waits_itself
from gateway.mcp.server import build_mcp, load_toolset
from gateway.mcp.toolkit import Toolset
from gateway.runtime import Gateway
from tests.fakes import FakeVehicle, fake_gateway, unit_settings


@pytest.fixture
async def gateway(tmp_path: Path) -> AsyncIterator[Gateway]:
    async with fake_gateway(unit_settings(tmp_path, mcp_wait_cap_s=5.0), [FakeVehicle("d1")]) as gw:
        yield gw


class CameraVerbs:
    """A part of the Commander that exists only in this test."""

    def __init__(self) -> None:
        self.calls: list[tuple[Caller, str, float]] = []

    async def point_camera(
        self,
        caller: Caller,
        drone_id: DroneId,
        tilt_deg: Annotated[
            float, Field(ge=-90, le=0, allow_inf_nan=False, description="deg, - is down")
        ] = -45.0,
        label: str = "point_camera",
    ) -> ActionResult:
        """Tilt the camera; 0 is level.

        For developers only: not part of the tool's description."""
        self.calls.append((caller, drone_id, tilt_deg))
        return ActionResult(drone_id=drone_id, action=label, message=f"camera at {tilt_deg:g} deg")


@pytest.fixture
def camera(gateway: Gateway) -> Iterator[CameraVerbs]:
    """``point_camera`` declared with its tool, as a verb module declares one; forgotten afterwards."""
    verbs, tools = dict(VERBS), dict(TOOLS)
    command(tool=Tool("point_camera", "navigation", idempotent=True, says="{drone_id} {message}"))(
        CameraVerbs.point_camera
    )
    part = gateway.commander.parts["CameraVerbs"] = CameraVerbs()
    try:
        yield part
    finally:
        VERBS.clear()
        VERBS.update(verbs)
        TOOLS.clear()
        TOOLS.update(tools)
        del gateway.commander.parts["CameraVerbs"]


async def test_a_declared_verb_is_a_tool_with_its_own_schema(gateway: Gateway, camera: CameraVerbs) -> None:
    async with Client(build_mcp(gateway)) as c:
        tool = {t.name: t for t in (await c.list_tools()).tools}["point_camera"]
        assert tool.description == "Tilt the camera; 0 is level."
        assert (tool.meta or {}).get("fleet-gateway/toolset") == "navigation"
        assert tool.annotations is not None and tool.annotations.idempotent_hint is True
        assert tool.annotations.read_only_hint is False and tool.annotations.destructive_hint is False
        # the verb's parameters after caller, with their bounds; label is the tool's own name
        assert tool.input_schema["properties"] == {
            "drone_id": {"type": "string"},
            "tilt_deg": {
                "type": "number",
                "minimum": -90,
                "maximum": 0,
                "default": -45.0,
                "description": "deg, - is down",
            },
        }
        assert tool.input_schema["required"] == ["drone_id"]
        r = await c.call_tool("point_camera", {"drone_id": "D1", "tilt_deg": -30})
        assert not r.is_error, r.content
        assert r.content[0].text == "d1 camera at -30 deg"
        assert r.structured_content == {
            "drone_id": "d1",
            "action": "point_camera",
            "message": "camera at -30 deg",
            "superseded_operation": None,
        }
        r = await c.call_tool("point_camera", {"drone_id": "d1", "tilt_deg": 20})
        assert r.is_error
        assert r.content[0].text == (
            "invalid arguments for point_camera: tilt_deg must be a number (deg, - is down), "
            "-90 <= tilt_deg <= 0 (got 20)"
        )
    [(caller, drone_id, tilt)] = camera.calls  # the bad call reached nothing
    assert (caller.via, drone_id, tilt) == ("mcp", "d1", -30.0)


def test_every_declared_tool_offers_its_verbs_parameters() -> None:
    """Each declared tool (the flight and navigation commands among them) is in a toolset the settings
    know, and its arguments are its verb's: no more, no fewer, in the verb's order."""
    assert {"takeoff", "go_to_location", "set_yaw", "set_max_speed", "hold_position"} <= set(TOOLS)
    for name, tool in TOOLS.items():
        assert tool.toolset in ALL_TOOLSETS, name
        toolset = load_toolset(tool.toolset)
        assert toolset is not None
        [spec] = [s for s in toolset.tools if s.name == name]
        verb = VERBS[tool.verb]
        answered = () if tool.confirm is None else (tool.confirm.into,)
        wanted = [
            tool.takes[p.name].name if p.name in tool.takes else p.name
            for p in list(verb.signature.parameters.values())[2:]
            if p.kind is inspect.Parameter.POSITIONAL_OR_KEYWORD
            and p.name not in (*FILLED, *tool.omit, *answered)
        ]
        if PRESENTERS[verb.result].waits and not waits_itself(verb):  # monitor waits itself
            wanted.append("wait")
        if tool.confirm is not None:
            wanted.insert(0, ANSWER)  # filled by a human's answer, never offered to the model
        assert list(inspect.signature(spec.fn).parameters)[1:] == wanted, name


def test_no_tool_is_both_declared_and_written_by_hand() -> None:
    for name in ALL_TOOLSETS:
        module: Any = importlib.import_module(f"gateway.mcp.tools.{name}")
        written = {spec.name for spec in module.toolset.tools}
        assert not written & set(TOOLS), (name, written & set(TOOLS))

    async def takeoff() -> None:
        """A hand-written copy of a declared tool."""

    copy = Toolset("flight")
    copy.tool()(takeoff)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="takeoff is declared by a verb and written by hand too"):
        complete(copy)


def test_contributing_shows_a_command_in_three_files_as_the_code_has_it() -> None:
    """The example of CONTRIBUTING.md ("Adding a command and its tool") is the real code of its three
    files: the verb with its tool, the VehicleActions member, its body."""
    root = Path(__file__).resolve().parents[2]
    text = (root / "CONTRIBUTING.md").read_text()
    shown = re.findall(
        r"\*\*[1-3]\. [^*]*?`(gateway/fleet/[a-z_/]+\.py)`\*\*.*?```python\n(.*?)```", text, re.S
    )
    assert [path for path, _ in shown] == [
        "gateway/fleet/commands/navigation_verbs.py",
        "gateway/fleet/vehicles/protocols.py",
        "gateway/fleet/vehicles/vehicle.py",
    ]
    for path, code in shown:
        assert code in (root / path).read_text(), path


def test_the_hand_written_tools_only_read() -> None:
    """gateway/mcp/tools/ holds only what is not a command: every tool written there is read-only (a
    command, anything that changes a drone or its state, is declared with its verb)."""
    modules = sorted(p.stem for p in TOOLS_DIR.glob("*.py") if p.stem != "__init__")
    assert modules, TOOLS_DIR
    written = {
        spec.name: spec.annotations.read_only_hint
        for name in modules
        for spec in importlib.import_module(f"gateway.mcp.tools.{name}").toolset.tools
    }
    assert written and all(written.values()), {n: r for n, r in written.items() if not r}


TOOLS_DIR = Path(__file__).resolve().parents[2] / "gateway" / "mcp" / "tools"
