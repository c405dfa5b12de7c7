"""What the ``serve``, ``drones`` and ``db`` commands share: settings from their options, the store they
open, and errors in one line."""

from __future__ import annotations

import argparse
import asyncio
import sys
from collections.abc import Awaitable, Callable
from typing import Any

from pydantic import ValidationError

from gateway.config import Settings
from gateway.errors import GatewayError
from gateway.registry.store import Store
from gateway.startup import StartupError, describe_database_error, prepare_database_location


def database_option(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "--database-url", default=None, help="SQLAlchemy async URL (default GATEWAY_DATABASE_URL)"
    )


# Any: pydantic-settings, which types the keyword arguments of Settings by its own fields
def settings_from(args: argparse.Namespace, **overrides: Any) -> Settings:
    """Settings from the environment, with the options given on the command line (None: not given)."""
    values = {k: v for k, v in overrides.items() if v is not None}
    if getattr(args, "database_url", None):
        values["database_url"] = args.database_url
    return Settings(**values)


def fail(message: str, code: int = 1) -> int:
    print(f"error: {message}", file=sys.stderr)
    return code


def validation_text(exc: ValidationError) -> str:
    parts = []
    for err in exc.errors():
        field = ".".join(str(p) for p in err.get("loc", ()))
        message = str(err.get("msg", "")).removeprefix("Value error, ")
        parts.append(f"{field}: {message}" if field else message)
    return "; ".join(parts)


def with_store(args: argparse.Namespace, action: Callable[[Store], Awaitable[str]]) -> int:
    try:
        settings = settings_from(args)
    except ValidationError as exc:
        return fail(validation_text(exc), 2)

    async def run() -> str:
        try:
            store = await Store.open(settings.database_url)
        except Exception as exc:
            raise StartupError(describe_database_error(settings.database_url, exc)) from None
        try:
            return await action(store)
        finally:
            await store.close()

    try:
        prepare_database_location(settings.database_url)
        print(asyncio.run(run()))
    except StartupError as exc:
        return fail(str(exc), 2)
    except GatewayError as exc:
        return fail(exc.message)
    return 0
