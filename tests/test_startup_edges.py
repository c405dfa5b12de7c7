"""The edges of starting the gateway: every failure is one line naming the thing and the fix, with a
non-zero exit and nothing left behind; --help imports none of the heavy areas; /docs works offline."""

from __future__ import annotations

import os
import socket
import subprocess
import sys
from pathlib import Path

import httpx
import pytest

from gateway.app import create_app
from gateway.config import Settings
from gateway.util.ports import free_tcp_port
from tests.helpers.timing import scaled

ROOT = Path(__file__).resolve().parents[1]


def fleet_gateway(
    *args: str, cwd: Path, env: dict[str, str] | None = None
) -> subprocess.CompletedProcess[str]:
    environment = {**os.environ, "PYTHONPATH": str(ROOT), **(env or {})}
    environment.pop("GATEWAY_DATABASE_URL", None)
    return subprocess.run(
        [sys.executable, "-m", "gateway.cli", *args],
        cwd=cwd, env=environment, capture_output=True, text=True, timeout=scaled(120),
    )  # fmt: skip


def error_lines(result: subprocess.CompletedProcess[str]) -> list[str]:
    return [line for line in result.stderr.splitlines() if line.strip()]


def test_top_level_help_imports_none_of_the_command_areas() -> None:
    code = (
        "import sys, contextlib, io\n"
        "from gateway.cli import main\n"
        "with contextlib.suppress(SystemExit), contextlib.redirect_stdout(io.StringIO()):\n"
        "    main(['--help'])\n"
        "heavy = ('uvicorn', 'sqlalchemy', 'mcp', 'openai', 'fastapi', 'mavsdk_grpc')\n"
        "print(','.join(m for m in heavy if m in sys.modules))\n"
    )
    out = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "", f"--help imported {out.stdout.strip()}"


