"""Arming a vehicle and switching its flight mode, in its autopilot's dialect: the arming mode switched
to first (ArduPilot's GUIDED), refusals the autopilot lifts by itself while it initialises retried within
one deadline, and every refusal told in the autopilot's words with what to do."""

from __future__ import annotations

import asyncio
import contextlib
import functools
import logging
import time
from typing import Protocol

from gateway.errors import CommandFailed, VehicleNotReady
from gateway.fleet.dialects import Dialect
from gateway.fleet.dialects.modes import ModeChoice
from gateway.fleet.vehicles.waits import armed_heard_since, holds_within, shown_though_unacknowledged
from gateway.link import refusals
from gateway.link.contract import OnWait
from gateway.link.session import Link

log = logging.getLogger("gateway.vehicle")

MODE_CONFIRM_S = 4.0
ARM_RETRY_S = 1.0
MAV_CMD_DO_SET_MODE = 176


class ArmingHost(Protocol):
    """What arming needs of its vehicle (`gateway.fleet.vehicles.vehicle.Vehicle`)."""

    def require_dialect(self) -> Dialect: ...

    def resolve_mode(self, name: str) -> ModeChoice: ...


class Arming:
    """Mode switches and arming of one vehicle, over its link."""

    def __init__(self, link: Link, vehicle: ArmingHost) -> None:
        self.link = link
        self.vehicle = vehicle

    async def switch_mode(self, choice: ModeChoice) -> None:
        """Switch to ``choice``; done once the HEARTBEAT reports it (CommandFailed naming what the
        vehicle reports instead after MODE_CONFIRM_S)."""
        facts = self.link.facts
        if facts.custom_mode == choice.custom_mode:
            return
        await self.link.command_long(MAV_CMD_DO_SET_MODE, *choice.params, what=f"set mode {choice.native}")
        in_it = lambda: self.link.facts.custom_mode == choice.custom_mode  # noqa: E731
        if not await holds_within(in_it, MODE_CONFIRM_S, poll_s=0.05):
            now = self.link.telemetry.fresh("flight_mode") or f"custom mode {self.link.facts.custom_mode}"
            raise CommandFailed(
                f"set mode {choice.native} on drone '{self.link.id}' was accepted "
                f"but the vehicle still reports {now}" + self.link.recent_complaint(),
                vehicle_id=self.link.id,
            )

    async def arm_by(
        self, deadline: float, ready: bool, notify: OnWait | None, trust_cache: bool = True
    ) -> bool:
        """Arm unless the cached state says armed (``trust_cache``); True when an arm command was sent."""
        if trust_cache and self.link.telemetry.fresh("armed"):
            return False
        system = self.link.system
        dialect = self.vehicle.require_dialect()
        loop = asyncio.get_running_loop()
        started = time.time()
        if dialect.arming_mode is not None:
            try:
                await self.switch_mode(self.vehicle.resolve_mode(dialect.arming_mode))
            except CommandFailed as exc:
                if ready:
                    raise
                said = self.link.said_since(started)
                raise self.refusal(exc, said, waited=True, ready=False) from None
        while True:
            attempt_at, sent = time.time(), time.monotonic()
            try:
                await self.link.call("arm", system.action.arm())
                return True
            except CommandFailed as exc:
                armed = functools.partial(armed_heard_since, self.link.telemetry, sent, True)
                if await shown_though_unacknowledged(exc, armed):
                    log.warning(
                        "%s: arm unacknowledged, but the autopilot says armed: accepted", self.link.id
                    )
                    return True
                said = self.link.said_since(attempt_at)
                passing = bool(said) and all(dialect.arming_will_pass(text) for text in said)
                if not ready or not passing or loop.time() + ARM_RETRY_S > deadline:
                    raise self.refusal(exc, said, waited=passing or not ready, ready=ready) from None
            log.info("%s: arming refused while initialising (%s); retrying", self.link.id, "; ".join(said))
            if notify is not None:
                with contextlib.suppress(Exception):  # a courtesy; the retry happens regardless
                    await notify(f"{self.link.id}: autopilot says {refusals.quoted(said)}; trying again")
            await asyncio.sleep(ARM_RETRY_S)

    def refusal(
        self, exc: CommandFailed, said: list[str], waited: bool, ready: bool = True
    ) -> CommandFailed | VehicleNotReady:
        """The refusal of an arming attempt: the autopilot's words and the drone's GPS (and, while it
        initialises, what the gateway still waits for); a reason it lifts by itself ("waited") also
        says what to do. A drone still initialising (not ``ready``) is refused as not ready, in the
        autopilot's words when it gave any, else in the gateway's (what it still waits for)."""
        if not said and not ready:
            try:
                self.link.require_ready()
            except VehicleNotReady as not_ready:
                return VehicleNotReady(
                    f"{not_ready.message}; call again in a few seconds or check fleet_status",
                    state=self.link.state.value,
                )
        if not said:
            return exc
        gps = self.link.telemetry.fresh("gps_info")
        facts = f"GPS {gps.fix_type}, {gps.num_satellites} satellites" if gps is not None else "no GPS report"
        waiting = self.link.initialising()
        if waiting is not None:
            facts += f"; still {waiting}"
        words = refusals.quoted(said)
        if waited:
            text = (
                f"drone '{self.link.id}' cannot arm yet: autopilot says {words} ({facts}); call again in a "
                "few seconds or check fleet_status"
            )
            if not ready:
                return VehicleNotReady(text, state=self.link.state.value)
            return CommandFailed(text, vehicle_id=self.link.id, result=exc.details.get("result"))
        return CommandFailed(
            f"drone '{self.link.id}' refused to arm: autopilot says {words} ({facts})",
            vehicle_id=self.link.id,
            result=exc.details.get("result"),
        )
