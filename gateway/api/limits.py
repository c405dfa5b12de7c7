"""Request body size limit with the API's JSON error body (Starlette's own limiter answers plain text),
and the door of /mcp: its body limit and its Host/Origin rule, answered as JSON-RPC errors."""

from __future__ import annotations

from starlette.datastructures import Headers
from starlette.exceptions import HTTPException
from starlette.responses import JSONResponse
from starlette.types import ASGIApp, Message, Receive, Scope, Send

from gateway.api.errors import error_response
from gateway.config import Settings
from gateway.hosts import mcp_foreign_request

INVALID_REQUEST = -32600  # JSON-RPC


def mcp_body_too_large(size: int | None, limit: int) -> JSONResponse:
    """413 with a JSON-RPC error body: MCP clients show its message (the tool call's arguments were too
    big), where a plain 413 reaches the model as "Server returned an error response". ``size`` is None
    for a body without Content-Length, found too big while read."""
    request = "request" if size is None else f"request of {size} bytes"
    message = (
        f"{request} is larger than the gateway's limit of {limit} bytes "
        "(GATEWAY_MAX_REQUEST_BODY_BYTES); nothing was done: send smaller arguments"
    )
    body = {"jsonrpc": "2.0", "id": None, "error": {"code": INVALID_REQUEST, "message": message}}
    return JSONResponse(body, status_code=413)


class BodyTooLarge(HTTPException):
    def __init__(self, limit: int) -> None:
        super().__init__(status_code=413, detail=f"request body larger than the limit of {limit} bytes")


class BodyLimitMiddleware:
    """Refuse bodies over ``max_bytes``: at once when Content-Length says so, else while reading."""

    def __init__(self, app: ASGIApp, max_bytes: int) -> None:
        self.app = app
        self.max_bytes = max_bytes

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return
        declared = Headers(scope=scope).get("content-length")
        if declared is not None and declared.isdigit() and int(declared) > self.max_bytes:
            response = error_response(
                413,
                "body_too_large",
                f"request body of {declared} bytes is larger than the limit of {self.max_bytes} bytes",
                {"limit": self.max_bytes},
            )
            await response(scope, receive, send)
            return
        received = 0

        async def limited_receive() -> Message:
            nonlocal received
            message = await receive()
            if message["type"] == "http.request":
                received += len(message.get("body", b""))
                if received > self.max_bytes:
                    raise BodyTooLarge(self.max_bytes)
            return message

        await self.app(scope, limited_receive, send)


class McpBodyLimit:
    """The body limit of the MCP endpoint, answered as a JSON-RPC 413 (which MCP clients show).

    A body with a Content-Length within the limit passes untouched (the HTTP server delivers no more
    than it declares); a body without one is read whole first, as the MCP transport reads it anyway,
    and refused once it grows past the limit.
    """

    def __init__(self, app: ASGIApp, max_bytes: int) -> None:
        self.app = app
        self.max_bytes = max_bytes

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        declared = Headers(scope=scope).get("content-length")
        if declared is not None and declared.isdigit():
            if int(declared) > self.max_bytes:
                await mcp_body_too_large(int(declared), self.max_bytes)(scope, receive, send)
            else:
                await self.app(scope, receive, send)
            return
        body = bytearray()
        messages: list[Message] = []
        while True:
            message = await receive()
            messages.append(message)
            if message["type"] != "http.request":
                break
            body += message.get("body", b"")
            if len(body) > self.max_bytes:
                await mcp_body_too_large(None, self.max_bytes)(scope, receive, send)
                return
            if not message.get("more_body", False):
                break
        whole: list[Message] = [{"type": "http.request", "body": bytes(body), "more_body": False}]
        whole += [m for m in messages if m["type"] != "http.request"]

        async def replay() -> Message:
            return whole.pop(0) if whole else await receive()

        await self.app(scope, replay, send)


class McpHostGuard:
    """The REST API's Host rule (and a browser's Origin) on /mcp, answered as a JSON-RPC error: one
    rule for both doors (`gateway.hosts`), where the MCP SDK's own check matched case and prefixes.
    Header values go on without the whitespace around them."""

    def __init__(self, app: ASGIApp, settings: Settings) -> None:
        self.app = app
        self.settings = settings

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        # RFC 9110 5.5: a field value is read without the whitespace around it (an Mcp-Name of
        # "  takeoff  " names takeoff); the HTTP server may hand it over with that whitespace
        scope = {**scope, "headers": [(k, v.strip(b" \t")) for k, v in scope["headers"]]}
        headers = Headers(scope=scope)
        refused = mcp_foreign_request(headers.get("host"), headers.get("origin"), self.settings)
        if refused is None:
            await self.app(scope, receive, send)
            return
        status, message = refused
        body = {"jsonrpc": "2.0", "id": None, "error": {"code": INVALID_REQUEST, "message": message}}
        await JSONResponse(body, status_code=status)(scope, receive, send)
