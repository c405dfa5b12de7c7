"""``--profile auto``: the profile chosen from what the endpoint says about its model (llama.cpp's
/v1/models and /props, Ollama's /api/show, served here over real HTTP), else from the model's name."""

from __future__ import annotations

import json
import threading
from collections.abc import Iterator
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from typing import Any, ClassVar

import pytest

from gateway.agent.autoprofile import ModelFacts, choose, params_from_name, probe, resolve

LLAMA_MODELS = {"data": [{"id": "tiny", "meta": {"n_params": 1_543_714_304, "n_ctx_train": 32768}}]}
LLAMA_PROPS = {"default_generation_settings": {"n_ctx": 16384}}
OLLAMA_SHOW = {"details": {"parameter_size": "8.0B"}, "model_info": {"llama.context_length": 131072}}


class _Endpoint(BaseHTTPRequestHandler):
    routes: ClassVar[dict[tuple[str, str], Any]] = {}

    def _answer(self, method: str) -> None:
        body = self.routes.get((method, self.path))
        if body is None:
            self.send_error(404)
            return
        data = json.dumps(body).encode()
        self.send_response(200)
        self.send_header("Content-Type", "application/json")
        self.send_header("Content-Length", str(len(data)))
        self.end_headers()
        self.wfile.write(data)

    def do_GET(self) -> None:
        self._answer("GET")

    def do_POST(self) -> None:
        self.rfile.read(int(self.headers.get("Content-Length") or 0))
        self._answer("POST")

    def log_message(self, *args: Any) -> None:
        pass


@pytest.fixture
def endpoint() -> Iterator[tuple[str, dict[tuple[str, str], Any]]]:
    routes: ClassVar[dict[tuple[str, str], Any]] = {}
    handler = type("Handler", (_Endpoint,), {"routes": routes})
    server = ThreadingHTTPServer(("127.0.0.1", 0), handler)
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    try:
        yield f"http://127.0.0.1:{server.server_address[1]}/v1", routes
    finally:
        server.shutdown()
        server.server_close()


async def test_llama_cpp_reports_the_size_and_context(endpoint) -> None:
    url, routes = endpoint
    routes[("GET", "/v1/models")] = LLAMA_MODELS
    routes[("GET", "/props")] = LLAMA_PROPS
    facts = await probe(url, "tiny")
    assert facts == ModelFacts(1_543_714_304.0, 16384, "llama.cpp /v1/models, /props")
    choice = await resolve("auto", url, "tiny")
    assert choice.profile == "small" and "1.5B parameters (llama.cpp" in choice.reason, choice


async def test_ollama_reports_the_size(endpoint) -> None:
    url, routes = endpoint
    routes[("POST", "/api/show")] = OLLAMA_SHOW
    facts = await probe(url, "llama3.1")
    assert facts == ModelFacts(8e9, 131072, "Ollama /api/show")
    assert choose(facts, "llama3.1").profile == "full"


async def test_an_endpoint_that_tells_nothing_leaves_the_name(endpoint) -> None:
    url, _ = endpoint
    assert await probe(url, "m") == ModelFacts()
    small = await resolve("auto", url, "qwen2.5-coder-1.5b-instruct")
    assert small.profile == "small" and "the name 'qwen2.5-coder-1.5b-instruct'" in small.reason, small
    unknown = await resolve("auto", url, "gpt-4o")
    assert unknown.profile == "full" and "not known" in unknown.reason
    assert (await resolve("small", url, "gpt-4o")).profile == "small"  # a profile asked for is kept


def test_sizes_and_contexts_from_names_and_facts() -> None:
    assert params_from_name("qwen2.5-coder-0.5b-instruct") == 0.5e9
    assert params_from_name("llama3.2:3b") == 3e9
    assert params_from_name("smollm2-360m-instruct") == 360e6
    assert params_from_name("qwen2.5-72b-instruct-q4_k_m") == 72e9
    assert params_from_name("gpt-4o") is None
    assert choose(ModelFacts(None, 8192, "llama.cpp"), "big-unknown").profile == "small"
    assert choose(ModelFacts(7e9, 32768, "llama.cpp"), "seven").profile == "full"
