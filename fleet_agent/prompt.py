"""What the model reads before a request: the steps in short (``system_prompt.txt``), then worked examples as
earlier turns, one line a plan (copied more faithfully than a description); one prefix, a server's cache."""

from __future__ import annotations

import json
import math
from collections import Counter
from functools import cache
from pathlib import Path
from typing import Any

#: what the plan's steps are, in short (the system prompt)
_STEPS = (Path(__file__).parent / "system_prompt.txt").read_text(encoding="utf-8")


def _examples(name: str) -> list[tuple[str, dict[str, Any]]]:
    """Worked examples (one a line: a request and its plan), in their order."""
    lines = (Path(__file__).parent / name).read_text(encoding="utf-8").splitlines()
    return [(example["request"], example["plan"]) for example in map(json.loads, filter(None, lines))]


#: shown before every request, written for a fleet of delta and echo
EXAMPLES, EXAMPLE_FLEET = _examples("examples.jsonl"), ["delta", "echo"]
#: requests of the development corpus with their plans, for alpha, bravo and charlie: the few nearest a
#: request are shown after the fixed examples, so the model sees its request's shape and language solved
POOL, POOL_FLEET, NEAREST = _examples("pool.jsonl"), ["alpha", "bravo", "charlie"], 3


def prefix_messages(fleet: list[str] | None = None) -> list[dict[str, str]]:
    """The system prompt, then each example as a user turn and the assistant's plan, its drones (delta and
    echo) shown as the fleet's first two ids: a decoder held to the fleet's ids cannot write others."""
    turns = [_turn(text, plan, EXAMPLE_FLEET, fleet) for text, plan in EXAMPLES]
    return [{"role": "system", "content": _STEPS}, *(m for turn in turns for m in turn)]


def _turn(
    text: str, plan: dict[str, Any], written_for: list[str], fleet: list[str] | None
) -> list[dict[str, str]]:
    """An example as a user turn and the assistant's plan, its drones renamed the fleet's in their order."""
    ids = (list(fleet) * len(written_for))[: len(written_for)] if fleet else written_for
    names = dict(zip(written_for, ids, strict=True))
    return [
        {"role": "user", "content": _renamed(user_message(text, written_for), names)},
        {"role": "assistant", "content": _renamed(_compact(plan), names)},
    ]


def _renamed(text: str, names: dict[str, str]) -> str:
    for old, new in names.items():
        text = text.replace(old, f"\0{new}").replace(old.capitalize(), f"\0{new.capitalize()}")
    return text.replace("\0", "")


def messages_for(
    request: str, fleet: list[str], places: list[str] | None = None, count: int = 0
) -> list[dict[str, str]]:
    """What the model is sent for a request: the fixed prefix, the ``count`` pool examples nearest the
    request (the nearest last), then the request."""
    chosen = nearest(request, fleet, count) if count else []
    near = [m for text, plan in chosen for m in _turn(text, plan, POOL_FLEET, fleet)]
    return [*prefix_messages(fleet), *near, {"role": "user", "content": user_message(request, fleet, places)}]


def _trigrams(text: str, ids: list[str]) -> Counter[str]:
    """The text's character trigrams, every digit as 0 and every drone id as @: nearness is in what is
    asked and in which language, not which drone or how far. Trigrams read every script with no words."""
    text = " ".join(text.lower().split())
    for name in sorted(ids, key=len, reverse=True):
        text = text.replace(name.lower(), "@")
    text = "".join("0" if c.isdigit() else c for c in f" {text} ")
    return Counter(text[i : i + 3] for i in range(len(text) - 2))


@cache
def _pool_vectors() -> tuple[list[dict[str, float]], dict[str, float]]:
    grams = [_trigrams(text, POOL_FLEET) for text, _ in POOL]
    seen = Counter(g for each in grams for g in each)
    weights = {g: math.log((1 + len(grams)) / (1 + n)) for g, n in seen.items()}
    return [_unit(each, weights) for each in grams], weights


def _unit(grams: Counter[str], weights: dict[str, float]) -> dict[str, float]:
    """Trigram counts weighted by rarity in the pool (those every example has weigh little), length 1."""
    vector = {g: n * weights.get(g, 0.0) for g, n in grams.items()}
    norm = math.sqrt(sum(x * x for x in vector.values())) or 1.0
    return {g: x / norm for g, x in vector.items()}


def nearest(request: str, fleet: list[str], count: int = NEAREST) -> list[tuple[str, dict[str, Any]]]:
    """The ``count`` pool examples nearest ``request`` (cosine of weighted trigrams), the nearest last."""
    vectors, weights = _pool_vectors()
    asked = _unit(_trigrams(request, fleet), weights)
    score = [sum(w * vector.get(g, 0.0) for g, w in asked.items()) for vector in vectors]
    return [POOL[i] for i in sorted(range(len(POOL)), key=score.__getitem__)[-count:]]


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
