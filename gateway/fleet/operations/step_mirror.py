"""A fleet step that another cluster node runs, seen here as a local mirror of the owner's operation:
kept up to date by following it on its owner (waits of FOLLOW_WAIT_S, one after the other)."""

from __future__ import annotations

import asyncio
from datetime import UTC, datetime

from gateway.errors import GatewayError
from gateway.fleet.operations.fleet_operation import FLEET_CALLER
from gateway.fleet.operations.operation_state import Operation, OpStatus
from gateway.fleet.operations.routing import ProgressMessage, RoutedCall, Router
from gateway.fleet.operations.views import OperationView

FOLLOW_WAIT_S = 30.0
"""A step run on another node is followed by waits of this length, one after the other."""


def mirror_view(mirror: Operation, view: OperationView) -> None:
    """Bring a local mirror of an operation another node runs up to date with its view there."""
    mirror.progress = view.progress
    mirror.message = view.message or mirror.message
    mirror.eta_s = view.eta_s
    status = OpStatus(view.status)
    if status is not OpStatus.running and not mirror.finished:
        mirror.status = status
        mirror.finished_at = datetime.now(UTC)
        mirror.done.set()
    mirror.changed.set()


async def follow(router: Router, mirror: Operation) -> None:
    """Wait on the owner, again and again, until the operation there has finished."""

    async def message(body: ProgressMessage) -> None:
        view = body.get("view")
        if view is not None:
            mirror_view(mirror, OperationView.model_validate(view))

    failures = 0
    while not mirror.finished:
        try:
            view = await router.call(
                RoutedCall(
                    mirror.vehicle_id,
                    "wait",
                    FLEET_CALLER,
                    {"operation_id": mirror.id, "cap_s": FOLLOW_WAIT_S},
                    message,
                    wait_s=FOLLOW_WAIT_S,
                )
            )
            mirror_view(mirror, OperationView.model_validate(view))
            failures = 0
        except asyncio.CancelledError:
            raise
        except GatewayError as exc:  # the owner was lost: its successor picks the operation up
            failures += 1
            mirror.message = f"following {mirror.vehicle_id} on its owner failed: {exc.message}"
            mirror.changed.set()
            if failures >= 5:
                mirror.status = OpStatus.interrupted
                mirror.finished_at = datetime.now(UTC)
                mirror.done.set()
                mirror.changed.set()
                return
            await asyncio.sleep(1.0)
