"""One command path: every command an MCP tool or a REST route runs is a declared verb (``@command``,
`gateway.fleet.commands.command_core.VERBS`), and the hand-written tools (gateway/mcp/tools/) run no
command at all, only reads. Read from the source of the doors: a door that calls something of the
Commander that is not a verb (an undeclared command, reaching around the declarations) is named. The
routes a verb declares (``route=Route(...)``, made by `gateway.api.declared`) are bound to it by
construction; no hand-written route serves the same method and path."""

from __future__ import annotations

import ast
import importlib
import inspect
import textwrap
from pathlib import Path
from typing import TypeGuard

from fastapi import APIRouter
from fastapi.routing import APIRoute

from gateway.api import API_PREFIX
from gateway.api.declared import build_declared_router
from gateway.app import create_app
from gateway.config import Settings
from gateway.fleet.commands.command_core import READ_VERBS, TOOLS, VERBS
from gateway.fleet.commands.routes import ROUTES
from gateway.mcp.declared import declared  # noqa: F401  (imports every verb module: fills VERBS)

ROOT = Path(__file__).resolve().parents[2]
API_MODULES = sorted((ROOT / "gateway" / "api").glob("*.py"))
#: what the doors read of the Commander that is no command (nothing is sent, nothing is audited)
READS = frozenset(
    {
        "canonical_id",
        "current_operation",
        "fleet_operation",
        "wait",
        "wait_fleet",
        "vehicle",
        "ready",
        "latest_operation",
        "operation",
        "registry",
        "locks",
        "geofences",
    }
)
#: the HTTP methods of a route that changes something (the audited ones)
CHANGING = frozenset({"POST", "PUT", "PATCH", "DELETE"})
#: what changes the registrations or the zones: the verbs' to do (`registry_verbs`, `zone_verbs`), never a
#: route's
CHANGES = frozenset({"add", "update", "remove", "connect", "disconnect", "move_origin", "replace"})


def commander_uses(path: Path | str) -> set[str]:
    """The attributes of a Commander a module uses: ``commander.X`` and ``<anything>.commander.X``; a
    verb called by name, ``commander.call("X", ...)``, counts as X (a name that is no literal as
    ``call``, which is no verb)."""
    used = set()
    by_name = set()
    tree = ast.parse(path if isinstance(path, str) else path.read_text())
    for node in ast.walk(tree):
        if isinstance(node, ast.Call) and _of_commander(node.func) and node.func.attr == "call":
            first = node.args[0] if node.args else None
            if isinstance(first, ast.Constant) and isinstance(first.value, str):
                used.add(first.value)
                by_name.add(id(node.func))
    for node in ast.walk(tree):
        if _of_commander(node) and id(node) not in by_name:
            used.add(node.attr)
    return used


def _of_commander(node: ast.AST) -> TypeGuard[ast.Attribute]:
    if not isinstance(node, ast.Attribute):
        return False
    owner = node.value
    return (isinstance(owner, ast.Name) and owner.id == "commander") or (
        isinstance(owner, ast.Attribute) and owner.attr == "commander"
    )


def test_reads_are_no_verbs() -> None:
    assert not READS & set(VERBS)


def test_every_rest_route_runs_a_declared_verb_or_reads() -> None:
    found = {
        f"{path.name}: {name}"
        for path in sorted((ROOT / "gateway" / "api").glob("*.py"))
        for name in commander_uses(path)
        if name not in VERBS and name not in READS
    }
    assert found == set()


def changes_made(path: Path) -> set[str]:
    """What a module changes itself: ``registry.X(...)`` / ``zones.X(...)`` calls of `CHANGES`, and
    assignments to ``.geofences``."""
    made = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and node.func.attr in CHANGES:
            owner = node.func.value
            if isinstance(owner, ast.Call):  # self._registry().add(...)
                owner = owner.func
            name = owner.id if isinstance(owner, ast.Name) else getattr(owner, "attr", "")
            name = name.lstrip("_").removeprefix("require_")
            if name in ("registry", "zones"):
                made.add(f"{name}.{node.func.attr}")
        if isinstance(node, ast.Assign | ast.AugAssign):
            targets = node.targets if isinstance(node, ast.Assign) else [node.target]
            made |= {"geofences =" for t in targets if isinstance(t, ast.Attribute) and t.attr == "geofences"}
    return made


