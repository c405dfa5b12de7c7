"""schemathesis with every check against a real gateway (``fleet-gateway serve`` on SQLite, a simulated
ArduCopter behind a real sidecar, operator tokens set so the authentication checks have something to
check): no check fails. Its checks cover what the REST API promises beyond "no 5xx"
(tests/fuzz/test_rest_schemathesis.py): each status and body the answers carry is in the OpenAPI document,
the document's schemas are as strict as the validation (a request it allows is accepted, one it forbids is
refused), a 405 names in ``Allow`` every method the path serves, a request without the token is refused.

The run is bounded (examples per operation) and seeded, so a failure replays. Where a rule is one a JSON
Schema cannot state (a time window backwards, a polygon that crosses itself), tests/fuzz/schemathesis.toml
names the operations whose 422 is then the expected answer, and why.
"""

from __future__ import annotations

import asyncio
import shutil
import subprocess
import sys
from pathlib import Path

import httpx
import pytest

from tests.fault.gateway_proc import gateway_process
from tests.helpers.procs import tail
from tests.helpers.sim import sim_process
from tests.helpers.timing import scaled

CONFIG = Path(__file__).with_name("schemathesis.toml")
TOKEN = "standards-operator-token"
EXAMPLES = 6
SEED = 20261129


def _schemathesis() -> str:
    found = shutil.which("schemathesis", path=str(Path(sys.executable).parent))
    if found is None:
        pytest.skip("schemathesis is not installed (pip install 'fleet-gateway[dev]' installs it)")
    return found


@pytest.mark.timeout(scaled(1200))
async def test_rest_api_passes_every_schemathesis_check_on_a_real_gateway(tmp_path: Path) -> None:
    command = _schemathesis()
    log = tmp_path / "gateway.log"
    auth = {"Authorization": f"Bearer {TOKEN}"}
    async with sim_process(1, speedup=5.0) as sim:
        with gateway_process(tmp_path / "gw.db", log, {"GATEWAY_OPERATOR_TOKENS": TOKEN}) as (_proc, base):
            async with httpx.AsyncClient(base_url=base, headers=auth, timeout=scaled(10)) as http:
                deadline = asyncio.get_running_loop().time() + scaled(60)
                while True:  # the gateway answers once its store and registry are up
                    try:
                        if (await http.get("/readyz")).status_code == 200:
                            break
                    except httpx.TransportError:
                        pass
                    assert asyncio.get_running_loop().time() < deadline, tail(str(log))
                    await asyncio.sleep(0.2)
                drone = {"id": "alpha", "url": sim.urls[0], "expected_sysid": sim.sysids[0]}
                assert (await http.post("/api/v1/vehicles", json=drone)).status_code == 201
            args = [
                command, "--config-file", str(CONFIG), "run", f"{base}/openapi.json",
                "--checks", "all", "--max-examples", str(EXAMPLES), "--seed", str(SEED),
                "--generation-database", "none", "--header", f"Authorization: Bearer {TOKEN}",
                # the live event stream never ends (tests/console/test_events_api.py covers it)
                "--exclude-path", "/api/v1/events",
                "--request-timeout", str(scaled(30)), "--no-color",
            ]  # fmt: skip
            done = await asyncio.to_thread(
                subprocess.run, args, capture_output=True, text=True, timeout=scaled(900), cwd=tmp_path
            )
    report = done.stdout[-12000:] + done.stderr[-2000:]
    print(report[-1500:])
    assert done.returncode == 0, report
    assert "passed" in done.stdout and "failed" not in done.stdout.split("SUMMARY")[-1], report
