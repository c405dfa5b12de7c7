"""Fault-injection control API of a running simulator: a tiny JSON-over-HTTP server on loopback, and
its client ``SimControl``.

Routes (vehicle = index 0..N-1):
  GET  /vehicles                         -> [state, ...]
  GET  /vehicles/{i}                     -> state (true position, mode, armed, battery, faults ...)
  GET  /vehicles/{i}/statustexts         -> [[t_boot_s, severity, text], ...]
  GET  /vehicles/{i}/record              -> what reached the vehicle and what it did (``gateway.sim.record``)
  POST /vehicles/{i}/record      {}      (start a new record; the first home is kept)
  POST /vehicles/{i}/link        {"up": bool}
  POST /vehicles/{i}/packet_loss {"pct": 0..100}
  POST /vehicles/{i}/gps         {"ok": bool}
  POST /vehicles/{i}/estimate    {"held": bool}   (the EKF's position estimate held back: GPS and home kept)
  POST /vehicles/{i}/battery     {"pct": 0..100}
  POST /vehicles/{i}/param       {"name": str, "value": number}   (as if set by a GCS, without MAVLink)
  POST /vehicles/{i}/mission_capacity {"items": int | null}   (storage, home included; null: unlimited)
  POST /vehicles/{i}/reboot      {}    (restart: boot timeline from zero, stream rates lost, clients dropped)
Errors answer 400/404 with {"error": "..."}.
"""

from __future__ import annotations

import asyncio
import contextlib
import json
import math
from collections.abc import Callable
from typing import Any

import httpx

from gateway.sim.fleet import SimFleet
from gateway.sim.params import ParamError
from gateway.sim.vehicle import SimVehicle

_MAX_BODY = 65536


class ControlError(Exception):
    def __init__(self, status: int, message: str) -> None:
        super().__init__(message)
        self.status = status


class ControlServer:
    def __init__(self, fleet: SimFleet, host: str = "127.0.0.1", port: int = 0) -> None:
        self.fleet = fleet
        self.host, self.port = host, port
        self._server: asyncio.base_events.Server | None = None

    @property
    def url(self) -> str:
        return f"http://{self.host}:{self.port}"

    async def start(self) -> None:
        self._server = await asyncio.start_server(self._client, self.host, self.port)
        self.port = self._server.sockets[0].getsockname()[1]

    async def stop(self) -> None:
        if self._server is not None:
            self._server.close()
            with contextlib.suppress(Exception):
                await self._server.wait_closed()
            self._server = None

    async def _client(self, reader: asyncio.StreamReader, writer: asyncio.StreamWriter) -> None:
        try:
            while True:
                request_line = await reader.readline()
                if not request_line:
                    break
                method, path, _ = request_line.decode("latin-1").split(" ", 2)
                headers: dict[str, str] = {}
                while True:
                    line = (await reader.readline()).decode("latin-1").strip()
                    if not line:
                        break
                    key, _, value = line.partition(":")
                    headers[key.strip().lower()] = value.strip()
                length = int(headers.get("content-length", "0") or 0)
                if length > _MAX_BODY:
                    status, payload = 413, {"error": "request body too large"}
                    body = b""
                else:
                    body = await reader.readexactly(length) if length else b""
                    try:
                        status, payload = 200, self._route(method.upper(), path.split("?", 1)[0], body)
                    except ControlError as exc:
                        status, payload = exc.status, {"error": str(exc)}
                data = json.dumps(payload).encode()
                reason = {200: "OK", 400: "Bad Request", 404: "Not Found", 405: "Method Not Allowed"}.get(
                    status, "Error"
                )
                writer.write(
                    f"HTTP/1.1 {status} {reason}\r\nContent-Type: application/json\r\n"
                    f"Content-Length: {len(data)}\r\n\r\n".encode()
                    + data
                )
                await writer.drain()
                if headers.get("connection", "").lower() == "close":
                    break
        except (ConnectionError, asyncio.IncompleteReadError, ValueError):
            pass
        finally:
            writer.close()

    def _route(self, method: str, path: str, body: bytes) -> object:
        parts = [p for p in path.split("/") if p]
        if parts == ["vehicles"] and method == "GET":
            return self.fleet.describe()
        if len(parts) < 2 or parts[0] != "vehicles":
            raise ControlError(404, f"no route {method} {path}")
        try:
            vehicle = self.fleet.vehicle(parts[1])
        except KeyError as exc:
            raise ControlError(404, str(exc.args[0])) from None
        action = parts[2] if len(parts) > 2 else None
        if method == "GET":
            return _get(vehicle, action, path)
        if method != "POST":
            raise ControlError(405, f"method {method} not allowed")
        args = _json_object(body)
        setter = _POSTS.get(action or "")
        if setter is None:
            raise ControlError(404, f"no route POST {path}")
        setter(vehicle, args)
        return vehicle.state()


