"""`fleet-gateway` command line: each area of the gateway registers its own subcommands.

Only the module of the command being run is imported (``fleet-gateway --help`` imports none of them):
the areas pull in uvicorn, SQLAlchemy, the MCP SDK or the OpenAI client, seconds of start-up together.
"""

from __future__ import annotations

import argparse
import logging
import sys
from collections.abc import Callable, Sequence
from types import ModuleType

from gateway.cli_help import add_command


# Each loader imports its module only when called (``--help`` imports none of them). The module's
# ``register(subparsers)`` adds its commands.
def _server_cli() -> ModuleType:
    from gateway import server_cli

    return server_cli


def _demo() -> ModuleType:
    from gateway import demo

    return demo


def _sim_cli() -> ModuleType:
    from gateway.sim import cli

    return cli


def _mcp_cli() -> ModuleType:
    from gateway.mcp import cli

    return cli


def _agent_cli() -> ModuleType:
    try:
        from fleet_agent import cli
    except ModuleNotFoundError as exc:  # the gateway's image leaves the agent host and its model client out
        if exc.name not in ("openai", "fleet_agent"):
            raise
        what = "the OpenAI client" if exc.name == "openai" else "the agent host (package fleet_agent)"
        extra = "pip install 'fleet-gateway[agent]'"
        raise SystemExit(f"error: `fleet-gateway agent` needs {what}, an optional extra: {extra}") from None
    return cli


Loader = Callable[[], ModuleType]

#: command -> the loader of the module that adds it (its one-line help is in gateway/cli_help.py)
COMMANDS: dict[str, Loader] = {
    "serve": _server_cli,
    "demo": _demo,
    "drones": _server_cli,
    "db": _server_cli,
    "sim": _sim_cli,
    "mcp-stdio": _mcp_cli,
    "agent": _agent_cli,
}
OPTIONS_WITH_VALUE = {"--log-level"}


def build_parser(command: str | None = None) -> argparse.ArgumentParser:
    """The parser; the full subcommands of ``command``'s module, one-line placeholders for the rest."""
    parser = argparse.ArgumentParser(
        prog="fleet-gateway",
        description="MCP gateway that lets LLMs fly a fleet of MAVLink drones under operator control.",
    )
    parser.add_argument(
        "--log-level", default=None, help="Python log level (default: GATEWAY_LOG_LEVEL or INFO)"
    )
    subparsers = parser.add_subparsers(dest="command", metavar="COMMAND")
    loaded = COMMANDS.get(command or "")
    if loaded is not None:
        loaded().register(subparsers)
    for name, loader in COMMANDS.items():
        if loader is not loaded:
            add_command(subparsers, name, add_help=False)
    return parser


def _command_word(argv: Sequence[str]) -> str | None:
    """The first word of ``argv`` that is not an option or an option's value."""
    skip = False
    for word in argv:
        if skip:
            skip = False
        elif word in OPTIONS_WITH_VALUE:
            skip = True
        elif not word.startswith("-"):
            return word
    return None


def _deepest(parser: argparse.ArgumentParser, args: argparse.Namespace) -> argparse.ArgumentParser:
    """The (sub)parser of the command that was chosen, so an error shows that command's usage."""
    while True:
        chosen = None
        for action in parser._actions:  # argparse keeps its subparsers here and nowhere public
            if isinstance(action, argparse._SubParsersAction):
                chosen = action.choices.get(getattr(args, action.dest, None) or "")
        if chosen is None:
            return parser
        parser = chosen


def main(argv: Sequence[str] | None = None) -> int:
    words = list(sys.argv[1:] if argv is None else argv)
    parser = build_parser(_command_word(words))
    args, unknown = parser.parse_known_args(words)
    if unknown:
        _deepest(parser, args).error(f"unrecognized argument(s): {' '.join(unknown)} (see --help)")
    if args.command is None:
        parser.error(f"a COMMAND is needed, one of: {', '.join(COMMANDS)} (fleet-gateway COMMAND --help)")
    from pydantic import ValidationError

    from gateway.config import get_settings

    try:
        configured = get_settings().log_level
    except ValidationError:  # a wrong setting: the command itself names it, in one line
        configured = "INFO"
    level = (args.log_level or configured).upper()
    logging.basicConfig(level=level, format="%(asctime)s %(levelname)s %(name)s: %(message)s")
    if level != "DEBUG":  # schema upgrades say "Context impl SQLiteImpl" and the like on every start
        logging.getLogger("alembic").setLevel(logging.WARNING)
    try:
        result = args.func(args)
    except KeyboardInterrupt:
        return 130
    finally:
        if argv is None:  # the process's own command line: the process exits next
            from gateway.util.heap import leave_heap_to_exit

            leave_heap_to_exit()
    return int(result or 0)


if __name__ == "__main__":
    sys.exit(main())
