"""schemathesis over the operator REST API's own OpenAPI document: generated valid and invalid requests for
every operation must never get a server error (5xx).

The app is the real one (real SQLite store, real HTTP on loopback) with the REST unit tests' stand-in
registry, so no request can start a sidecar on a generated URL. A drone "alpha" exists, and a share of the
requests with a vehicle id aim at it. Examples are bounded (15 per operation) to keep the suite short.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import httpx
import schemathesis
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from schemathesis.checks import not_a_server_error
from schemathesis.generation import GenerationMode

from gateway.app import create_app
from gateway.config import Settings
from tests.api.server import serve_in_thread
from tests.fakes import FakeRegistry
from tests.helpers.timing import scaled

EXAMPLES_PER_OPERATION = 15
DRONE = {"id": "alpha", "url": "udpin://127.0.0.1:14550", "expected_sysid": 1}


def test_rest_api_answers_generated_requests_without_server_errors(tmp_path: Path) -> None:
    config = Settings(_env_file=None, database_url=f"sqlite+aiosqlite:///{tmp_path / 'gateway.db'}")
    app = create_app(config, registry_factory=FakeRegistry)
    checked: dict[str, int] = {}
    with serve_in_thread(app) as base_url:
        schema = schemathesis.openapi.from_url(f"{base_url}/openapi.json")
        # the live event stream never ends (it is tested in tests/console/test_events_api.py)
        operations = [
            op
            for op in (result.ok() for result in schema.get_all_operations())
            if op.path != "/api/v1/events"
        ]
        assert len(operations) >= 20, [op.label for op in operations]

        def ensure_drone() -> None:
            httpx.post(f"{base_url}/api/v1/vehicles", json=DRONE, timeout=scaled(30))

        for operation in operations:
            strategies = [
                operation.as_strategy(generation_mode=GenerationMode.POSITIVE),
                operation.as_strategy(generation_mode=GenerationMode.NEGATIVE),
            ]
            if "{vehicle_id}" in operation.path:
                strategies.append(
                    operation.as_strategy(
                        generation_mode=GenerationMode.POSITIVE, path_parameters={"vehicle_id": "alpha"}
                    )
                )

            @settings(
                max_examples=EXAMPLES_PER_OPERATION,
                deadline=None,
                database=None,
                derandomize=True,
                suppress_health_check=list(HealthCheck),
            )
            @given(case=st.one_of(strategies))
            def run(case: Any) -> None:
                ensure_drone()
                case.call_and_validate(base_url=base_url, checks=[not_a_server_error], timeout=scaled(30))
                label = case.operation.label
                checked[label] = checked.get(label, 0) + 1

            run()
    print(f"\nschemathesis: {len(checked)} operations, {sum(checked.values())} requests, no server error")
    assert set(checked) == {op.label for op in operations}
