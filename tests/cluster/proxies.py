"""The fault matrix's TCP proxies (`tests.helpers.tcpproxy.TcpProxy`: cut, heal, delay) in a process of
their own, driven over a pipe, instead of threads of the test process.

Every node's NATS and PostgreSQL connections pass through them. As threads of the test process they
shared its interpreter with the test's own work (its MCP and HTTP clients, pytest's reports): whatever
held that process back held every node's database path back at once, and both nodes' lease renewals
timed out together. In a process of their own they wait on nothing but the CPU.

Run as ``python -m tests.cluster.proxies``: one JSON request a line on stdin (``open`` a proxy to a
target, ``cut``, ``heal``, ``delay`` one, ``close`` all), one JSON answer a line on stdout, sent once the
request is in effect.
"""

from __future__ import annotations

import contextlib
import json
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path
from typing import Any

from tests.helpers.tcpproxy import TcpProxy
from tests.helpers.timing import scaled

ROOT = Path(__file__).resolve().parents[2]


class ProxyProcess:
    """The process that holds the proxies; :meth:`open` makes one (a :class:`RemoteProxy`)."""

    def __init__(self) -> None:
        self.proc = subprocess.Popen(
            [sys.executable, "-m", "tests.cluster.proxies"],
            cwd=ROOT,
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            text=True,
            bufsize=1,
            start_new_session=True,
        )

    def ask(self, **request: Any) -> dict[str, Any]:
        """One request, answered once it is in effect."""
        assert self.proc.stdin is not None and self.proc.stdout is not None
        self.proc.stdin.write(json.dumps(request) + "\n")
        self.proc.stdin.flush()
        line = self.proc.stdout.readline()
        if not line:
            raise RuntimeError(f"the proxy process ended (exit {self.proc.poll()}) on {request}")
        answer: dict[str, Any] = json.loads(line)
        if "error" in answer:
            raise RuntimeError(f"the proxy process refused {request}: {answer['error']}")
        return answer

    def open(self, target_host: str, target_port: int) -> RemoteProxy:
        port = int(self.ask(op="open", host=target_host, port=target_port)["port"])
        return RemoteProxy(self, port)

    def close(self) -> None:
        if self.proc.poll() is None:
            with contextlib.suppress(OSError, RuntimeError, ValueError):
                self.ask(op="close")
            self.proc.terminate()
            try:
                self.proc.wait(timeout=scaled(10))
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait(timeout=scaled(10))
        for pipe in (self.proc.stdin, self.proc.stdout):
            if pipe is not None:
                with contextlib.suppress(OSError):
                    pipe.close()


class RemoteProxy:
    """One proxy of the process, as the matrix drives a `TcpProxy`: ``port``, ``cut``, ``heal``,
    ``delay_s``."""

    def __init__(self, owner: ProxyProcess, port: int) -> None:
        self._owner = owner
        self.port = port
        self._delay_s = 0.0

    def cut(self) -> None:
        self._owner.ask(op="cut", port=self.port)

    def heal(self) -> None:
        self._owner.ask(op="heal", port=self.port)

    @property
    def delay_s(self) -> float:
        return self._delay_s

    @delay_s.setter
    def delay_s(self, seconds: float) -> None:
        self._owner.ask(op="delay", port=self.port, s=seconds)
        self._delay_s = seconds


@contextlib.contextmanager
def proxy_process() -> Iterator[ProxyProcess]:
    """A proxy process, ended (its proxies closed) on exit."""
    process = ProxyProcess()
    try:
        yield process
    finally:
        process.close()


def serve() -> None:
    proxies: dict[int, TcpProxy] = {}
    for line in sys.stdin:
        try:
            request = json.loads(line)
            op = request["op"]
            answer: dict[str, Any] = {"ok": True}
            if op == "open":
                proxy = TcpProxy(str(request["host"]), int(request["port"]))
                proxies[proxy.port] = proxy
                answer["port"] = proxy.port
            elif op == "cut":
                proxies[int(request["port"])].cut()
            elif op == "heal":
                proxies[int(request["port"])].heal()
            elif op == "delay":
                proxies[int(request["port"])].delay_s = float(request["s"])
            elif op == "close":
                for proxy in proxies.values():
                    proxy.close()
                proxies.clear()
            else:
                answer = {"error": f"op: one of open, cut, heal, delay, close; got {op!r}"}
        except (ValueError, KeyError, TypeError, OSError) as exc:
            answer = {"error": repr(exc)}
        sys.stdout.write(json.dumps(answer) + "\n")
        sys.stdout.flush()
    for proxy in proxies.values():
        proxy.close()


if __name__ == "__main__":
    serve()
