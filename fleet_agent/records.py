"""What a turn leaves behind: the model's settings, the calls sent, the events told, the turn's result."""

from __future__ import annotations

import time
from collections.abc import Awaitable, Callable
from dataclasses import dataclass, field
from typing import Any, Literal, Protocol

Arguments = dict[str, Any]
ProgressFn = Callable[[float, float | None, str | None], Awaitable[None]]
Outcome = Literal["answered", "invalid_plan", "model_error", "step_limit", "empty_answer"]


@dataclass(frozen=True)
class ToolOutcome:
    text: str
    is_error: bool = False
    structured: dict[str, Any] | None = None

    @property
    def refusal(self) -> Refusal | None:
        """The gateway's refusal as data (code, rule, details), when the result is an error."""
        if not self.is_error:
            return None
        data = self.structured or {}
        message, details = str(data.get("message") or self.text), dict(data.get("details") or {})
        return Refusal(str(data.get("code") or "error"), data.get("rule"), message, details)


@dataclass(frozen=True)
class Refusal:
    code: str
    rule: str | None
    message: str
    details: dict[str, Any]


class ToolCaller(Protocol):
    async def call_tool(
        self, name: str, arguments: Arguments, progress: ProgressFn | None = None
    ) -> ToolOutcome: ...


@dataclass
class ModelConfig:
    """An OpenAI-compatible endpoint and how plans are decoded there (``decoding``: one of
    `fleet_agent.decoding.DECODINGS`, described in `fleet_agent.settings.AgentSettings`)."""

    base_url: str
    model: str
    api_key: str = "not-needed"
    temperature: float = 0.0
    timeout_s: float = 300.0
    max_retries: int = 1
    max_tokens: int | None = 512
    decoding: str = "json_schema"
    nearest: int = 0  # pool examples shown nearest the request (`fleet_agent.prompt.nearest`)


@dataclass
class Usage:
    prompt_tokens: int | None = None
    completion_tokens: int | None = None

    def add(self, prompt: int | None, completion: int | None) -> None:
        if prompt is not None:
            self.prompt_tokens = (self.prompt_tokens or 0) + prompt
        if completion is not None:
            self.completion_tokens = (self.completion_tokens or 0) + completion


@dataclass
class ToolCallRecord:
    id: str
    name: str
    arguments: Arguments
    status: str  # ok | error | invalid | skipped
    text: str = ""
    refusal: Refusal | None = None


@dataclass
class TurnResult:
    outcome: Outcome
    final_text: str | None
    tool_calls: list[ToolCallRecord] = field(default_factory=list)
    usage: Usage = field(default_factory=Usage)
    steps: int = 0  # model requests
    plan: Any = None
    parsed_from_text: int = 0  # kept for the benchmark's tables: plans are never read from prose


@dataclass
class AgentEvent:
    kind: str
    data: dict[str, Any]
    at: float = field(default_factory=time.time)

    def to_json(self) -> dict[str, Any]:
        return {"kind": self.kind, "at": self.at, **self.data}


EventSink = Callable[[AgentEvent], None]
