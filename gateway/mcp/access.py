"""What an MCP tool gets: the Commander, the caller it acts for, and the presenting of its results.

The MCP server's lifespan yields a `FleetState` (the running gateway's Commander and settings); the
tool wrapper (`gateway.mcp.toolkit`) builds one `ToolCall` per call from it, naming the caller
(``via="mcp"``, the token principal, the MCP session). A tool is one Commander call plus presenting its
result: `ToolCall.finish` waits for an operation when the model asked to (capped, with progress
notifications) and turns it into the tool's structured result and one line of text.
"""

from __future__ import annotations

import contextlib
from collections.abc import Awaitable, Callable
from contextvars import ContextVar
from dataclasses import dataclass
from typing import Literal

from gateway.config import Settings
from gateway.errors import GatewayError
from gateway.fleet.commands.commander import Commander
from gateway.fleet.operations.views import OperationView
from gateway.fleet.policy.caller import Caller
from gateway.mcp.results import OperationOut
from gateway.mcp.sdk_types import ToolContext
from gateway.runtime import Gateway
from gateway.util.read_through import ReadThrough

# --- per-call audit information, set by the session middleware, filled in by the tool wrapper --------


@dataclass
class CallInfo:
    session_key: str | None = None
    principal: str | None = None
    vehicle_id: str | None = None
    outcome: Literal["ok", "error", "refused", "running"] | None = None
    error: str | None = None
    before_tool: Callable[[], Awaitable[None]] | None = None
    """Awaited by the tool wrapper once the SDK has taken the arguments, before the tool runs: the
    session middleware writes there the row of a call that commands a drone (a call refused for its
    arguments never gets there: it sent nothing, and its row is queued when it ends)."""


current_call: ContextVar[CallInfo | None] = ContextVar("current_call", default=None)


@dataclass(frozen=True)
class FleetState:
    """What the MCP server's lifespan yields (``ctx.request_context.lifespan_context``): the gateway
    the server runs over. Its Commander is taken per call, so a server over a gateway that is not
    running (listing tools for the docs) answers calls with "not running" instead of failing to start."""

    gateway: Gateway
    commander = ReadThrough[Commander]("gateway")
    settings = ReadThrough[Settings]("gateway")


class ToolCall:
    """One tool call: the Commander, who asks, and how to present what came back."""

    def __init__(self, state: FleetState, ctx: ToolContext) -> None:
        self.commander = state.commander
        self.settings = state.settings
        self.ctx = ctx
        call = current_call.get()
        principal = "local" if call is None or call.principal is None else call.principal
        self.caller = Caller(
            via="mcp", principal=principal, session=None if call is None else call.session_key
        )

    @classmethod
    def of(cls, ctx: ToolContext) -> ToolCall:
        state = ctx.request_context.lifespan_context
        if not isinstance(state, FleetState):
            raise GatewayError("the MCP server runs without a gateway (its lifespan did not start)")
        return cls(state, ctx)

    async def notify(self, text: str) -> None:
        """Tell the client what the command waits for (a progress notification at 0)."""
        with contextlib.suppress(Exception):  # progress is a courtesy
            await self.ctx.report_progress(0.0, 1.0, text)

    async def progress(self, view: OperationView) -> None:
        await self.ctx.report_progress(round(view.progress, 3), 1.0, view.message)

    async def finish(self, view: OperationView, wait: bool, action: str | None = None) -> OperationOut:
        """Wait for the operation (capped, with progress) if asked, then present it."""
        if wait and view.running:
            view = await self.commander.wait(view.operation_id, self.settings.mcp_wait_cap_s, self.progress)
        return operation_out(view, action)


def operation_out(view: OperationView, action: str | None = None) -> OperationOut:
    name = action or view.kind
    if view.running:
        eta = f", ETA {view.eta_s:.0f} s" if view.eta_s is not None else ""
        text = (
            f"{name} on {view.drone_id} still running ({view.progress:.0%}{eta}): {view.message}. "
            f"Call monitor_flight(drone_id='{view.drone_id}') to keep waiting."
        )
    else:
        text = f"{name} on {view.drone_id} {view.status}: {view.message}"
    return OperationOut.model_validate(view, from_attributes=True).say(text)