def _get(vehicle: SimVehicle, action: str | None, path: str) -> object:
    if action is None:
        return vehicle.state()
    if action == "statustexts":
        return [[round(t, 3), sev, text] for t, sev, text in vehicle.status_texts]
    if action == "record":
        return vehicle.record.describe(vehicle)
    raise ControlError(404, f"no route GET {path}")


def _json_object(body: bytes) -> dict:
    try:
        args = json.loads(body or b"{}")
    except json.JSONDecodeError as exc:
        raise ControlError(400, f"body is not JSON: {exc}") from None
    if not isinstance(args, dict):
        raise ControlError(400, "body must be a JSON object")
    return args


def _post_mode(vehicle: SimVehicle, args: dict) -> None:
    """A pilot's RC switch or another ground station (not the gateway)."""
    name, text = args.get("mode"), args.get("text")
    if not isinstance(name, str) or (text is not None and not isinstance(text, str)):
        raise ControlError(400, "'mode' must be a mode name and 'text' (optional) a string")
    try:
        vehicle.pilot_mode(name, text)
    except ValueError as exc:
        raise ControlError(400, str(exc)) from None


def _post_mission_capacity(vehicle: SimVehicle, args: dict) -> None:
    items = args.get("items")
    if items is not None and (isinstance(items, bool) or not isinstance(items, int)):
        raise ControlError(400, "'items' must be a whole number of mission items or null")
    _call(vehicle.set_mission_capacity, items)


def _post_param(vehicle: SimVehicle, args: dict) -> None:
    name = args.get("name")
    if not isinstance(name, str):
        raise ControlError(400, "'name' must be a parameter name string")
    try:
        param = vehicle.params.set(name, _number(args, "value"))
    except ParamError as exc:
        raise ControlError(400, str(exc)) from None
    vehicle.broadcast(vehicle.param_value(param))


_POSTS: dict[str, Callable[[SimVehicle, dict], None]] = {
    "link": lambda vehicle, args: vehicle.set_link(_bool(args, "up")),
    "packet_loss": lambda vehicle, args: _call(vehicle.set_packet_loss, _number(args, "pct")),
    "gps": lambda vehicle, args: vehicle.set_gps(_bool(args, "ok")),
    "estimate": lambda vehicle, args: vehicle.hold_estimate(_bool(args, "held")),
    "battery": lambda vehicle, args: _call(vehicle.set_battery, _number(args, "pct")),
    "reboot": lambda vehicle, args: vehicle.reboot(),
    "record": lambda vehicle, args: vehicle.record.reset(),
    "mode": _post_mode,
    "mission_capacity": _post_mission_capacity,
    "param": _post_param,
}


def _bool(args: dict, key: str) -> bool:
    value = args.get(key)
    if not isinstance(value, bool):
        raise ControlError(400, f"'{key}' must be true or false, got {value!r}")
    return value