def test_agent_without_the_openai_extra_says_how_to_add_it() -> None:
    """The image leaves the agent host's model client out: `fleet-gateway agent` then says what to install,
    in one line, and the gateway's own commands do not need it."""
    code = (
        "import sys\n"
        "sys.modules['openai'] = None  # as if not installed: importing it raises ModuleNotFoundError\n"
        "from gateway.cli import main\n"
        "try:\n"
        "    main(['agent', '--help'])\n"
        "except SystemExit as exc:\n"
        "    print(exc.code)\n"
        "from gateway import server_cli, app\n"
        "from gateway.sim import cli\n"
    )
    out = subprocess.run(
        [sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, timeout=scaled(60)
    )
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == (
        "error: `fleet-gateway agent` needs the OpenAI client, an optional extra: "
        "pip install 'fleet-gateway[agent]'"
    )
    # the image copies gateway/ only: without the agent's package the command says so the same way
    without_package = code.replace("sys.modules['openai']", "sys.modules['fleet_agent']")
    out = subprocess.run(
        [sys.executable, "-c", without_package], cwd=ROOT, capture_output=True, text=True, timeout=scaled(60)
    )
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == (
        "error: `fleet-gateway agent` needs the agent host (package fleet_agent), an optional extra: "
        "pip install 'fleet-gateway[agent]'"
    )


@pytest.mark.parametrize(
    ("args", "usage", "named"),
    [
        (["--bogus"], "usage: fleet-gateway [-h]", "unrecognized argument(s): --bogus"),
        (["serve", "--prot", "9000"], "usage: fleet-gateway serve", "unrecognized argument(s): --prot 9000"),
        ([], "usage: fleet-gateway [-h]", "a COMMAND is needed, one of: serve, demo"),
    ],
)
def test_a_bad_flag_is_named_with_its_commands_usage(
    tmp_path: Path, args: list[str], usage: str, named: str
) -> None:
    result = fleet_gateway(*args, cwd=tmp_path)
    assert result.returncode == 2
    assert usage in result.stderr and named in result.stderr, result.stderr
    assert list(tmp_path.iterdir()) == []


def test_serve_and_demo_help_describe_the_command(tmp_path: Path) -> None:
    for command in ("serve", "demo"):
        result = fleet_gateway(command, "--help", cwd=tmp_path)
        assert result.returncode == 0
        assert result.stdout.split("\n\n")[1].strip(), result.stdout  # a description under the usage


def test_serve_on_a_port_in_use_says_so_before_writing_anything(tmp_path: Path) -> None:
    with socket.socket() as holder:
        holder.bind(("127.0.0.1", 0))
        holder.listen()
        port = holder.getsockname()[1]
        result = fleet_gateway("serve", "--port", str(port), cwd=tmp_path)
    assert result.returncode == 2
    assert error_lines(result) == [
        f"error: port {port} on 127.0.0.1 is already in use (another fleet-gateway?); "
        "pass --port N (or set GATEWAY_PORT), or stop what holds it"
    ]
    assert list(tmp_path.iterdir()) == []  # no ./fleet-gateway.db left behind


def test_a_second_demo_on_a_taken_port_says_so_at_once(tmp_path: Path) -> None:
    with socket.socket() as holder:
        holder.bind(("127.0.0.1", 0))
        holder.listen()
        port = holder.getsockname()[1]
        result = fleet_gateway("demo", "--port", str(port), cwd=tmp_path)
    assert result.returncode == 2
    assert error_lines(result) == [
        f"fleet-gateway demo: error: port {port} on 127.0.0.1 is already in use (another fleet-gateway?); "
        "pass --port N (or set GATEWAY_PORT), or stop what holds it"
    ]
    assert list(tmp_path.iterdir()) == []


def test_a_missing_database_directory_is_created(tmp_path: Path) -> None:
    db = tmp_path / "not" / "yet" / "there" / "fg.db"
    result = fleet_gateway("db", "upgrade", "--database-url", f"sqlite+aiosqlite:///{db}", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert result.stdout.startswith("database at revision") and db.is_file()
    assert "alembic" not in result.stderr  # no migration chatter at the default log level


def test_a_database_directory_that_cannot_be_created_is_one_line(tmp_path: Path) -> None:
    blocker = tmp_path / "a-file"
    blocker.write_text("")
    url = f"sqlite+aiosqlite:///{blocker}/sub/fg.db"
    for args in (["db", "upgrade"], ["drones", "list"]):
        result = fleet_gateway(*args, "--database-url", url, cwd=tmp_path)
        assert result.returncode == 2
        lines = error_lines(result)
        assert len(lines) == 1 and lines[0].startswith(
            f"error: cannot create the database directory {blocker}/sub"
        )
        assert "choose another --database-url" in lines[0]


def test_an_unreachable_postgresql_is_one_line_without_its_password(tmp_path: Path) -> None:
    url = f"postgresql+asyncpg://pilot:s3cret@127.0.0.1:{free_tcp_port()}/fleet"
    result = fleet_gateway("drones", "list", "--database-url", url, cwd=tmp_path)
    assert result.returncode == 2
    lines = error_lines(result)
    assert len(lines) == 1 and "s3cret" not in result.stderr, result.stderr
    assert lines[0].startswith("error: cannot open the database postgresql+asyncpg://pilot:***@127.0.0.1:")
    assert "is the database server running and reachable?" in lines[0]


def test_a_missing_sidecar_binary_stops_serve_before_the_database(tmp_path: Path) -> None:
    result = fleet_gateway(
        "serve", "--port", str(free_tcp_port()), cwd=tmp_path,
        env={"GATEWAY_MAVSDK_SERVER_PATH": str(tmp_path / "no-such-mavsdk_server")},
    )  # fmt: skip
    assert result.returncode == 2
    assert error_lines(result) == [
        f"error: mavsdk_server not found at {tmp_path / 'no-such-mavsdk_server'} "
        "(GATEWAY_MAVSDK_SERVER_PATH); "
        "point it at the binary, or unset it to use the one bundled with mavsdk-grpc"
    ]
    assert list(tmp_path.iterdir()) == []


async def test_docs_load_no_asset_from_another_host(tmp_path: Path) -> None:
    settings = Settings(_env_file=None, database_url=f"sqlite+aiosqlite:///{tmp_path / 'g.db'}")
    app = create_app(settings)
    async with httpx.AsyncClient(
        transport=httpx.ASGITransport(app=app), base_url="http://testserver"
    ) as http:
        page = await http.get("/docs")
        assert page.status_code == 200 and "swagger-ui" in page.text
        assert "cdn" not in page.text.lower() and "https://" not in page.text, page.text
        for asset in ("/docs-assets/swagger-ui-bundle.js", "/docs-assets/swagger-ui.css"):
            r = await http.get(asset)
            assert r.status_code == 200 and len(r.content) > 10_000, asset
        assert (await http.get("/openapi.json")).json()["info"]["title"] == "fleet-gateway"


def test_a_scope_that_confines_no_agent_stops_serve_with_one_line(tmp_path: Path) -> None:
    env = {"GATEWAY_AGENT_TOKENS": "alpha-token", "GATEWAY_AGENT_SCOPES": '{"agent-0badc0de": ["alpha"]}'}
    result = fleet_gateway("serve", "--port", str(free_tcp_port()), cwd=tmp_path, env=env)
    assert result.returncode == 2
    lines = error_lines(result)
    assert len(lines) == 1 and "GATEWAY_AGENT_SCOPES key agent-0badc0de is neither" in lines[0], lines
    assert list(tmp_path.iterdir()) == []  # nothing written
