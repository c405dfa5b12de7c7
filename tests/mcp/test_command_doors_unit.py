"""One command path: every command an MCP tool or a REST route runs is a declared verb (``@command``,
`gateway.fleet.commands.command_core.VERBS`), and the hand-written tools (gateway/mcp/tools/) run no
command at all, only reads. Read from the source of the doors: a door that calls something of the
Commander that is not a verb (an undeclared command, reaching around the declarations) is named."""

from __future__ import annotations

import ast
from pathlib import Path

from gateway.fleet.commands.command_core import READ_VERBS, TOOLS, VERBS
from gateway.mcp.declared import declared  # noqa: F401  (imports every verb module: fills VERBS)

ROOT = Path(__file__).resolve().parents[2]
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
    }
)


def commander_uses(path: Path) -> set[str]:
    """The attributes of a Commander a module uses: ``commander.X`` and ``<anything>.commander.X``."""
    used = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if not isinstance(node, ast.Attribute):
            continue
        owner = node.value
        if (isinstance(owner, ast.Name) and owner.id == "commander") or (
            isinstance(owner, ast.Attribute) and owner.attr == "commander"
        ):
            used.add(node.attr)
    return used


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


def test_hand_written_tools_run_no_command() -> None:
    """(``monitor`` is a wait, a read verb; its ``land_on_arrival`` lands through the pass.)"""
    commands = set(VERBS) - READ_VERBS
    found = {
        f"{path.name}: {name}"
        for path in sorted((ROOT / "gateway" / "mcp" / "tools").glob("*.py"))
        for name in commander_uses(path)
        if name in commands or (name not in VERBS and name not in READS | READ_VERBS)
    }
    assert found == set()


def test_the_scan_sees_the_doors() -> None:
    """The scan finds what the doors do call (else the two tests above would pass on nothing)."""
    assert {"kill", "stop_one", "set_param", "lock"} <= commander_uses(
        ROOT / "gateway" / "api" / "control.py"
    ) | (
        commander_uses(ROOT / "gateway" / "api" / "flying.py")
        | commander_uses(ROOT / "gateway" / "api" / "params.py")
    )
    assert "get_param" in commander_uses(ROOT / "gateway" / "mcp" / "tools" / "params.py")
    assert {tool.verb for tool in TOOLS.values()} <= set(VERBS)
