"""`fleet-gateway db upgrade` and `drones add|list|remove`, on the database and through a running gateway."""

from __future__ import annotations

import asyncio
import gc
import json
import subprocess
import sys
import threading
import time
from datetime import UTC, datetime, timedelta
from pathlib import Path

import pytest

import gateway.cli
from gateway.app import create_app
from gateway.config import Settings
from gateway.registry.database import create_engine_for, current_revision, head_revision
from gateway.registry.store import Store
from gateway.server_cli import main
from gateway.util.ports import free_tcp_port
from tests.fakes import FakeRegistry
from tests.helpers.timing import scaled

from .server import serve_in_thread


def run_cli(*argv: str) -> int:
    return main(list(argv))


def revision_of(url: str) -> str | None:
    async def get() -> str | None:
        engine = create_engine_for(url)
        try:
            return await current_revision(engine)
        finally:
            await engine.dispose()

    return asyncio.run(get())


def test_db_upgrade_command_in_a_subprocess(tmp_path: Path) -> None:
    url = f"sqlite+aiosqlite:///{tmp_path / 'fresh.db'}"
    result = subprocess.run(
        [sys.executable, "-m", "gateway.server_cli", "db", "upgrade", "--database-url", url],
        capture_output=True,
        text=True,
        timeout=scaled(120),
    )
    assert result.returncode == 0, result.stderr
    assert f"database at revision {head_revision()}" in result.stdout
    assert revision_of(url) == head_revision()
    # idempotent
    assert run_cli("db", "upgrade", "--database-url", url) == 0