def test_rest_routes_change_registrations_and_zones_through_verbs() -> None:
    """Registering, changing, removing, connecting drones, moving an origin and swapping zones are
    verbs (`register_drone`, `set_geofences`, `upload_plan`...): no route does it itself."""
    found = {
        f"{path.name}: {made}"
        for path in sorted((ROOT / "gateway" / "api").glob("*.py"))
        for made in changes_made(path)
    }
    assert found == set()
    assert {"registry.add", "zones.replace", "geofences ="} <= changes_made(
        ROOT / "gateway" / "fleet" / "commands" / "registry_verbs.py"
    ) | changes_made(ROOT / "gateway" / "fleet" / "commands" / "zone_verbs.py") | changes_made(
        ROOT / "gateway" / "fleet" / "policy" / "zones.py"
    ), "the scan sees what the verbs change"


def test_every_rest_route_that_changes_something_runs_a_verb() -> None:
    """Each POST, PUT, PATCH and DELETE route of /api/v1 (decorated or added with add_api_route) calls
    at least one declared verb: no change is made beside the one command path."""
    routers = [getattr(importlib.import_module(f"gateway.api.{p.stem}"), "router", None) for p in API_MODULES]
    routes = [
        r
        for router in routers
        if isinstance(router, APIRouter)
        for r in router.routes
        if isinstance(r, APIRoute) and r.methods & CHANGING
    ]
    assert len(routes) > 10  # the scan sees the routes
    without = sorted(
        f"{sorted(r.methods & CHANGING)} {r.path}"
        for r in routes
        if not commander_uses(textwrap.dedent(inspect.getsource(r.endpoint))) & set(VERBS)
    )
    assert without == []


def test_every_declared_route_is_served_once_and_runs_its_verb(tmp_path: Path) -> None:
    """Each `Route` a verb declares is one route of /api/v1 (its method and path, named as declared),
    made from the declaration; no hand-written route answers the same method and path."""
    assert {route.verb for route in ROUTES.values()} <= set(VERBS)
    made = {
        (method, r.path): r.name
        for r in build_declared_router().routes
        if isinstance(r, APIRoute)
        for method in r.methods
    }
    assert {f"{m} {p}" for m, p in made} == set(ROUTES)
    app = create_app(Settings(_env_file=None, database_url=f"sqlite+aiosqlite:///{tmp_path / 'g.db'}"))
    served = {
        (method.upper(), path.removeprefix(API_PREFIX)): operation["operationId"]
        for path, item in app.openapi()["paths"].items()
        for method, operation in item.items()
    }
    assert {key: served.get(key) for key in made} == made
    routers = [getattr(importlib.import_module(f"gateway.api.{p.stem}"), "router", None) for p in API_MODULES]
    by_hand = {
        (method, r.path)
        for router in routers
        if isinstance(router, APIRouter)
        for r in router.routes
        if isinstance(r, APIRoute)
        for method in r.methods
    }
    assert not by_hand & set(made), "a hand-written route serves a declared route's method and path"
    assert made[("POST", "/vehicles/{vehicle_id}/takeoff")] == "takeoff_vehicle"
    assert ROUTES["POST /vehicles/{vehicle_id}/takeoff"].verb == "takeoff"
    assert ROUTES["POST /vehicles/{vehicle_id}/hold"].verb == "stop_one"


def test_hand_written_tools_run_no_command() -> None:
    commands = set(VERBS) - READ_VERBS
    found = {
        f"{path.name}: {name}"
        for path in sorted((ROOT / "gateway" / "mcp" / "tools").glob("*.py"))
        for name in commander_uses(path)
        if name in commands or (name not in VERBS and name not in READS | READ_VERBS)
    }
    assert found == set()


def test_a_verb_called_by_name_is_scanned_by_its_name(tmp_path: Path) -> None:
    door = tmp_path / "door.py"
    door.write_text(
        "async def route(commander, verb):\n"
        "    await commander.call('goto', caller, drone_id='d1')\n"
        "    await commander.call(verb, caller)\n"
    )
    assert commander_uses(door) == {"goto", "call"}


def test_the_scan_sees_the_doors() -> None:
    """The scan finds what the doors do call (else the two tests above would pass on nothing)."""
    assert {"stop_all", "set_param", "upload_plan"} <= commander_uses(
        ROOT / "gateway" / "api" / "control.py"
    ) | commander_uses(ROOT / "gateway" / "api" / "params.py") | commander_uses(
        ROOT / "gateway" / "api" / "missions.py"
    )
    assert "get_param" in commander_uses(ROOT / "gateway" / "mcp" / "tools" / "params.py")
    assert {tool.verb for tool in TOOLS.values()} <= set(VERBS)
