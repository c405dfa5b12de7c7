"""Start-up figures: `fleet-gateway --help` and `serve` (fresh database) until /healthz answers.

Prints the median and maximum of N runs; ``--write`` puts them into docs/benchmarks.md. Nothing is
asserted: the targets (--help under 0.5 s, serve healthy under 5 s on an idle machine) are read here.
"""

from __future__ import annotations

import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import httpx

sys.path.insert(0, str(Path(__file__).resolve().parent))
from common import ROOT, machine, parser, table, write_section

from gateway.util.ports import free_tcp_port

CLI = [sys.executable, "-m", "gateway.cli"]


def help_time_s() -> float:
    started = time.perf_counter()
    subprocess.run([*CLI, "--help"], cwd=ROOT, check=True, capture_output=True)
    return time.perf_counter() - started


def serve_time_s() -> float:
    """From `fleet-gateway serve` on a new database until /healthz answers 200."""
    with tempfile.TemporaryDirectory(prefix="bench-startup-") as folder:
        port = free_tcp_port()
        env = {
            **os.environ,
            "GATEWAY_PORT": str(port),
            "GATEWAY_DATABASE_URL": f"sqlite+aiosqlite:///{Path(folder) / 'g.db'}",
            "GATEWAY_LOG_LEVEL": "WARNING",
        }
        started = time.perf_counter()
        proc = subprocess.Popen([*CLI, "serve"], cwd=folder, env=env, stdout=subprocess.DEVNULL,
                                stderr=subprocess.DEVNULL, start_new_session=True)  # fmt: skip
        try:
            while True:
                if proc.poll() is not None:
                    raise SystemExit(f"serve exited with {proc.returncode} before it was healthy")
                try:
                    if httpx.get(f"http://127.0.0.1:{port}/healthz", timeout=1.0).status_code == 200:
                        return time.perf_counter() - started
                except httpx.HTTPError:
                    pass
                if time.perf_counter() - started > 120:
                    raise SystemExit("serve was not healthy within 120 s")
                time.sleep(0.05)
        finally:
            proc.terminate()
            proc.wait(timeout=30)


def main() -> int:
    args = parser(__doc__.splitlines()[0]).parse_args()
    runs = 10 if args.full else 3
    helps = [help_time_s() for _ in range(runs)]
    serves = [serve_time_s() for _ in range(runs)]
    body = table(
        ["what", "runs", "median s", "max s"],
        [
            ["fleet-gateway --help", runs, f"{statistics.median(helps):.2f}", f"{max(helps):.2f}"],
            [
                "serve until /healthz (new database)",
                runs,
                f"{statistics.median(serves):.2f}",
                f"{max(serves):.2f}",
            ],
        ],
    )
    print(body)
    if args.write:
        write_section("startup", "Start-up", body, machine())
    return 0


if __name__ == "__main__":
    sys.exit(main())
