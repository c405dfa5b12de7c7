"""The model side of a turn: one request to the chat model, and its reply as the host's tool calls.

A call the model wrote as text instead of a structured ``tool_calls`` entry is recovered here
(parsing.py reads it); what goes back into the conversation is always the structured form.
"""

from __future__ import annotations

import itertools
import json
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import openai

from gateway.agent.parsing import ArgumentsError, extract_tool_calls, known_case, parse_arguments
from gateway.agent.toolbox import Arguments
from gateway.agent.turns import ModelCall, ModelConfig, ModelReplyError, Usage

# One message of the conversation, in the Chat Completions wire form (role, content, tool_calls ...).
Message = dict[str, Any]


@dataclass
class ModelReply:
    """What the model answered to one request."""

    content: str | None
    calls: list[ModelCall] = field(default_factory=list)
    parsed: bool = False  # the calls were read from the text of the reply
    truncated: bool = False  # the reply stopped at the token limit
    finish_reason: str | None = None
    prompt_tokens: int | None = None
    completion_tokens: int | None = None
    # what parsing.py repaired to read the calls written as text
    notes: list[str] = field(default_factory=list)


class ChatModel:
    """One chat model behind an OpenAI-compatible Chat Completions endpoint, as the host asks it."""

    def __init__(self, config: ModelConfig, client: openai.AsyncOpenAI | None = None) -> None:
        self.config = config
        self.client = client or openai.AsyncOpenAI(
            base_url=config.endpoint,
            api_key=config.api_key or "not-needed",
            timeout=config.timeout_s,
            max_retries=config.max_retries,
        )
        self._ids = itertools.count(1)

    def new_id(self) -> str:
        """An id for a call that came without one (every call read from text)."""
        return f"call_host_{next(self._ids)}"

    async def ask(
        self,
        messages: list[Message],
        tool_specs: Sequence[Mapping[str, Any]],
        parameters: Mapping[str, list[str]],
        usage: Usage,
    ) -> ModelReply:
        """Send the conversation with the tool specs; the reply's tool calls, structured or read from text.
        ``parameters`` names each offered tool's arguments (to read calls written as text)."""
        model = self.config
        kwargs: dict[str, Any] = {"model": model.model, "messages": messages}
        if tool_specs:
            kwargs["tools"] = tool_specs
        if model.temperature is not None:
            kwargs["temperature"] = model.temperature
        if model.max_tokens is not None:
            kwargs["max_tokens"] = model.max_tokens
        response = await self.client.chat.completions.create(**kwargs)
        u = getattr(response, "usage", None)
        prompt = getattr(u, "prompt_tokens", None) if u is not None else None
        completion = getattr(u, "completion_tokens", None) if u is not None else None
        usage.add(prompt, completion)
        if not response.choices:
            raise ModelReplyError("the model endpoint returned no choices")
        choice = response.choices[0]
        message = choice.message
        content = message.content
        calls: list[ModelCall] = [
            {
                "id": tc.id or self.new_id(),
                "name": known_case(clean_name(tc.function.name), parameters),
                "raw_args": tc.function.arguments,
            }
            for tc in (message.tool_calls or [])
            if getattr(tc, "function", None) is not None
        ]
        parsed = False
        if not calls and content:
            found = extract_tool_calls(content, parameters)
            if found:
                parsed = True
                calls = [
                    {
                        "id": self.new_id(),
                        "name": c.name,
                        "raw_args": c.arguments,
                        "parse_error": c.error,
                        "notes": c.notes,
                    }
                    for c in found
                ]
        return ModelReply(
            content=content,
            calls=calls,
            parsed=parsed,
            truncated=choice.finish_reason == "length",
            finish_reason=choice.finish_reason,
            prompt_tokens=prompt,
            completion_tokens=completion,
            notes=sorted({n for c in calls for n in c.get("notes", [])}),
        )


def call_arguments(call: ModelCall) -> Arguments | None:
    """A call's arguments as a dict, or None when they do not parse."""
    if call.get("parse_error") is not None:
        return None
    try:
        return parse_arguments(call["raw_args"])
    except ArgumentsError:
        return None


def clean_name(name: str | None) -> str:
    name = (name or "").strip()
    return name[len("functions.") :] if name.startswith("functions.") else name


def assistant_message(content: str | None, calls: list[ModelCall], parsed: bool) -> Message:
    """The assistant turn as it goes back into the conversation. A call recovered from text is given the
    structured form, so that the tool results that follow refer to a call the API knows about."""
    tool_calls = []
    for c in calls:
        raw = c["raw_args"]
        if isinstance(raw, str):
            args_text = raw
        else:
            args_text = json.dumps(raw if raw is not None else {})
        tool_calls.append(
            {"id": c["id"], "type": "function", "function": {"name": c["name"], "arguments": args_text}}
        )
    return {"role": "assistant", "content": None if parsed else content, "tool_calls": tool_calls}


def close_open_calls(messages: list[Message], text: str) -> None:
    """Answer with ``text`` every tool call of the last assistant message that has no result yet (the API
    rejects a conversation with unanswered tool calls)."""
    for i in range(len(messages) - 1, -1, -1):
        msg = messages[i]
        if msg.get("role") == "assistant" and msg.get("tool_calls"):
            answered = {m.get("tool_call_id") for m in messages[i + 1 :] if m.get("role") == "tool"}
            for tc in msg["tool_calls"]:
                if tc["id"] not in answered:
                    messages.append({"role": "tool", "tool_call_id": tc["id"], "content": text})
            return
        if msg.get("role") == "user":
            return
