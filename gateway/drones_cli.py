"""`fleet-gateway drones add|list|remove|mission|release`: the registered drones, in the database or
through a running gateway's REST API (``--api URL``)."""

from __future__ import annotations

import argparse
import contextlib
import json
import math
import os
import sys
import time
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any

from pydantic import ValidationError

from gateway.cli_help import add_command
from gateway.cli_support import database_option, fail, validation_text, with_store
from gateway.config import Settings
from gateway.errors import DuplicateVehicle
from gateway.registry.spec import VehicleSpec
from gateway.registry.store import Store
from gateway.util.json_types import JsonObject, JsonValue

if TYPE_CHECKING:  # httpx (and its CLI extras rich, pygments) is imported by the commands that call the API
    import httpx


def register(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    drones = add_command(subparsers, "drones")
    drone_cmds = drones.add_subparsers(dest="drones_command", required=True, metavar="ACTION")

    add = drone_cmds.add_parser("add", help="register a drone")
    # each option's dest is the VehicleSpec field it fills (`_spec_from_args`)
    add.add_argument("id", help="drone id: 1-32 of a-z, 0-9, '-'")
    add.add_argument("url", help="MAVLink URL in mavsdk_server syntax, e.g. tcpout://127.0.0.1:5760")
    add.add_argument("--name", default=None, help="human-readable name")
    add.add_argument(
        "--sysid",
        dest="expected_sysid",
        metavar="SYSID",
        type=int,
        default=None,
        help="MAVLink system id the drone must report",
    )
    add.add_argument(
        "--tag", dest="tags", metavar="TAG", action="append", default=[], help="a tag (repeatable)"
    )
    add.add_argument(
        "--node-tag", default=None, help="cluster: only nodes carrying this tag own the drone (e.g. a site)"
    )
    add.add_argument(
        "--gcs",
        dest="gcs_endpoints",
        action="append",
        default=[],
        metavar="URL",
        help="a ground station endpoint the drone's MAVLink is relayed to, e.g. udpout://127.0.0.1:14550 "
        "or tcpin://127.0.0.1:5790 (repeatable; README: Ground stations beside the gateway)",
    )
    add.add_argument("--no-connect", action="store_true", help="register without connecting")
    add.add_argument(
        "--if-missing",
        action="store_true",
        help="succeed without change when the id is already registered (for provisioning scripts)",
    )
    _target_options(add)
    add.set_defaults(func=cmd_drones_add)

    lst = drone_cmds.add_parser("list", help="list registered drones")
    lst.add_argument("--json", action="store_true", help="print JSON instead of a table")
    _target_options(lst)
    lst.set_defaults(func=cmd_drones_list)

    remove = drone_cmds.add_parser("remove", help="remove a drone")
    remove.add_argument("id", help="drone id")
    _target_options(remove)
    remove.set_defaults(func=cmd_drones_remove)

    mission = drone_cmds.add_parser(
        "mission", help="a drone's mission as a ground station's file (QGC .plan or QGC WPL 110), in or out"
    )
    mission_cmds = mission.add_subparsers(dest="mission_command", required=True, metavar="ACTION")
    put = mission_cmds.add_parser(
        "put", help="store a mission file on a connected drone (checked like any mission)"
    )
    put.add_argument("id", help="drone id")
    put.add_argument("file", help="a .plan (JSON) or QGC WPL 110 waypoint file; - reads standard input")
    put.add_argument(
        "--format", choices=("plan", "waypoints"), default=None, help="default: told from the file"
    )
    _target_options(put)
    put.set_defaults(func=cmd_drones_mission_put)
    get = mission_cmds.add_parser("get", help="write a connected drone's mission as a file")
    get.add_argument("id", help="drone id")
    get.add_argument("--format", choices=("plan", "waypoints"), default="plan", help="default: plan")
    get.add_argument("--output", "-o", default=None, help="file to write (default: standard output)")
    _target_options(get)
    get.set_defaults(func=cmd_drones_mission_get)

    release = drone_cmds.add_parser(
        "release",
        help="give a drone taken over by a pilot or ground station back to agents (docs/safety.md)",
    )
    release.add_argument("id", help="drone id")
    _target_options(release)
    release.set_defaults(func=cmd_drones_release)


def _target_options(parser: argparse.ArgumentParser) -> None:
    database_option(parser)
    parser.add_argument(
        "--api",
        default=None,
        metavar="URL",
        help="talk to a running gateway's REST API (e.g. http://127.0.0.1:8765) instead of the database",
    )
    parser.add_argument(
        "--token",
        default=None,
        help="bearer token for --api (default: GATEWAY_API_TOKEN, else the first of GATEWAY_OPERATOR_TOKENS)",
    )
    parser.add_argument(
        "--wait",
        type=float,
        default=0.0,
        metavar="SECONDS",
        help="with --api: wait up to SECONDS for the gateway to answer /readyz before the call (for "
        "provisioning beside a gateway that is still starting; default 0: call at once)",
    )


def _spec_from_args(args: argparse.Namespace) -> VehicleSpec:
    """The drone `drones add` names: its options' dests are VehicleSpec's fields."""
    return VehicleSpec.model_validate({k: v for k, v in vars(args).items() if k in VehicleSpec.model_fields})


def cmd_drones_add(args: argparse.Namespace) -> int:
    try:
        spec = _spec_from_args(args)
    except ValidationError as exc:
        return fail(f"invalid drone: {validation_text(exc)}", 2)
    connect = not args.no_connect
    already = f"{spec.id} is already registered; left as it is"
    if args.api:
        body = {**spec.model_dump(), "connect": connect}
        return _api_call(
            args,
            "POST",
            "/api/v1/vehicles",
            body,
            lambda d: f"registered {d['id']} ({d['url']})",
            ok_codes={DuplicateVehicle.code: already} if args.if_missing else None,
        )

    async def run(store: Store) -> str:
        try:
            record = await store.add_vehicle(spec, auto_connect=connect)
        except DuplicateVehicle:
            if args.if_missing:
                return already
            raise
        return f"registered {record.id} ({record.url}); a running gateway picks it up on its next start"

    return with_store(args, run)


def cmd_drones_list(args: argparse.Namespace) -> int:
    if args.api:
        return _api_call(args, "GET", "/api/v1/vehicles", None, lambda d: _table(d["items"], args.json))

    async def run(store: Store) -> str:
        records = [r.model_dump(mode="json") for r in await store.list_vehicles()]
        return _table(records, args.json)

    return with_store(args, run)


def cmd_drones_remove(args: argparse.Namespace) -> int:
    if args.api:
        return _api_call(args, "DELETE", f"/api/v1/vehicles/{args.id}", None, lambda _d: f"removed {args.id}")

    async def run(store: Store) -> str:
        await store.remove_vehicle(args.id)
        return f"removed {args.id}"

    return with_store(args, run)


def _mission_request(
    args: argparse.Namespace,
    method: str,
    params: Mapping[str, str],
    content: bytes | None = None,
    content_type: str | None = None,
) -> httpx.Response | int:
    """A mission-file request to the running gateway; an int is the exit code of a failure (printed)."""
    if not args.api:
        return fail("drones mission needs --api URL: the file goes to (or comes from) a connected drone", 2)
    token = _api_token(args)
    headers = {"Authorization": f"Bearer {token}"} if token else {}
    if content_type is not None:
        headers["content-type"] = content_type
    url = f"{args.api.rstrip('/')}/api/v1/vehicles/{args.id}/mission"
    import httpx

    try:
        response = httpx.request(method, url, headers=headers, timeout=60.0, params=params, content=content)
    except httpx.HTTPError as exc:
        return fail(f"cannot reach the gateway at {args.api}: {exc}")
    if response.status_code >= 400:
        try:
            error = response.json()["error"]
            return fail(f"{error['message']} ({error['code']})")
        except (ValueError, KeyError, TypeError):
            return fail(f"HTTP {response.status_code}: {response.text[:200]}")
    return response


def cmd_drones_mission_put(args: argparse.Namespace) -> int:
    try:
        text = sys.stdin.read() if args.file == "-" else Path(args.file).read_text(encoding="utf-8-sig")
    except (OSError, UnicodeDecodeError) as exc:
        return fail(f"cannot read the mission file {args.file}: {exc}", 2)
    params = {"format": args.format} if args.format else {}
    kind = "application/json" if text.lstrip().startswith("{") else "text/plain"
    response = _mission_request(args, "PUT", params, content=text.encode(), content_type=kind)
    if isinstance(response, int):
        return response
    print(f"{args.id}: {response.json()['message']}")
    return 0


def cmd_drones_mission_get(args: argparse.Namespace) -> int:
    response = _mission_request(args, "GET", {"format": args.format})
    if isinstance(response, int):
        return response
    if args.output:
        Path(args.output).write_text(response.text, encoding="utf-8")
        print(f"{args.id}: mission written to {args.output} ({args.format})")
    else:
        print(response.text, end="")
    return 0


def cmd_drones_release(args: argparse.Namespace) -> int:
    def said(was_locked: bool) -> str:
        return (
            f"released {args.id}: agents may command it again"
            if was_locked
            else f"{args.id} was not taken over"
        )

    if args.api:
        return _api_call(
            args,
            "DELETE",
            f"/api/v1/vehicles/{args.id}/takeover",
            None,
            lambda d: said(bool(d["was_locked"])),
        )

    async def run(store: Store) -> str:
        if not await store.delete_takeover(args.id):
            return said(False)
        return (
            said(True) + " after the gateway's next start (use --api URL to release it in a running gateway)"
        )

    return with_store(args, run)


def _table(items: list[JsonObject], as_json: bool) -> str:  # JSON rows, as REST sends them
    if as_json:
        return json.dumps(items, indent=2)
    if not items:
        return "no drones registered"
    columns = ["id", "url", "name", "tags", "expected_sysid", "auto_connect", "state"]
    rows = [[_cell(item.get(c)) for c in columns] for item in items]
    widths = [max(len(c), *(len(r[i]) for r in rows)) for i, c in enumerate(columns)]
    lines = ["  ".join(c.upper().ljust(w) for c, w in zip(columns, widths, strict=True))]
    lines += ["  ".join(v.ljust(w) for v, w in zip(row, widths, strict=True)) for row in rows]
    return "\n".join(line.rstrip() for line in lines)


def _cell(value: JsonValue) -> str:
    """A table cell: a list (the tags) comma-separated, nothing for null."""
    if isinstance(value, list):
        return ",".join(str(v) for v in value)
    return "" if value is None else str(value)


def _api_token(args: argparse.Namespace) -> str | None:
    if args.token:
        return str(args.token)
    if os.environ.get("GATEWAY_API_TOKEN"):
        return os.environ["GATEWAY_API_TOKEN"]
    try:
        operators = [t.strip() for t in Settings().operator_tokens.split(",") if t.strip()]
    except ValidationError:
        return None
    return operators[0] if operators else None


def _api_call(
    args: argparse.Namespace,
    method: str,
    path: str,
    body: Mapping[str, object] | None,
    render: Callable[[Any], str],  # Any: httpx, the decoded JSON answer
    ok_codes: dict[str, str] | None = None,
) -> int:
    """Call the gateway's REST API; an error whose code is in ``ok_codes`` prints its text and succeeds."""
    base = args.api
    token = _api_token(args)
    headers = {"Authorization": f"Bearer {token}"} if token else {}
    if not math.isfinite(args.wait) or args.wait < 0:
        return fail(f"--wait must be a number of seconds, 0 or more; got {args.wait}", 2)
    if args.wait > 0 and not _wait_ready(base, args.wait):
        return fail(f"the gateway at {base} did not answer /readyz within {args.wait:g} s (--wait)")
    import httpx

    try:
        response = httpx.request(method, base.rstrip("/") + path, json=body, headers=headers, timeout=30.0)
    except httpx.HTTPError as exc:
        return fail(f"cannot reach the gateway at {base}: {exc}")
    if response.status_code >= 400:
        try:
            error = response.json()["error"]
            if ok_codes and error["code"] in ok_codes:
                print(ok_codes[error["code"]])
                return 0
            return fail(f"{error['message']} ({error['code']})")
        except (ValueError, KeyError, TypeError):
            return fail(f"HTTP {response.status_code}: {response.text[:200]}")
    print(render(response.json() if response.content else None))
    return 0


def _wait_ready(base: str, wait_s: float) -> bool:
    """True once ``base``/readyz answers 200, False if it has not within ``wait_s`` seconds."""
    import httpx

    deadline = time.monotonic() + wait_s
    while True:
        with contextlib.suppress(httpx.HTTPError):
            if httpx.get(base.rstrip("/") + "/readyz", timeout=5.0).status_code == 200:
                return True
        if time.monotonic() >= deadline:
            return False
        time.sleep(min(1.0, max(0.0, deadline - time.monotonic())))
