"""MAVProxy (PyPI) as a ground station at a drone's gcs_endpoints, by hand: a simulated drone, a gateway
(`fleet-gateway serve` on a temporary SQLite file), the drone registered over REST with a `tcpin`
endpoint, an operator's takeoff, then MAVProxy connects there and switches the mode to LOITER; prints
what MAVProxy saw and what the gateway reports (the takeover, the endpoint's counters).

MAVProxy pulls in OpenCV, VTK and matplotlib, so it is not a test dependency; install it apart:

    python3 -m venv /tmp/mavproxy && /tmp/mavproxy/bin/pip install mavproxy
    .venv/bin/python scripts/mavproxy_through_relay.py /tmp/mavproxy/bin/mavproxy.py
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
import time
import urllib.error
import urllib.request
from pathlib import Path
from typing import Any

from gateway.util.ports import free_tcp_port


def main(mavproxy: str) -> int:
    tmp = Path(tempfile.mkdtemp(prefix="mavproxy-relay-"))
    sim_port, gw_port, gcs_port = free_tcp_port(), free_tcp_port(), free_tcp_port()
    base = f"http://127.0.0.1:{gw_port}"

    def rest(method: str, path: str, body: dict[str, Any] | None = None) -> Any:
        data = None if body is None else json.dumps(body).encode()
        req = urllib.request.Request(
            base + path, method=method, data=data, headers={"content-type": "application/json"}
        )
        with urllib.request.urlopen(req, timeout=30) as answer:
            return json.loads(answer.read() or b"null")

    def until(what: str, check: Any, within_s: float = 120.0) -> None:
        deadline = time.monotonic() + within_s
        while time.monotonic() < deadline:
            try:
                if check():
                    return
            except (OSError, urllib.error.URLError, KeyError, TypeError):
                pass
            time.sleep(0.5)
        raise SystemExit(f"gave up waiting for {what}")

    exe = str(Path(sys.executable).with_name("fleet-gateway"))
    env = dict(os.environ, GATEWAY_DATABASE_URL=f"sqlite+aiosqlite:///{tmp / 'gateway.db'}")
    sim = subprocess.Popen(
        [exe, "sim", "--count", "1", "--tcp-base-port", str(sim_port), "--speedup", "4"],
        stdout=(tmp / "sim.log").open("w"),
        stderr=subprocess.STDOUT,
    )
    gateway = subprocess.Popen(
        [exe, "serve", "--port", str(gw_port)],
        env=env,
        stdout=(tmp / "gateway.log").open("w"),
        stderr=subprocess.STDOUT,
    )
    proxy: subprocess.Popen[str] | None = None
    try:
        until("the gateway", lambda: urllib.request.urlopen(base + "/healthz", timeout=2))
        endpoint = f"tcpin://127.0.0.1:{gcs_port}"
        drone = {"id": "d1", "url": f"tcpout://127.0.0.1:{sim_port}", "gcs_endpoints": [endpoint]}
        rest("POST", "/api/v1/vehicles", drone)
        until("d1 ready", lambda: rest("GET", "/api/v1/vehicles/d1")["state"] == "ready")
        rest("POST", "/api/v1/vehicles/d1/takeoff", {"alt_rel_m": 10})
        until(
            "d1 at 8 m", lambda: rest("GET", "/api/v1/vehicles/d1")["telemetry"]["position"]["rel_alt_m"] > 8
        )
        log = tmp / "mavproxy.log"
        proxy = subprocess.Popen(
            [
                mavproxy,
                f"--master=tcp:127.0.0.1:{gcs_port}",
                "--source-system",
                "255",
                "--state-basedir",
                str(tmp),
            ],
            stdin=subprocess.PIPE,
            stdout=log.open("w"),
            stderr=subprocess.STDOUT,
            text=True,
        )
        until("MAVProxy to see the drone", lambda: "online system" in log.read_text(errors="replace"))
        assert proxy.stdin is not None
        proxy.stdin.write("mode LOITER\n")
        proxy.stdin.flush()
        until("the takeover", lambda: rest("GET", "/api/v1/vehicles/d1")["taken_over"] is not None, 30)
        vehicle = rest("GET", "/api/v1/vehicles/d1")
        seen = [
            line
            for line in log.read_text(errors="replace").splitlines()
            if "Detected" in line or "ACK" in line
        ]
        print("MAVProxy:", *seen, sep="\n  ")
        print("gateway: taken_over", vehicle["taken_over"]["reason"])
        print("gateway: mode", vehicle["status"]["flight_mode"])
        print("gateway: ground station endpoint", vehicle["status"]["ground_stations"])
        return 0
    finally:
        for proc in (proxy, gateway, sim):
            if proc is not None and proc.poll() is None:
                proc.terminate()
                try:
                    proc.wait(20)
                except subprocess.TimeoutExpired:
                    proc.kill()


if __name__ == "__main__":
    if len(sys.argv) != 2:
        raise SystemExit(__doc__)
    sys.exit(main(sys.argv[1]))
