"""`fleet-gateway serve` and `fleet-gateway db upgrade|prune` (`drones` comes from gateway/drones_cli.py)."""

from __future__ import annotations

import argparse
import asyncio
import contextlib
import ipaddress
import math
import sys
from collections.abc import Iterator
from datetime import UTC, datetime, timedelta

from pydantic import ValidationError

from gateway import drones_cli
from gateway.cli_help import add_command
from gateway.cli_support import database_option, fail, settings_from, validation_text, with_store
from gateway.registry.database import (
    SchemaUpgradeFailed,
    create_engine_for,
    current_revision,
    in_memory,
    migrations_dir,
    upgrade_in_child_process,
    upgrade_schema,
)
from gateway.registry.schema_check import schema_is_current
from gateway.registry.store import Store
from gateway.startup import (
    StartupError,
    check_nats_reachable,
    check_port_free,
    check_sidecar_binary,
    describe_database_error,
    prepare_database_location,
)
from gateway.util.lean_uvicorn import Config, Server

LOOPBACK_NAMES = {"localhost"}


def register(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    serve = add_command(subparsers, "serve")
    serve.add_argument("--host", default=None, help="bind address (default GATEWAY_HOST or 127.0.0.1)")
    serve.add_argument("--port", type=int, default=None, help="HTTP port (default GATEWAY_PORT or 8765)")
    database_option(serve)
    serve.set_defaults(func=cmd_serve)

    drones_cli.register(subparsers)

    db = add_command(subparsers, "db")
    db_cmds = db.add_subparsers(dest="db_command", required=True, metavar="ACTION")
    upgrade = db_cmds.add_parser(
        "upgrade", help="upgrade the database schema (the gateway also does on start)"
    )
    upgrade.add_argument("--revision", default="head", help="target Alembic revision (default head)")
    database_option(upgrade)
    upgrade.set_defaults(func=cmd_db_upgrade)
    prune = db_cmds.add_parser(
        "prune", help="delete flights, tracks, status texts, audit and sessions older than N days"
    )
    prune.add_argument(
        "--older-than-days", type=float, required=True, metavar="DAYS", help="age limit in days"
    )
    database_option(prune)
    prune.set_defaults(func=cmd_db_prune)


def _is_loopback(host: str) -> bool:
    if host in LOOPBACK_NAMES:
        return True
    try:
        return ipaddress.ip_address(host).is_loopback
    except ValueError:
        return False


# --- serve -----------------------------------------------------------------------------------------


def cmd_serve(args: argparse.Namespace) -> int:
    from gateway.app import create_app

    try:
        settings = settings_from(args, host=args.host, port=args.port)
    except ValidationError as exc:
        return fail(validation_text(exc), 2)
    if settings.clustered:
        from gateway.cluster.node import ClusterSetupError, check_settings

        try:
            check_settings(settings)
        except ClusterSetupError as exc:
            return fail(exc.message, 2)
    if not _is_loopback(settings.host) and not settings.operator_tokens.strip():
        return fail(
            f"refusing to serve on {settings.host}: without operator tokens (GATEWAY_OPERATOR_TOKENS) "
            "the gateway binds to loopback only",
            2,
        )
    try:  # in this order: nothing is written when the port is taken
        check_port_free(settings.host, settings.port)
        check_sidecar_binary(settings)
        prepare_database_location(settings.database_url)
        if settings.clustered:
            check_nats_reachable(settings.cluster_nats_url)
        asyncio.run(_open_database(settings.database_url))
    except StartupError as exc:
        return fail(str(exc), 2)
    app = create_app(settings)
    config = Config(
        app,
        host=settings.host,
        port=settings.port,
        log_level=settings.log_level.lower(),
        lifespan="on",
        timeout_graceful_shutdown=10,
    )
    server = GatewayServer(config)
    # SIGINT/SIGTERM: uvicorn stops accepting, then the lifespan stops every sidecar; exit status 0.
    server.run()
    return 0 if server.started else 1


async def _open_database(url: str) -> None:
    """Open the database and bring its schema up to date; StartupError in one line if it cannot.

    A schema behind the code is upgraded by a child process, so that Alembic and Mako are not left
    in the serving process (an in-memory database, which no other process can reach, is upgraded by
    the gateway's own start, in this process)."""
    try:
        engine = create_engine_for(url)
        try:
            current = await schema_is_current(engine, migrations_dir())
        finally:
            await engine.dispose()
        if not current and not in_memory(url):
            await upgrade_in_child_process(url)
        store = await Store.open(url)
    except SchemaUpgradeFailed as exc:
        raise StartupError(str(exc)) from None
    except Exception as exc:
        raise StartupError(describe_database_error(url, exc)) from None
    await store.close()


class GatewayServer(Server):
    """uvicorn's server, except that the signal which stopped it cleanly is not raised again afterwards
    (uvicorn does, so the process would die of it): a clean stop exits with status 0."""

    @contextlib.contextmanager
    def capture_signals(self) -> Iterator[None]:
        with super().capture_signals():
            try:
                yield
            finally:
                captured = getattr(self, "_captured_signals", None)
                if isinstance(captured, list):
                    captured.clear()


# --- db --------------------------------------------------------------------------------------------


def cmd_db_upgrade(args: argparse.Namespace) -> int:
    try:
        settings = settings_from(args)
    except ValidationError as exc:
        return fail(validation_text(exc), 2)

    async def run() -> str | None:
        try:
            engine = create_engine_for(settings.database_url)
        except Exception as exc:
            raise StartupError(describe_database_error(settings.database_url, exc)) from None
        try:
            await upgrade_schema(engine, settings.database_url, args.revision)
            return await current_revision(engine)
        except Exception as exc:
            raise StartupError(describe_database_error(settings.database_url, exc)) from None
        finally:
            await engine.dispose()

    try:
        prepare_database_location(settings.database_url)
        revision = asyncio.run(run())
    except StartupError as exc:
        return fail(str(exc), 2)
    print(f"database at revision {revision}")
    return 0


def cmd_db_prune(args: argparse.Namespace) -> int:
    if not math.isfinite(args.older_than_days) or args.older_than_days <= 0:
        return fail(f"--older-than-days must be a positive number of days; got {args.older_than_days}", 2)
    cutoff = datetime.now(UTC) - timedelta(days=args.older_than_days)

    async def run(store: Store) -> str:
        counts = await store.prune(cutoff)
        deleted = ", ".join(f"{n} {name}" for name, n in counts.items())
        return f"deleted what was older than {cutoff.isoformat(timespec='seconds')}: {deleted}"

    return with_store(args, run)


def main(argv: list[str] | None = None) -> int:
    """Run only these commands (``python -m gateway.server_cli ...``), without the other areas' ones."""
    import logging

    parser = argparse.ArgumentParser(prog="fleet-gateway")
    register(parser.add_subparsers(dest="command", required=True, metavar="COMMAND"))
    args = parser.parse_args(argv)
    logging.basicConfig(level="INFO", format="%(asctime)s %(levelname)s %(name)s: %(message)s")
    return int(args.func(args) or 0)


if __name__ == "__main__":
    sys.exit(main())
