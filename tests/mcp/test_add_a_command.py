"""A new command, added as CONTRIBUTING.md's "Adding a command and its tool" shows, changes its source
files and its own test only: in a copy of the project, a toy command (``set_light``: a verb with its
tool and its operator's REST route declared, a `VehicleActions` member, its body) is added, and nothing
in gateway/api/ is touched; docs/tools.md is regenerated (`make docs`); then the tests that count the
tools, the docs check, the declared-tool checks, the doors' checks (the declared route is served and
runs its verb), the REST document's checks, mypy (the fake vehicle against `FlyingVehicle`) and the
command's own test (MCP and REST) pass, and no other file changed."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from tests.helpers.timing import scaled

ROOT = Path(__file__).resolve().parents[2]
COPIED = ("gateway", "migrations", "tests", "scripts", "docs", "fleet_agent", "bench", "deploy")
COPIED_FILES = ("pyproject.toml", "setup.py", "CONTRIBUTING.md", "README.md", "alembic.ini")

VERB = '''
    @command(
        tool=Tool("set_light", "navigation", idempotent=True, says="{drone_id}: {message}"),
        route=Route("light", "Switch the light (operator)"),
    )
    @routed
    async def set_light(self, caller: Caller, drone_id: DroneId, on: bool) -> ActionResult:
        """Switch the drone's light on or off."""

        def decide(vehicle: FlyingVehicle, ctx: VehicleContext) -> Order:
            self.commands.safety.check_actuation(ctx, caller.policy_via)
            return Order(lambda: vehicle.set_light(on))

        await self.commands.run(caller, drone_id, "set_light", decide)
        return ActionResult(drone_id=drone_id, action="set_light", message=f"light {'on' if on else 'off'}")

'''
MEMBER = "    async def set_light(self, on: bool) -> None: ...\n\n"
BODY = """    async def set_light(self, on: bool) -> None:
        self.require_dialect()
        await self.link.call("light", self.link.require_session().action.set_actuator(1, 1.0 if on else -1.0))

"""
OWN_TEST = '''"""The light command through its MCP tool and its REST route, over the fake drones."""

from pathlib import Path

import httpx
from mcp import Client

from gateway.app import create_app
from gateway.config import Settings
from gateway.mcp.server import build_mcp
from gateway.registry.store import Store
from tests.api.live import lifespan_running
from tests.fakes import FakeRegistry, FakeVehicle, fake, fake_gateway, unit_settings


async def test_the_light_goes_on(tmp_path: Path) -> None:
    async with fake_gateway(unit_settings(tmp_path), [FakeVehicle("d1")]) as gateway:
        async with Client(build_mcp(gateway)) as c:
            result = await c.call_tool("set_light", {"drone_id": "d1", "on": True})
        assert not result.is_error, result.content
        assert result.content[0].text == "d1: light on"
        assert fake(gateway, "d1").sent[-1] == ("set_light", True)


async def test_an_operator_switches_it_off_over_rest(tmp_path: Path) -> None:
    drone = FakeVehicle("d1")

    def registry(settings: Settings, store: Store) -> FakeRegistry:
        return FakeRegistry(settings, store, [drone])

    async with lifespan_running(create_app(unit_settings(tmp_path), registry_factory=registry)) as app:
        transport = httpx.ASGITransport(app=app)
        async with httpx.AsyncClient(transport=transport, base_url="http://127.0.0.1:8765") as http:
            answer = await http.post("/api/v1/vehicles/d1/light", json={"on": False})
            refused = await http.post("/api/v1/vehicles/d1/light", json={"on": "off"})
            document = (await http.get("/openapi.json")).json()
    assert answer.status_code == 200, answer.text
    assert answer.json()["message"] == "light off"
    assert answer.json()["action"] == "set_light" and answer.json()["vehicle_id"] == "d1"
    route = document["paths"]["/api/v1/vehicles/{vehicle_id}/light"]["post"]
    assert route["operationId"] == "set_light_vehicle" and route["tags"] == ["operator control"]
    assert drone.sent[-1] == ("set_light", False)
    assert refused.status_code == 422 and "on" in refused.text  # bad input changes nothing
    assert [s for s in drone.sent if s[0] == "set_light"] == [("set_light", False)]
