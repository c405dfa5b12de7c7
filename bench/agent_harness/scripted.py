"""A scripted OpenAI-compatible Chat Completions server: replays fixed model replies over real HTTP.

Used by the tests and by the benchmark's harness self-check. It is *not* a model: it answers the n-th
request with the n-th scripted reply (or a function of the request), so the host's loop, parsing and
display can be exercised, and every request it received is kept for inspection.
"""

from __future__ import annotations

import itertools
import json
import threading
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from typing import Any


@dataclass
class ScriptedReply:
    """One model reply. ``tool_calls`` items are ``(name, arguments)`` where arguments is a dict (sent as
    JSON) or a string (sent verbatim, e.g. malformed JSON). ``usage`` None = computed from sizes;
    ``{}`` = no usage field at all (as some local servers do)."""

    content: str | None = None
    tool_calls: Sequence[tuple[str, Any]] = ()
    usage: dict[str, int] | None = None
    finish_reason: str | None = None  # None: "tool_calls" or "stop", as the reply has calls or not


Reply = ScriptedReply | Callable[[dict[str, Any]], ScriptedReply]


def call(name: str, **arguments: Any) -> ScriptedReply:
    """Shorthand: a reply with one structured tool call."""
    return ScriptedReply(tool_calls=[(name, arguments)])


def say(text: str) -> ScriptedReply:
    """Shorthand: a final text answer."""
    return ScriptedReply(content=text)


@dataclass
class ScriptedModelServer:
    """Serves ``POST /v1/chat/completions`` on 127.0.0.1 (a free port) from a list of replies.

    When the script is exhausted it repeats the last reply if ``repeat_last`` is set, otherwise it
    answers HTTP 500 with an error naming the exhaustion (a test then fails loudly)."""

    replies: list[Reply] = field(default_factory=list)
    repeat_last: bool = False
    model_name: str = "scripted"
    requests: list[dict[str, Any]] = field(default_factory=list)
    _server: ThreadingHTTPServer | None = None
    _thread: threading.Thread | None = None
    _lock: threading.Lock = field(default_factory=threading.Lock)
    _ids: Any = field(default_factory=lambda: itertools.count(1))

    @property
    def base_url(self) -> str:
        assert self._server is not None, "server not started"
        host, port = self._server.server_address[:2]
        return f"http://{host}:{port}/v1"

    def start(self) -> ScriptedModelServer:
        owner = self

        class Handler(BaseHTTPRequestHandler):
            def do_POST(self) -> None:
                if self.path.rstrip("/") not in ("/v1/chat/completions", "/chat/completions"):
                    self._send(404, {"error": {"message": f"no route {self.path}", "type": "not_found"}})
                    return
                length = int(self.headers.get("Content-Length") or 0)
                try:
                    body = json.loads(self.rfile.read(length) or b"{}")
                except json.JSONDecodeError as exc:
                    self._send(400, {"error": {"message": f"bad JSON: {exc}", "type": "invalid_request"}})
                    return
                status, payload = owner._answer(body)
                self._send(status, payload)

            def do_GET(self) -> None:
                if self.path.rstrip("/") == "/v1/models":
                    self._send(200, {"object": "list", "data": [{"id": owner.model_name, "object": "model"}]})
                else:
                    self._send(404, {"error": {"message": "not found"}})

            def _send(self, status: int, payload: dict[str, Any]) -> None:
                data = json.dumps(payload).encode()
                self.send_response(status)
                self.send_header("Content-Type", "application/json")
                self.send_header("Content-Length", str(len(data)))
                self.end_headers()
                self.wfile.write(data)

            def log_message(self, format: str, *args: Any) -> None:  # quiet
                return

        self._server = ThreadingHTTPServer(("127.0.0.1", 0), Handler)
        self._server.daemon_threads = True
        self._thread = threading.Thread(target=self._server.serve_forever, name="scripted-model", daemon=True)
        self._thread.start()
        return self

    def stop(self) -> None:
        if self._server is not None:
            self._server.shutdown()
            self._server.server_close()
            self._server = None
        if self._thread is not None:
            self._thread.join(timeout=5)
            self._thread = None

    def __enter__(self) -> ScriptedModelServer:
        return self.start()

    def __exit__(self, *exc: object) -> None:
        self.stop()

    def _answer(self, body: dict[str, Any]) -> tuple[int, dict[str, Any]]:
        with self._lock:
            index = len(self.requests)
            self.requests.append(body)
            if index < len(self.replies):
                reply = self.replies[index]
            elif self.repeat_last and self.replies:
                reply = self.replies[-1]
            else:
                return 500, {
                    "error": {
                        "message": f"scripted model exhausted after {len(self.replies)} replies",
                        "type": "script_exhausted",
                    }
                }
        try:
            resolved = reply(body) if callable(reply) else reply
        except Exception as exc:  # a scripted function failed: say so instead of hanging the client
            return 500, {"error": {"message": f"scripted reply failed: {exc!r}", "type": "script_error"}}
        return 200, self._completion(body, resolved)

    def _completion(self, body: dict[str, Any], reply: ScriptedReply) -> dict[str, Any]:
        message: dict[str, Any] = {"role": "assistant", "content": reply.content}
        if reply.tool_calls:
            message["tool_calls"] = [
                {
                    "id": f"call_scripted_{next(self._ids)}",
                    "type": "function",
                    "function": {
                        "name": name,
                        "arguments": args if isinstance(args, str) else json.dumps(args),
                    },
                }
                for name, args in reply.tool_calls
            ]
        out: dict[str, Any] = {
            "id": f"chatcmpl-scripted-{len(self.requests)}",
            "object": "chat.completion",
            "created": int(time.time()),
            "model": body.get("model", self.model_name),
            "choices": [
                {
                    "index": 0,
                    "message": message,
                    "finish_reason": reply.finish_reason or ("tool_calls" if reply.tool_calls else "stop"),
                }
            ],
        }
        if reply.usage is None:
            # An estimate (4 characters a token) of what the request would cost, tools included.
            prompt = (len(json.dumps(body.get("messages", []))) + len(json.dumps(body.get("tools", [])))) // 4
            completion = len(json.dumps(message)) // 4
            out["usage"] = {
                "prompt_tokens": prompt,
                "completion_tokens": completion,
                "total_tokens": prompt + completion,
            }
        elif reply.usage:
            out["usage"] = dict(reply.usage)
        return out
