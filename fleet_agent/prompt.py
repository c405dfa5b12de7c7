"""What the model reads before a request: the plan's steps in short, and worked examples.

The examples (``examples.jsonl``) are earlier turns, each plan on one line: a small model copies a reply it
has seen more faithfully than a described one, at half the tokens of an indented one. All before the
request stays the same (a local server reuses its cached prefix); the steps are in ``system_prompt.txt``."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

#: what the plan's steps are, in short (the system prompt)
_STEPS = (Path(__file__).parent / "system_prompt.txt").read_text(encoding="utf-8")


def _examples() -> list[tuple[str, dict[str, Any]]]:
    """The worked examples (``examples.jsonl``, one a line: a request and its plan), in their order."""
    lines = (Path(__file__).parent / "examples.jsonl").read_text(encoding="utf-8").splitlines()
    return [(example["request"], example["plan"]) for example in map(json.loads, filter(None, lines))]


EXAMPLES = _examples()


EXAMPLE_FLEET = ["delta", "echo"]


def prefix_messages(fleet: list[str] | None = None) -> list[dict[str, str]]:
    """The system prompt, then each example as a user turn and the assistant's plan. The examples are
    written for a fleet of delta and echo; they are shown with the fleet's own first two ids instead (a
    decoder held to the fleet's ids cannot write an example's id, and a small model that wanted to then
    writes whichever id the grammar lets through). The prefix stays the same while the fleet does."""
    names = _renaming(fleet or EXAMPLE_FLEET)
    messages = [{"role": "system", "content": _STEPS}]
    for text, plan in EXAMPLES:
        messages.append({"role": "user", "content": _renamed(user_message(text, EXAMPLE_FLEET), names)})
        messages.append({"role": "assistant", "content": _renamed(_compact(plan), names)})
    return messages


def _renaming(fleet: list[str]) -> dict[str, str]:
    ids = (list(fleet) * 2)[:2] if fleet else EXAMPLE_FLEET
    return dict(zip(EXAMPLE_FLEET, ids, strict=True))


def _renamed(text: str, names: dict[str, str]) -> str:
    for old, new in names.items():
        text = text.replace(old, f"\0{new}").replace(old.capitalize(), f"\0{new.capitalize()}")
    return text.replace("\0", "")


def messages_for(request: str, fleet: list[str], places: list[str] | None = None) -> list[dict[str, str]]:
    """What the model is sent for a request: the fixed prefix, then the request."""
    return [*prefix_messages(fleet), {"role": "user", "content": user_message(request, fleet, places)}]


def system_prompt(fleet: list[str] | None = None) -> str:
    """The fixed prefix as one text (its size is what a request costs before its own words)."""
    return "\n".join(m["content"] for m in prefix_messages(fleet))


def _compact(plan: dict[str, Any]) -> str:
    return json.dumps(plan, separators=(",", ":"), ensure_ascii=False)


def user_message(request: str, fleet: list[str], places: list[str] | None = None) -> str:
    lines = [f"Fleet: {', '.join(fleet)}"]
    if places:
        lines.append(f"Named places: {', '.join(places)}")
    lines.append(f"Request: {request}")
    return "\n".join(lines)
