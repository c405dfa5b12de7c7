"""Asking the model for a plan: decoded under the plan's JSON schema where the endpoint offers it, always
validated with pydantic, and repaired once with the validation errors when it does not validate."""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from typing import Any

import openai
from pydantic import ValidationError

from fleet_agent.consistency import read_plan
from fleet_agent.plan import Plan, plan_schema
from fleet_agent.prompt import messages_for
from fleet_agent.records import ModelConfig, Usage

DECODINGS = ("json_schema", "ollama", "guided", "none")
MAX_ERRORS_SHOWN = 6
CUT = "Your plan repeated its steps until the length limit cut it off: write each step once"


@dataclass
class PlanAttempt:
    """What one request for a plan gave: the plan (None when even the repair did not validate)."""

    plan: Plan | None
    replies: list[str] = field(default_factory=list)
    errors: list[str] = field(default_factory=list)
    usage: Usage = field(default_factory=Usage)
    model_error: str | None = None
    gaps: int = 0  # what the plan taken leaves out of the request (`fleet_agent.consistency`)


def decoding_options(decoding: str, schema: dict[str, Any]) -> dict[str, Any]:
    """The request options that make the endpoint decode under ``schema``."""
    named = {"type": "json_schema", "json_schema": {"name": "plan", "schema": schema}}
    options: dict[str, dict[str, Any]] = {
        "json_schema": {"response_format": named}, "ollama": {"extra_body": {"format": schema}},
        "guided": {"extra_body": {"guided_json": schema}}, "none": {},
    }  # fmt: skip
    if decoding not in options:
        raise ValueError(f"decoding must be one of {', '.join(DECODINGS)}; got {decoding!r}")
    return options[decoding]


def describe_errors(exc: ValidationError | ValueError) -> str:
    """A validation error as short lines: where in the plan, and what is wrong."""
    if not isinstance(exc, ValidationError):
        return str(exc)
    errors = exc.errors()[:MAX_ERRORS_SHOWN]
    return "; ".join(f"{'.'.join(str(p) for p in e['loc']) or 'plan'}: {e['msg']}" for e in errors)


class Planner:
    """One model endpoint, asked for plans."""

    def __init__(self, model: ModelConfig, client: openai.AsyncOpenAI | None = None) -> None:
        self.model = model
        self.client = client or openai.AsyncOpenAI(
            base_url=model.base_url, api_key=model.api_key, timeout=model.timeout_s,
            max_retries=model.max_retries,
        )  # fmt: skip

    async def plan(self, request: str, fleet: list[str], places: list[str] | None = None) -> PlanAttempt:
        """A plan for ``request``: one request to the model, and one repair round when the plan does not
        validate or leaves out a drone or a number of the request (`fleet_agent.consistency`)."""
        messages: list[dict[str, Any]] = list(messages_for(request, fleet, places, self.model.nearest))
        attempt = PlanAttempt(plan=None)
        options = decoding_options(self.model.decoding, plan_schema(fleet))
        for round_ in range(2):
            try:
                reply, cut = await self._complete(messages, options, attempt.usage)
            except openai.OpenAIError as exc:
                endpoint = f"the model endpoint {self.model.base_url} (model {self.model.model})"
                attempt.model_error = f"{endpoint} did not answer: {type(exc).__name__}: {exc}"
                return attempt
            attempt.replies.append(reply)
            problem = self._read(reply, request, fleet, attempt)
            if problem is None or round_ == 1:
                return attempt
            # a reply cut at the token limit repeated itself: shown again, it is repeated again
            messages += [] if cut else [{"role": "assistant", "content": reply}]
            messages += [{"role": "user", "content": repair_message(CUT if cut else problem, request)}]
        return attempt

    @staticmethod
    def _read(reply: str, request: str, fleet: list[str], attempt: PlanAttempt) -> str | None:
        """Take the reply's plan into ``attempt`` when it validates and leaves out less of the request than
        the plan there (not a repair that does worse or writes the host's note back); else what is wrong."""
        echo = bool(attempt.errors) and attempt.errors[-1][:50] in reply
        try:
            plan, notes = read_plan(request, fleet, json.loads(_json_part(reply)))
        except (ValidationError, ValueError) as exc:
            attempt.errors.append(describe_errors(exc))
            return f"That plan is not valid: {attempt.errors[-1]}"
        if not echo and (attempt.plan is None or len(notes) < attempt.gaps):
            attempt.plan, attempt.gaps = plan, len(notes)
        if not notes:
            return None
        attempt.errors.append("; ".join(notes))
        return f"Check the plan against the request: {attempt.errors[-1]}"

    async def _complete(self, messages: list[Any], options: dict[str, Any], usage: Usage) -> tuple[str, bool]:
        """The reply, and whether the token limit cut it."""
        response = await self.client.chat.completions.create(
            model=self.model.model, messages=messages,
            temperature=self.model.temperature, max_tokens=self.model.max_tokens, **options,
        )  # fmt: skip
        if response.usage is not None:
            usage.add(response.usage.prompt_tokens, response.usage.completion_tokens)
        choice = response.choices[0] if response.choices else None
        return (choice.message.content or "", choice.finish_reason == "length") if choice else ("", False)


def repair_message(problem: str, request: str) -> str:
    """What goes back with a plan that needs correcting: what is wrong, then the request again (a small
    model that reads the correction alone writes a plan for an earlier example instead)."""
    return f"{problem}.\nRequest: {request}\nWrite the whole plan for this request again, corrected."


def _json_part(reply: str) -> str:
    """The JSON object in a reply (a model without constrained decoding may wrap it in a code fence)."""
    start, end = reply.find("{"), reply.rfind("}")
    if start < 0 or end < start:
        raise ValueError("the reply holds no JSON object")
    text = reply[start : end + 1]
    json.loads(text)  # a JSON error is reported as such, before pydantic's
    return text