def _number(args: dict, key: str) -> float:
    value = args.get(key)
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
        raise ControlError(400, f"'{key}' must be a finite number, got {value!r}")
    return float(value)


def _call(fn, value: float) -> None:
    try:
        fn(value)
    except ValueError as exc:
        raise ControlError(400, str(exc)) from None


class SimControl:
    """Client of a simulator's control API (``fleet-gateway sim --control-port P``).

    All methods are async and take the vehicle index (0..N-1); setters return the vehicle's new state.
    Raises ``httpx.HTTPStatusError`` on a refused request (its response JSON holds ``error``).
    """

    def __init__(self, base_url: str, timeout: float = 10.0) -> None:
        self.base_url = base_url.rstrip("/")
        self._client = httpx.AsyncClient(base_url=self.base_url, timeout=timeout)

    async def aclose(self) -> None:
        await self._client.aclose()

    async def __aenter__(self) -> SimControl:
        return self

    async def __aexit__(self, *exc) -> None:
        await self.aclose()

    async def _get(self, path: str) -> Any:  # Any: httpx, the decoded JSON answer
        response = await self._client.get(path)
        response.raise_for_status()
        return response.json()

    async def _post(self, path: str, body: dict) -> dict:
        response = await self._client.post(path, json=body)
        response.raise_for_status()
        return response.json()

    async def vehicles(self) -> list[dict]:
        return await self._get("/vehicles")

    async def state(self, index: int) -> dict:
        """True state: lat, lon, alt_amsl_m, rel_alt_m, mode, armed, landed, battery_pct, faults ..."""
        return await self._get(f"/vehicles/{index}")

    async def status_texts(self, index: int) -> list[tuple[float, int, str]]:
        return [tuple(x) for x in await self._get(f"/vehicles/{index}/statustexts")]

    async def link_down(self, index: int) -> dict:
        return await self._post(f"/vehicles/{index}/link", {"up": False})

    async def link_up(self, index: int) -> dict:
        return await self._post(f"/vehicles/{index}/link", {"up": True})

    async def set_packet_loss(self, index: int, pct: float) -> dict:
        return await self._post(f"/vehicles/{index}/packet_loss", {"pct": pct})

    async def gps_loss(self, index: int, lost: bool = True) -> dict:
        return await self._post(f"/vehicles/{index}/gps", {"ok": not lost})

    async def hold_estimate(self, index: int, held: bool = True) -> dict:
        """Hold the EKF's position estimate back (or release it): GUIDED arming refused meanwhile."""
        return await self._post(f"/vehicles/{index}/estimate", {"held": held})

    async def set_battery(self, index: int, pct: float) -> dict:
        return await self._post(f"/vehicles/{index}/battery", {"pct": pct})

    async def pilot_mode(self, index: int, mode: str, text: str | None = None) -> dict:
        """Switch mode as a pilot or another ground station would; ``text``: a STATUSTEXT said first."""
        return await self._post(f"/vehicles/{index}/mode", {"mode": mode, "text": text})

    async def record(self, index: int) -> dict:
        """What reached the vehicle since ``reset_record`` and what it did (``gateway.sim.record``)."""
        return await self._get(f"/vehicles/{index}/record")

    async def reset_record(self, index: int) -> dict:
        return await self._post(f"/vehicles/{index}/record", {})

    async def reboot(self, index: int) -> dict:
        """Restart the vehicle like an autopilot reboot (stream rates are lost; TCP clients reconnect)."""
        return await self._post(f"/vehicles/{index}/reboot", {})

    async def set_param(self, index: int, name: str, value: float) -> dict:
        return await self._post(f"/vehicles/{index}/param", {"name": name, "value": value})

    async def set_mission_capacity(self, index: int, items: int | None) -> dict:
        """Mission storage in items, home included (None: unlimited): longer uploads get NO_SPACE."""
        return await self._post(f"/vehicles/{index}/mission_capacity", {"items": items})
