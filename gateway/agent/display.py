"""Rendering agent events: live on a rich terminal, or as JSON lines (``--json``)."""

from __future__ import annotations

import json
import sys
from typing import IO

from rich.console import Console
from rich.markup import escape
from rich.status import Status

from gateway.agent.turns import AgentEvent, EventData

_STATUS_STYLE = {
    "ok": "green",
    "error": "red",
    "invalid": "yellow",
    "unknown_tool": "yellow",
    "repeat": "yellow",
    "skipped": "yellow",
    "left_out": "yellow",
}


class JsonLinesDisplay:
    """One JSON object per event, flushed at once, so a pipe sees the flight as it happens."""

    def __init__(self, stream: IO[str] | None = None) -> None:
        self.stream = stream or sys.stdout

    def __call__(self, event: AgentEvent) -> None:
        self.stream.write(json.dumps(event.to_json(), default=str) + "\n")
        self.stream.flush()

    def close(self) -> None:
        """Nothing to close (symmetry with RichDisplay)."""


class RichDisplay:
    """Human view: every tool call with its arguments, live progress, one line per result, the answer.

    On a terminal the progress of a running tool is a spinner line updated in place; elsewhere (a log,
    a test) each distinct progress message is printed as its own line."""

    def __init__(
        self, console: Console | None = None, *, show_usage: bool = True, echo_user: bool = True
    ) -> None:
        self.console = console or Console()
        self.show_usage = show_usage
        self.echo_user = echo_user  # off at an interactive prompt, where the user's line is already shown
        self._status: Status | None = None
        self._last_progress: tuple[str, str] | None = None

    def __call__(self, event: AgentEvent) -> None:
        handler = getattr(self, f"_on_{event.kind}", None)
        if handler is not None:
            handler(event.data)

    def close(self) -> None:
        self._stop_status()

    # --- handlers --------------------------------------------------------------------------------

    def _on_turn_start(self, d: EventData) -> None:
        if self.echo_user:
            self.console.print(f"[bold cyan]you[/] {escape(d['user'])}")

    def _on_model_reply(self, d: EventData) -> None:
        if d.get("tool_calls") and d.get("content") and not d.get("parsed_from_text"):
            self.console.print(f"[dim]model: {escape(_one_line(d['content'], 200))}[/]")

    def _on_parsed_from_text(self, d: EventData) -> None:
        notes = f" ({', '.join(d['notes'])})" if d.get("notes") else ""
        self.console.print(f"[yellow]parsed a tool call from text[/] [dim]x{d['count']}{escape(notes)}[/]")

    def _on_tool_call(self, d: EventData) -> None:
        args = d["arguments"]
        if isinstance(args, dict):
            shown = ", ".join(f"{k}={json.dumps(v, default=str)}" for k, v in args.items())
        else:  # arguments that could not be decoded are shown as the model wrote them
            shown = repr(args)
        self.console.print(f"[bold magenta]→ {escape(d['name'])}[/]({escape(shown)})")
        self._last_progress = None
        if self.console.is_terminal:
            self._status = self.console.status(f"[dim]{escape(d['name'])} running…[/]")
            self._status.start()

    def _on_progress(self, d: EventData) -> None:
        text = _progress_text(d)
        key = (d["id"], text)
        if key == self._last_progress:
            return
        self._last_progress = key
        if self._status is not None:
            self._status.update(f"[blue]{escape(d['name'])}[/] {escape(text)}")
        else:
            self.console.print(f"  [blue]… {escape(d['name'])}[/] {escape(text)}")

    def _on_tool_result(self, d: EventData) -> None:
        self._stop_status()
        style = _STATUS_STYLE.get(d["status"], "white")
        mark = "✓" if d["status"] == "ok" else "✗"
        label = "" if d["status"] in ("ok", "error") else f" {d['status'].replace('_', ' ')}:"
        self.console.print(f"  [{style}]{mark}{label}[/] {escape(d['summary'])}")

    def _on_final(self, d: EventData) -> None:
        self._stop_status()
        self.console.print(f"[bold green]model[/] {escape(d['text'])}")

    def _on_empty_reply(self, d: EventData) -> None:
        self.console.print(f"[yellow]empty reply[/] [dim]asking again with the request ({d['attempt']})[/]")

    def _on_empty_answer(self, d: EventData) -> None:
        self._stop_status()
        self.console.print(f"[bold red]no answer[/] {escape(d['message'])}")

    def _on_arguments_corrected(self, d: EventData) -> None:
        self.console.print(f"  [dim]{escape('; '.join(d['notes']))}[/]")

    def _on_step_limit(self, d: EventData) -> None:
        self._stop_status()
        self.console.print(f"[bold red]step limit[/] {escape(d['message'])}")

    def _on_interrupted(self, d: EventData) -> None:
        self._stop_status()
        self.console.print(f"[bold yellow]interrupted[/] {escape(d['message'])}")

    def _on_model_error(self, d: EventData) -> None:
        self._stop_status()
        self.console.print(f"[bold red]model error[/] {escape(d['error'])}")

    def _on_turn_end(self, d: EventData) -> None:
        if not self.show_usage:
            return
        tokens = (
            f"{d['prompt_tokens']} in / {d['completion_tokens']} out tokens"
            if d.get("prompt_tokens") is not None
            else "tokens not reported by the endpoint"
        )
        self.console.print(
            f"[dim]{d['steps']} model step(s), {d['tool_calls']} tool call(s), {tokens}, "
            f"{d['wall_s']:.1f} s[/]"
        )

    def _stop_status(self) -> None:
        if self._status is not None:
            self._status.stop()
            self._status = None


def _progress_text(d: EventData) -> str:
    p, total, msg = d.get("progress"), d.get("total"), d.get("message")
    if total and isinstance(p, int | float):
        head = f"{100.0 * float(p) / float(total):.0f}%"
    else:
        head = f"{p:g}" if isinstance(p, (int, float)) else ""
    return f"{head} {msg}".strip() if msg else head


def _one_line(text: str, limit: int) -> str:
    line = " ".join(text.split())
    return line if len(line) <= limit else line[: limit - 1] + "…"