'''
#: the tests a new command used to have to edit (tool counts, docs, declared tools), and its own
CHECKS = [
    "tests/mcp/test_names_unit.py::test_no_tool_argument_or_result_uses_a_retired_name",
    "tests/mcp/test_surface_unit.py::test_takeoff_goto_land_and_refusals",
    "tests/mcp/test_tool_budget.py::test_core_toolsets_fit_the_token_budget",
    "tests/mcp/test_tools_doc.py",
    "tests/mcp/test_declared_unit.py",
    "tests/mcp/test_command_doors_unit.py",
    "tests/mcp/test_set_light.py",
    "tests/api/test_openapi.py",
]


def _insert(path: Path, before: str, text: str) -> None:
    source = path.read_text()
    assert source.count(before) == 1, f"{path}: {before!r} is not where CONTRIBUTING.md says"
    path.write_text(source.replace(before, text + before))


def _snapshot(root: Path) -> dict[str, bytes]:
    return {
        str(p.relative_to(root)): p.read_bytes()
        for p in root.rglob("*")
        if p.is_file() and "__pycache__" not in p.parts and ".mypy_cache" not in p.parts
        and ".pytest_cache" not in p.parts and not p.name.endswith(".db")
    }  # fmt: skip


def _run(copy: Path, *args: str) -> subprocess.CompletedProcess[str]:
    env = {**os.environ, "PYTHONPATH": str(copy)}  # the copy's gateway, not the installed one
    return subprocess.run([sys.executable, *args], cwd=copy, env=env, capture_output=True, text=True)


@pytest.fixture
def copy(tmp_path: Path) -> Path:
    root = tmp_path / "project"
    ignore = shutil.ignore_patterns("__pycache__", ".mypy_cache", ".pytest_cache", "*.db", "vendor")
    for name in COPIED:
        shutil.copytree(ROOT / name, root / name, ignore=ignore)
    for name in COPIED_FILES:
        shutil.copy2(ROOT / name, root / name)
    # `make test` runs mypy beside the suite: the copy's run checks only what changed (a cold run took 214 s
    # under load); a cache file mypy is still writing (its "*.tmp", renamed when whole) is left out
    if (ROOT / ".mypy_cache").is_dir():
        shutil.copytree(ROOT / ".mypy_cache", root / ".mypy_cache", ignore=shutil.ignore_patterns("*.tmp"))
    return root


@pytest.mark.timeout(scaled(900))  # a sub-suite and mypy in a copy: minutes on a loaded machine
def test_a_command_is_its_source_files_and_its_own_test(copy: Path) -> None:
    where = _run(copy, "-c", "import gateway; print(gateway.__file__)")
    assert where.stdout.strip().startswith(str(copy)), where.stdout + where.stderr
    before = _snapshot(copy)

    # 1-3: the verb with its tool, the action's member, its body (CONTRIBUTING.md, the three files)
    _insert(
        copy / "gateway/fleet/commands/navigation_verbs.py",
        "    @command\n    @routed\n    async def arrival(",
        VERB,
    )
    _insert(
        copy / "gateway/fleet/vehicles/protocols.py", "    async def set_flight_mode(self, name: str)", MEMBER
    )
    _insert(copy / "gateway/fleet/vehicles/vehicle.py", "    # --- where the autopilot flies to", BODY)
    # its own test
    (copy / "tests/mcp/test_set_light.py").write_text(OWN_TEST)
    # then: `make docs` (docs/tools.md is generated from the declarations)
    generated = _run(copy, "scripts/gen_tools_doc.py")
    assert generated.returncode == 0, generated.stdout + generated.stderr

    changed = {name for name, data in _snapshot(copy).items() if before.get(name) != data}
    assert changed == {
        "gateway/fleet/commands/navigation_verbs.py",
        "gateway/fleet/vehicles/protocols.py",
        "gateway/fleet/vehicles/vehicle.py",
        "tests/mcp/test_set_light.py",
        "docs/tools.md",
    }
    assert "### `set_light`" in (copy / "docs/tools.md").read_text()

    tests = _run(copy, "-m", "pytest", "-q", "-p", "no:cacheprovider", "-p", "no:xdist", *CHECKS)
    assert tests.returncode == 0, tests.stdout[-4000:] + tests.stderr[-2000:]
    typed = _run(copy, "-m", "mypy")  # the fake vehicle is checked against FlyingVehicle
    assert typed.returncode == 0, typed.stdout[-4000:] + typed.stderr[-2000:]
