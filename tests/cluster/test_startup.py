"""A cluster node whose NATS server cannot be reached does not start: one line naming the URL and the
setting, a non-zero exit, nothing written."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

from gateway.util.ports import free_tcp_port
from tests.helpers.timing import scaled

ROOT = Path(__file__).resolve().parents[2]


def test_serve_with_nats_unreachable_says_so_in_one_line_and_exits_non_zero(tmp_path: Path) -> None:
    nats_url = f"nats://127.0.0.1:{free_tcp_port()}"  # nothing listens there
    env = {
        **os.environ,
        "PYTHONPATH": str(ROOT),
        "GATEWAY_CLUSTER_NATS_URL": nats_url,
        # checked after NATS: never reached, so no PostgreSQL server is needed here
        "GATEWAY_DATABASE_URL": f"postgresql+asyncpg://fleet:fleet@127.0.0.1:{free_tcp_port()}/fleet",
    }
    result = subprocess.run(
        [sys.executable, "-m", "gateway.cli", "serve", "--port", str(free_tcp_port())],
        cwd=tmp_path, env=env, capture_output=True, text=True, timeout=scaled(120),
    )  # fmt: skip
    lines = [line for line in result.stderr.splitlines() if line.strip()]
    assert result.returncode == 2, result.stderr
    assert len(lines) == 1, lines
    assert lines[0].startswith(f"error: cannot reach NATS at {nats_url} (GATEWAY_CLUSTER_NATS_URL): "), lines
    assert "unset GATEWAY_CLUSTER_NATS_URL" in lines[0]
    assert list(tmp_path.iterdir()) == []
