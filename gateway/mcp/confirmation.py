"""A human confirms a command before it runs (a declaration's ``confirm=Confirm(...)``,
`gateway.fleet.commands.command_core.Confirm`): the tool's extra parameter, filled by the SDK's resolver
(``Resolve``) by eliciting a yes from the client's user, never by the model.

The resolver runs before the tool body, on every round of the question, and changes nothing: it asks
the verb's part whether and what to ask (``Confirm.question``), which also judges the command first, so
a command the policy refuses is refused before anyone is asked (the audit row learns the refusal)."""

from __future__ import annotations

import inspect
from typing import Annotated, Literal

from mcp.server.elicitation import AcceptedElicitation
from mcp.server.mcpserver import Elicit, ElicitationResult, Resolve
from mcp.server.mcpserver.exceptions import ToolError
from pydantic import BaseModel, Field

from gateway.errors import GatewayError, SafetyRefusal
from gateway.fleet.commands.command_core import Confirm
from gateway.fleet.operations.routing import Verb
from gateway.mcp.access import ToolCall, current_call
from gateway.mcp.sdk_types import ToolContext
from gateway.mcp.toolkit import check_drone_id

#: the tool's parameter the answer fills (dropped from the inputSchema by the SDK)
ANSWER = "answer"


class Confirmation(BaseModel):
    confirm: bool = Field(description="true to go ahead")


def answer_parameter(verb: Verb, confirm: Confirm) -> inspect.Parameter:
    """The tool's parameter that a human's answer fills (``ElicitationResult[Confirmation]``)."""
    part = verb.declared.__qualname__.split(".")[-2]

    def resolve(drone_id: str, ctx: ToolContext) -> Elicit[Confirmation] | Confirmation:
        call = ToolCall.of(ctx)
        try:
            check_drone_id(drone_id)
            drone_id = call.commander.canonical_id(drone_id)
            question: str | None = getattr(call.commander.parts[part], confirm.question)(
                call.caller, drone_id
            )
        except SafetyRefusal as exc:
            _mark("refused", exc.message)
            raise ToolError(f"Refused: {exc.message}") from None
        except GatewayError as exc:
            _mark("error", exc.message)
            raise ToolError(exc.message) from None
        if question is None:
            return Confirmation(confirm=True)
        return Elicit(question, Confirmation)

    return inspect.Parameter(
        ANSWER,
        inspect.Parameter.POSITIONAL_OR_KEYWORD,
        annotation=Annotated[ElicitationResult[Confirmation], Resolve(resolve)],
    )


def confirmed(answer: object) -> bool:
    """Whether the human said yes (an accepted answer with ``confirm`` true)."""
    if not isinstance(answer, AcceptedElicitation):
        return False
    return isinstance(answer.data, Confirmation) and answer.data.confirm


def _mark(outcome: Literal["refused", "error"], error: str) -> None:
    info = current_call.get()
    if info is not None:
        info.outcome, info.error = outcome, error


__all__ = ["ANSWER", "Confirmation", "answer_parameter", "confirmed"]