def test_only_the_processs_own_command_leaves_its_heap_to_the_exit(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """main() run as the process's command (its words from sys.argv) moves the heap to the collector's
    permanent generation when the command returns, so the exit does not collect it all (seconds for a
    gateway that served); called with words, as a test does in its own process, it leaves it alone."""
    args = ["db", "upgrade", "--database-url", f"sqlite+aiosqlite:///{tmp_path / 'exit.db'}"]
    before = gc.get_freeze_count()
    assert gateway.cli.main(args) == 0
    assert gc.get_freeze_count() == before
    monkeypatch.setattr(sys, "argv", ["fleet-gateway", *args])
    try:
        assert gateway.cli.main() == 0
        assert gc.get_freeze_count() > before
    finally:
        gc.unfreeze()


def test_drones_on_the_database(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    url = f"sqlite+aiosqlite:///{tmp_path / 'cli.db'}"
    db = ["--database-url", url]
    assert (
        run_cli("drones", "add", "alpha", "tcpout://127.0.0.1:5760", "--name", "Alpha", "--tag", "a", *db)
        == 0
    )
    assert (
        run_cli("drones", "add", "bravo", "udpin://0.0.0.0:14541", "--sysid", "2", "--no-connect", *db) == 0
    )
    capsys.readouterr()

    assert run_cli("drones", "list", "--json", *db) == 0
    listed = json.loads(capsys.readouterr().out)
    assert [(d["id"], d["name"], d["tags"], d["auto_connect"]) for d in listed] == [
        ("alpha", "Alpha", ["a"], True),
        ("bravo", None, [], False),
    ]
    assert run_cli("drones", "list", *db) == 0
    table = capsys.readouterr().out.splitlines()
    assert table[0].split()[:2] == ["ID", "URL"] and table[1].startswith("alpha")

    assert run_cli("drones", "add", "alpha", "tcpout://127.0.0.1:5770", *db) == 1
    assert "already registered" in capsys.readouterr().err
    # provisioning scripts re-run: --if-missing succeeds and changes nothing
    assert run_cli("drones", "add", "alpha", "tcpout://127.0.0.1:5770", "--if-missing", *db) == 0
    assert "alpha is already registered; left as it is" in capsys.readouterr().out
    assert run_cli("drones", "add", "Bad!", "tcpout://127.0.0.1:5770", *db) == 2
    assert "id:" in capsys.readouterr().err
    assert run_cli("drones", "add", "charlie", "http://x", *db) == 2
    assert "url:" in capsys.readouterr().err

    assert run_cli("drones", "remove", "bravo", *db) == 0
    assert run_cli("drones", "remove", "bravo", *db) == 1
    assert "no drone with id 'bravo'" in capsys.readouterr().err

    async def ids() -> list[str]:
        store = await Store.open(url)
        try:
            return [v.id for v in await store.list_vehicles()]
        finally:
            await store.close()

    assert asyncio.run(ids()) == ["alpha"]

    async def url_of_alpha() -> str:
        store = await Store.open(url)
        try:
            record = await store.get_vehicle("alpha")
            assert record is not None
            return record.url
        finally:
            await store.close()

    assert asyncio.run(url_of_alpha()) == "tcpout://127.0.0.1:5760"


def test_drones_through_a_running_gateway(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    settings = Settings(database_url=f"sqlite+aiosqlite:///{tmp_path / 'api.db'}")
    app = create_app(settings, registry_factory=FakeRegistry)
    with serve_in_thread(app) as base:
        assert run_cli("drones", "add", "alpha", "tcpout://127.0.0.1:5760", "--api", base) == 0
        assert "registered alpha" in capsys.readouterr().out
        assert run_cli("drones", "add", "alpha", "tcpout://127.0.0.1:5760", "--api", base) == 1
        assert "(duplicate_vehicle)" in capsys.readouterr().err
        assert (
            run_cli("drones", "add", "alpha", "tcpout://127.0.0.1:5999", "--if-missing", "--api", base) == 0
        )
        assert "already registered; left as it is" in capsys.readouterr().out
        assert run_cli("drones", "list", "--json", "--api", base) == 0
        [drone] = json.loads(capsys.readouterr().out)
        assert drone["id"] == "alpha" and drone["state"] == "connecting"
        assert run_cli("drones", "remove", "ghost", "--api", base) == 1
        assert "unknown drone id 'ghost'" in capsys.readouterr().err
        assert run_cli("drones", "remove", "alpha", "--api", base) == 0
    port_closed = run_cli("drones", "list", "--api", base)
    assert port_closed == 1 and "cannot reach the gateway" in capsys.readouterr().err


def test_registration_waits_for_a_gateway_still_starting(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """`drones add --api URL --wait S` started before the gateway listens (as podman-compose starts the
    compose file's registrars) registers once the gateway is ready."""
    port = free_tcp_port()
    base = f"http://127.0.0.1:{port}"
    codes: list[int] = []
    argv = ["drones", "add", "alpha", "tcpout://127.0.0.1:5760", "--api", base, "--wait", str(scaled(120))]
    registrar = threading.Thread(target=lambda: codes.append(run_cli(*argv)))
    registrar.start()
    try:
        time.sleep(1.0)  # the registrar asks a closed port meanwhile
        assert registrar.is_alive(), capsys.readouterr()
        settings = Settings(database_url=f"sqlite+aiosqlite:///{tmp_path / 'late.db'}")
        with serve_in_thread(create_app(settings, registry_factory=FakeRegistry), port=port):
            registrar.join(timeout=scaled(120))
            assert codes == [0], capsys.readouterr()
            assert "registered alpha" in capsys.readouterr().out
    finally:
        registrar.join(timeout=scaled(130))
    # nobody answers: the wait ends with one line; a bad --wait is named and nothing is called
    assert run_cli("drones", "list", "--api", base, "--wait", "0.5") == 1
    assert f"the gateway at {base} did not answer /readyz within 0.5 s (--wait)" in capsys.readouterr().err
    assert run_cli("drones", "list", "--api", base, "--wait", "-3") == 2
    assert "--wait must be a number of seconds, 0 or more; got -3.0" in capsys.readouterr().err


def test_serve_refuses_a_public_bind_without_tokens(capsys: pytest.CaptureFixture[str]) -> None:
    assert run_cli("serve", "--host", "0.0.0.0", "--port", "1") == 2
    assert "loopback only" in capsys.readouterr().err
    assert run_cli("serve", "--port", "70000") == 2
    assert "port" in capsys.readouterr().err


def test_db_prune_command(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    url = f"sqlite+aiosqlite:///{tmp_path / 'prune.db'}"

    async def seed() -> None:
        store = await Store.open(url)
        try:
            fid = await store.open_flight("alpha", datetime.now(UTC) - timedelta(days=100))
            await store.close_flight(fid, datetime.now(UTC) - timedelta(days=99))
            await store.open_flight("alpha", datetime.now(UTC))
        finally:
            await store.close()

    asyncio.run(seed())
    assert run_cli("db", "prune", "--older-than-days", "30", "--database-url", url) == 0
    assert "1 flights" in capsys.readouterr().out
    assert run_cli("db", "prune", "--older-than-days", "0", "--database-url", url) == 2
    assert "positive number of days" in capsys.readouterr().err
    assert run_cli("db", "prune", "--older-than-days", "nan", "--database-url", url) == 2


def test_drones_add_takes_ground_station_endpoints(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """`--gcs URL`, repeatable, is stored with the registration (and shown); a bad one is named in one line
    and registers nothing. Through a running gateway the same field goes over REST."""
    url = f"sqlite+aiosqlite:///{tmp_path / 'cli.db'}"
    db = ["--database-url", url]
    gcs = ["--gcs", "udpout://127.0.0.1:14550", "--gcs", "tcpin://127.0.0.1:5790"]
    assert run_cli("drones", "add", "alpha", "tcpout://127.0.0.1:5760", *gcs, *db) == 0
    assert (
        run_cli("drones", "add", "bravo", "tcpout://127.0.0.1:5770", "--gcs", "udp://127.0.0.1:1", *db) == 2
    )
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "gcs_endpoints: 'udp://127.0.0.1:1' is not accepted" in err[0], err
    assert "udpout://host:port" in err[0]
    assert run_cli("drones", "list", "--json", *db) == 0
    [alpha] = json.loads(capsys.readouterr().out)
    assert alpha["gcs_endpoints"] == ["udpout://127.0.0.1:14550", "tcpin://127.0.0.1:5790"]

    settings = Settings(database_url=f"sqlite+aiosqlite:///{tmp_path / 'api.db'}")
    app = create_app(settings, registry_factory=FakeRegistry)
    with serve_in_thread(app) as base:
        assert run_cli("drones", "add", "alpha", "tcpout://127.0.0.1:5760", *gcs[:2], "--api", base) == 0
        capsys.readouterr()
        assert run_cli("drones", "list", "--json", "--api", base) == 0
        [drone] = json.loads(capsys.readouterr().out)
        assert drone["gcs_endpoints"] == ["udpout://127.0.0.1:14550"]
