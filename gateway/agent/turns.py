"""What a turn of the agent host is made of: the model's calls, their records, the events, how it ended.

Plain records, shared by the conversation loop (host.py), the model side (chat.py), the host's checks of
a call (checks.py) and its words to the model and the user (wording.py).
"""

from __future__ import annotations

from collections.abc import Awaitable, Callable, Sequence
from dataclasses import dataclass, field
from typing import Any, NotRequired, Protocol, TypedDict

from gateway.agent.toolbox import Arguments, ToolOutcome

# An empty reply is asked again at most this many times before the turn ends as ``empty_answer``.
MAX_EMPTY_REPROMPTS = 2

# The MCP progress callback: progress, total, message.
Progress = Callable[[float, float | None, str | None], Awaitable[None]]


# The fields of one event: JSON values, a different set for each kind (``--json`` prints them as they are).
EventData = dict[str, Any]


class ModelReplyError(RuntimeError):
    """The model endpoint answered with something that is not a usable chat completion."""


@dataclass
class AgentEvent:
    """One thing that happened in a turn; displays render these, ``--json`` prints them as lines."""

    kind: str
    data: EventData

    def to_json(self) -> EventData:
        return {"event": self.kind, **self.data}


EventSink = Callable[[AgentEvent], None]


class ToolCaller(Protocol):
    """What the host needs from an MCP connection (``McpLink`` implements it)."""

    async def call_tool(
        self, name: str, arguments: Arguments, progress: Progress | None = None
    ) -> ToolOutcome: ...


@dataclass
class ModelConfig:
    """Where and how to reach the chat model (any OpenAI-compatible Chat Completions endpoint)."""

    endpoint: str
    model: str
    api_key: str = "not-needed"
    temperature: float | None = 0.0
    timeout_s: float = 300.0
    max_retries: int = 1
    max_tokens: int | None = None  # cap on one reply (a small model on a CPU can ramble for minutes)


class ModelCall(TypedDict):
    """One tool call of a model reply, as the host received it: structured by the API, or read from text."""

    id: str
    name: str
    # the arguments as written: a JSON string from the API, or what parsing.py recovered from text
    raw_args: str | Arguments | None
    parse_error: NotRequired[str | None]  # why the arguments written as text could not be read
    notes: NotRequired[list[str]]  # what parsing.py repaired to read them


@dataclass
class ToolCallRecord:
    """One tool call of a turn, as executed (or not)."""

    id: str
    name: str
    arguments: Arguments | None
    status: str  # ok | error | invalid | unknown_tool | repeat | skipped | left_out
    summary: str
    parsed_from_text: bool = False
    text: str = ""  # what the model was told
    running: bool = False  # the result says the action is still going (a repeat of it is expected)

    @property
    def ok(self) -> bool:
        return self.status == "ok"


@dataclass
class Usage:
    """Token counts as reported by the API (None where the endpoint gave no usage)."""

    prompt_tokens: int | None = None
    completion_tokens: int | None = None
    model_calls: int = 0
    calls_without_usage: int = 0

    def add(self, prompt: int | None, completion: int | None) -> None:
        self.model_calls += 1
        if prompt is None and completion is None:
            self.calls_without_usage += 1
            return
        self.prompt_tokens = (self.prompt_tokens or 0) + (prompt or 0)
        self.completion_tokens = (self.completion_tokens or 0) + (completion or 0)

    def merge(self, other: Usage) -> None:
        """Add another turn's counts (a side nobody reported stays None)."""
        if other.prompt_tokens is not None or other.completion_tokens is not None:
            self.prompt_tokens = (self.prompt_tokens or 0) + (other.prompt_tokens or 0)
            self.completion_tokens = (self.completion_tokens or 0) + (other.completion_tokens or 0)
        self.model_calls += other.model_calls
        self.calls_without_usage += other.calls_without_usage


def relative_moves(calls: Sequence[ToolCallRecord]) -> list[Arguments]:
    """The arguments of the relative moves that succeeded, in order."""
    return [c.arguments for c in calls if c.ok and c.name == "move_to_relative" and c.arguments is not None]


def moves_of(moves: Sequence[Arguments], drone: object) -> list[Arguments]:
    """The moves (arguments) of one drone."""
    return [a for a in moves if a.get("drone_id") == drone]


@dataclass
class TurnResult:
    """How one user turn ended."""

    outcome: str  # answered | empty_answer | step_limit | model_error
    final_text: str | None
    steps: int
    tool_calls: list[ToolCallRecord] = field(default_factory=list)
    usage: Usage = field(default_factory=Usage)
    wall_s: float = 0.0
    error: str | None = None
    parsed_from_text: int = 0
    empty_replies: int = 0
    # empty replies since the model last acted; the turn ends when it passes MAX_EMPTY_REPROMPTS
    empty_streak: int = 0
    # who wrote final_text: the model, or the host from the gateway's results when the model gave none
    answered_by: str = "model"


@dataclass
class TurnMemory:
    """What the host remembers within one turn, to judge the model's next reply."""

    request: str = ""  # the user's words
    host_notes: list[str] = field(default_factory=list)  # what the host itself told the model (echoes)
    held: set[str] = field(default_factory=set)  # why answers were sent back (each reason once)
    # the host's own refusals of calls (an answer copying one is no answer)
    error_texts: list[str] = field(default_factory=list)
    # the gateway's errors (its refusals among them): an answer copying one tells the user what
    # happened, even when a host note quoted it first
    gateway_errors: list[str] = field(default_factory=list)
    refly_held: set[str] = field(default_factory=set)  # calls held back once as flying a finished step again
