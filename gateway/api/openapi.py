"""The OpenAPI document at /openapi.json: operation ids, the bearer scheme and the error responses.

FastAPI documents what a route returns when it succeeds and a 422 of its own shape. This adds what the
gateway really answers besides: the one error body (``gateway.api.errors``) for every error status, the
bearer scheme of ``gateway.api.deps.authorize`` (401 without a valid token when tokens are configured;
403 for a viewer token on anything but a read), 404 on routes that name a vehicle, flight, operation or
zone, 409 where the vehicle's state or an existing registration conflicts, 403/409/502 on the commands
the Commander sends to a drone (a safety refusal, a drone not ready, the autopilot's refusal), and 503
while the gateway starts or stops. Operation ids are the route functions' names (``list_vehicles``).
"""

from __future__ import annotations

import json
from typing import Any  # FastAPI's OpenAPI document is plain JSON: get_openapi returns dict[str, Any]

from fastapi import FastAPI
from fastapi.openapi.utils import get_openapi
from fastapi.routing import APIRoute

from gateway.util.json_types import JsonObject

ERROR_SCHEMA: dict[str, object] = {
    "title": "Error",
    "type": "object",
    "required": ["error"],
    "properties": {
        "error": {
            "type": "object",
            "required": ["code", "message"],
            "properties": {
                "code": {
                    "type": "string",
                    "description": "Stable machine-readable code, e.g. unknown_vehicle.",
                },
                "message": {
                    "type": "string",
                    "description": "One line saying what was wrong and what is accepted.",
                },
                "details": {
                    "type": "object",
                    "description": "Structured details (fields, rule, numbers), when there are any.",
                },
            },
        }
    },
}

_WHY = {
    "400": "The body is not valid JSON (or not readable as the declared content type).",
    "401": "No token, or an unknown one, while operator or viewer tokens are configured.",
    "403": "A viewer token on a route that changes something.",
    "404": "No such vehicle, flight, operation, zone or parameter.",
    "409": "The vehicle's state or an existing registration conflicts with the request.",
    "422": "An argument is invalid: the message names it, what was given and what is accepted.",
    "502": "The autopilot refused the command (its own words are in the message).",
    "503": "The gateway is starting or stopping, or the vehicle's owner node cannot be reached.",
}
_COMMAND_TAGS = {"operator control"}
_CONFLICTS = {("post", "/api/v1/vehicles")}
BEARER = "bearer"
#: the paths behind `gateway.api.deps.authorize`: the API (its router's dependency) and /metrics
SECURED = ("/api/v1", "/metrics")


def operation_id(route: APIRoute) -> str:
    """The route function's name: readable, and unique (checked by the tests)."""
    return route.name


def _responses(method: str, path: str, operation: dict[str, object]) -> dict[str, str]:
    codes = {"401": _WHY["401"], "422": _WHY["422"], "503": _WHY["503"]}
    if "requestBody" in operation:
        codes["400"] = _WHY["400"]
    if method not in ("get", "head", "options"):
        codes["403"] = _WHY["403"]
    if "{" in path:
        codes["404"] = _WHY["404"]
    if (method, path) in _CONFLICTS:
        codes["409"] = "A vehicle with this id is already registered."
    tags = operation.get("tags")
    if isinstance(tags, list) and _COMMAND_TAGS & set(tags):
        codes["403"] = "A safety rule refused the command (details.rule names it), or a viewer token."
        codes["409"] = (
            "The vehicle is not ready, or its state makes the command moot (a land for a drone on the "
            "ground): the message says its state."
        )
        codes["502"] = _WHY["502"]
    return codes


def build_openapi(app: FastAPI) -> dict[str, object]:
    schema = get_openapi(title=app.title, version=app.version, description=app.description, routes=app.routes)
    components = schema.setdefault("components", {})
    components.setdefault("schemas", {})["Error"] = ERROR_SCHEMA
    components["securitySchemes"] = {
        BEARER: {
            "type": "http",
            "scheme": "bearer",
            "description": "An operator token (everything) or a viewer token (reads only), from "
            "GATEWAY_OPERATOR_TOKENS / GATEWAY_VIEWER_TOKENS. With none configured the API is open "
            "and the gateway listens on loopback only.",
        }
    }
    error_ref = {"application/json": {"schema": {"$ref": "#/components/schemas/Error"}}}
    for path, item in schema.get("paths", {}).items():
        if not path.startswith(SECURED):
            continue
        for method, operation in item.items():
            operation["security"] = [{BEARER: []}]
            responses = operation.setdefault("responses", {})
            codes = (
                _responses(method, path, operation) if path.startswith("/api/v1") else {"401": _WHY["401"]}
            )
            for code, why in codes.items():
                responses[code] = {"description": why, "content": error_ref}
    for item in schema.get("paths", {}).values():
        for operation in item.values():
            _type_responses(operation.get("responses", {}), error_ref)
    components["schemas"].pop("HTTPValidationError", None)
    components["schemas"].pop("ValidationError", None)
    # pydantic keeps JsonValue's (untyped) definition where every use of it is a DocumentedJsonObject
    if '"#/components/schemas/JsonValue"' not in json.dumps(schema):
        components["schemas"].pop("JsonValue", None)
    return schema


#: the body schema of a media type a route declares without one (a file, a stream, a free JSON object)
_MEDIA_SCHEMAS: dict[str, JsonObject] = {
    "application/json": {"type": "object"},
    "application/geo+json": {"type": "object"},
    "application/octet-stream": {"type": "string", "format": "binary"},
}
_TEXT_SCHEMA: JsonObject = {"type": "string"}


# Any: FastAPI, the OpenAPI document as get_openapi builds it
def _type_responses(responses: dict[str, Any], error_ref: dict[str, Any]) -> None:
    """Every response body typed: an error status a route declares (``responses={404: ...}``) gets the
    one error body; a file or stream without a schema gets its media type's."""
    for code, response in responses.items():
        if code[:1] in "45" and "content" not in response:
            response["content"] = error_ref
        for media, content in response.get("content", {}).items():
            body = content.get("schema")
            if not body or not set(body) & {"type", "$ref", "anyOf", "oneOf", "allOf"}:
                typed: JsonObject = dict(body) if body else {}
                typed.update(_MEDIA_SCHEMAS.get(media, _TEXT_SCHEMA))
                content["schema"] = typed


def install_openapi(app: FastAPI) -> None:
    """Serve :func:`build_openapi`'s document (built once, on first request)."""

    def openapi() -> dict[str, object]:
        if app.openapi_schema is None:
            app.openapi_schema = build_openapi(app)
        return app.openapi_schema

    app.openapi = openapi  # type: ignore[method-assign]
