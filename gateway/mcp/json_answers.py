"""Plain JSON answers to single-exchange MCP requests that asked for no progress.

A 2026-07-28 request is one POST and one answer. In SSE mode the SDK runs each request's handler as a
task beside a disconnect watcher, with a memory stream between them and a timer, so that progress
notifications can be streamed before the answer: about a fifth of the CPU of a small call (a cache
read, a refused argument). Only progress is ever streamed to such a request (a 2026 request has no
back channel for sampling or elicitation, and the gateway sends no log messages), and only when the
request carries a ``progressToken``. So a request without one is answered as the SDK's JSON mode
answers it, and every other request (a progress token, a 2025-era session, a subscription stream)
goes the SDK's usual way.

What the JSON answer gives up: keep-alive pings while a silent handler runs longer than 15 s (a call
that waits for its operation, at most ``GATEWAY_MCP_WAIT_CAP_S``, 45 s by default). A client behind a
proxy with a shorter idle timeout asks for progress, and gets pings and progress again.

This uses the SDK's own entry for these requests with the session manager's own settings, through
``gateway/mcp/sdk_private.py``; ``tests/mcp/test_json_answers.py`` fails when the SDK changes them.
"""

from __future__ import annotations

from mcp.server.streamable_http_manager import StreamableHTTPSessionManager
from mcp.server.transport_security import RequestBodyLimitMiddleware
from mcp_types.version import HANDSHAKE_PROTOCOL_VERSIONS
from starlette.types import Message, Receive, Scope, Send

from gateway.mcp import sdk_private

VERSION_HEADER = b"mcp-protocol-version"


def answer_silent_requests_as_json(manager: StreamableHTTPSessionManager) -> None:
    """Route the manager's single-exchange requests without a progress token to JSON answers."""
    manager.asgi_app = RequestBodyLimitMiddleware(JsonWhenSilent(manager), manager.max_request_body_size)


class JsonWhenSilent:
    """ASGI, behind the SDK's body limit (which hands the body on whole, in one message)."""

    def __init__(self, manager: StreamableHTTPSessionManager) -> None:
        self.manager = manager

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope.get("method") != "POST" or not _single_exchange(scope):
            await sdk_private.handle_request(self.manager, scope, receive, send)
            return
        first = await receive()
        pending: list[Message] = [first]

        async def replay() -> Message:
            return pending.pop() if pending else await receive()

        if wants_no_stream(first):
            await sdk_private.answer_single_exchange_as_json(self.manager, scope, replay, send)
        else:
            await sdk_private.handle_request(self.manager, scope, replay, send)


def _single_exchange(scope: Scope) -> bool:
    """The request names a protocol version past the handshake ones (the SDK's own test for the path)."""
    version = next((v for k, v in scope.get("headers", ()) if k == VERSION_HEADER), None)
    return version is not None and version.decode("latin-1") not in HANDSHAKE_PROTOCOL_VERSIONS


def wants_no_stream(message: Message) -> bool:
    """A whole request body that asks for no progress and opens no subscription stream. A mention of
    either word anywhere (even inside an argument) keeps the streamed answer: the safe side."""
    if message.get("type") != "http.request" or message.get("more_body", False):
        return False
    body = message.get("body", b"")
    return b"progressToken" not in body and b"subscriptions/listen" not in body
