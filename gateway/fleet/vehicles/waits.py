"""Waiting on a vehicle: its connection state, one wait for every view of a drone (a `Vehicle` this node
flies, a `RemoteVehicle` another node flies), read from `VehicleView.state`; and a condition on what it
reports, polled until a deadline."""

from __future__ import annotations

import asyncio
from collections.abc import Callable

from gateway.errors import CommandFailed, VehicleNotReady
from gateway.fleet.vehicles.protocols import VehicleView
from gateway.link.contract import ConnectionState
from gateway.link.telemetry import TelemetryCache

POLL_S = 0.1
#: an action whose ACK MAVSDK gave up on ("Timeout") counts as run once the autopilot shows its effect
#: (its mode or armed state in its 1 Hz HEARTBEAT, the target it reports) within this long
UNACKED_WAIT_S = 3.0


async def wait_for_state(
    view: VehicleView, *states: ConnectionState | str, within_s: float = 60.0
) -> ConnectionState:
    """Wait until the drone's state is one of ``states``; VehicleNotReady naming the state it is in
    (and why, when its view says: what it still waits for, its last error) once ``within_s`` passed."""
    wanted = {ConnectionState(s) for s in states}
    if not await holds_within(lambda: view.state in wanted, within_s):
        state = view.state
        why = "; ".join(filter(None, (view.initialising(), view.last_error)))
        raise VehicleNotReady(
            f"drone '{view.id}' did not reach {'/'.join(sorted(s.value for s in wanted))} within "
            f"{within_s:g} s; it is {state.value}" + (f" ({why})" if why else ""),
            state=state.value,
        )
    return view.state


async def holds_within(check: Callable[[], bool], within_s: float, poll_s: float = POLL_S) -> bool:
    """Whether ``check()`` holds within ``within_s`` (asked every ``poll_s``; False once the time passed)."""
    loop = asyncio.get_running_loop()
    deadline = loop.time() + within_s
    while not check():
        if loop.time() > deadline:
            return False
        await asyncio.sleep(poll_s)
    return True


def ack_lost(exc: CommandFailed) -> bool:
    """MAVSDK gave up waiting for the COMMAND_ACK (its retries spent): the autopilot may have run it."""
    return exc.details.get("result") == "TIMEOUT"


async def shown_though_unacknowledged(exc: CommandFailed, shown: Callable[[], bool]) -> bool:
    """Whether an action that failed with ``exc`` ran all the same: its ACK was lost (a starved
    autopilot's ACKs come after MAVSDK's retries) and ``shown()`` holds within UNACKED_WAIT_S."""
    return ack_lost(exc) and await holds_within(shown, UNACKED_WAIT_S)


def armed_heard_since(telemetry: TelemetryCache, sent: float, armed: bool) -> bool:
    """Whether a report heard at or after ``sent`` (monotonic) says the motors are ``armed`` (True) or
    disarmed (False): the effect of an arm, disarm or kill, never a report from before it."""
    sample = telemetry.armed
    return sample is not None and sample.received_at >= sent and sample.value is armed


def mode_heard_since(
    telemetry: TelemetryCache, sent: float, modes: frozenset[str], other_than: str | None
) -> bool:
    """Whether a report heard at or after ``sent`` (monotonic) shows one of ``modes`` other than
    ``other_than`` (the mode before the call): a mode the call switched to, never one it was already in."""
    sample = telemetry.flight_mode
    return (
        sample is not None
        and sample.received_at >= sent
        and sample.value in modes
        and sample.value != other_than
    )
