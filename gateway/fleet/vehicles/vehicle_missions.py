"""A vehicle's mission: upload, download, clear, start, jump to an item, and its progress in the user's
item numbers (1..N), through the autopilot's dialect.

Missions are uploaded with ``mission_raw`` in the dialect's layout (ArduPilot: home at seq 0, hidden;
PX4: none) and come back in user numbers 1..N; a mission the autopilot rejects is refused with its
words and never started. Each command first asks the vehicle for its dialect (`Vehicle.require_dialect`),
which refuses an autopilot the gateway has no dialect for before anything is sent.
"""

from __future__ import annotations

import asyncio
import contextlib
import json
from collections.abc import Sequence
from typing import Protocol

from gateway.errors import CommandFailed, InvalidArgument
from gateway.fleet.dialects import Dialect, DialectReads
from gateway.fleet.dialects.base import mission_progress
from gateway.fleet.missions import mission
from gateway.fleet.missions.mission import MissionItem, WirePlan
from gateway.link.mavsdk_system import MissionRawItem, System
from gateway.link.session import Link
from gateway.link.telemetry import MissionProgressValue, StatusTextValue

MISSION_TIMEOUT_S = 30.0
MISSION_STATE_COMPLETE = 5  # MISSION_CURRENT.mission_state


class MissionHost(Protocol):
    """What a vehicle's mission needs of the vehicle (`gateway.fleet.vehicles.vehicle.Vehicle`)."""

    @property
    def dialect(self) -> DialectReads: ...

    def require_dialect(self) -> Dialect: ...

    def require_ready(self) -> None: ...

    def on_ground(self, fresh: bool = True) -> bool | None: ...

    async def arm(self) -> None: ...


class MissionControl:
    """The mission of one vehicle, over its link: what is on board (``plan``, in the dialect's layout),
    how far it is (``state``: MISSION_CURRENT.mission_state) and the autopilot's words when it refused
    the last upload (``rejection``)."""

    def __init__(self, link: Link, vehicle: MissionHost) -> None:
        self.link = link
        self.vehicle = vehicle
        self.plan: WirePlan | None = None
        self.state: int | None = None  # MISSION_CURRENT.mission_state (5 = COMPLETE)
        self.rejection: str | None = None  # the autopilot's words when it refused the mission

    def wire_progress(self, current: int, total: int) -> MissionProgressValue:
        """MAVSDK's mission progress (wire seq, wire count) in user numbers. "Finished" comes from
        MISSION_CURRENT's mission_state COMPLETE: MAVSDK's progress never reaches current == total
        against ArduPilot, whose MISSION_CURRENT.total leaves out home."""
        finished = self.state == MISSION_STATE_COMPLETE
        return mission_progress(
            self.vehicle.dialect, current, total, self.plan, finished, from_mission_current=False
        )

    async def follow(self, system: System) -> None:
        """MISSION_CURRENT (requested at 1 Hz): current seq and the mission state."""
        async for msg in system.mavlink_direct.message("MISSION_CURRENT"):
            fields = json.loads(msg.fields_json)
            state = int(fields.get("mission_state", 0))
            if state != self.state:
                self.state = state
                progress = mission_progress(
                    self.vehicle.dialect,
                    int(fields.get("seq", 0)),
                    int(fields.get("total", 0)),
                    self.plan,
                    state == MISSION_STATE_COMPLETE,
                    from_mission_current=True,
                )
                self.link.telemetry.put("mission_progress", progress)

    async def upload(self, items: Sequence[MissionItem | dict[str, object]]) -> int:
        """Upload user items 1..N in the dialect's layout (ArduPilot: home at seq 0, hidden). Returns N.

        Raises CommandFailed with the autopilot's words when it refuses the mission, in the MISSION_ACK
        (ArduPilot: e.g. NO_SPACE and "Only N items are supported") or (PX4) in the text of its
        feasibility check. After a refused (or failed) upload the drone holds the mission it had, or
        one it rejected: either way not the caller's, so `start_mission` refuses until an upload
        succeeds or the mission is cleared."""
        dialect = self.vehicle.require_dialect()
        if not isinstance(items, list | tuple) or not items:
            raise InvalidArgument("a mission needs at least one item")
        if len(items) > mission.MAX_ITEMS:
            raise InvalidArgument(f"a mission holds at most {mission.MAX_ITEMS} items; got {len(items)}")
        parsed: list[MissionItem] = []
        for k, item in enumerate(items, start=1):
            try:
                parsed.append(item if isinstance(item, MissionItem) else MissionItem.model_validate(item))
            except Exception as exc:
                raise InvalidArgument(f"mission item {k}: {exc}") from None
        system = self.link.require_session()
        home = self.link.telemetry.home
        plan = dialect.encode_mission(
            parsed, (home.value.lat_deg, home.value.lon_deg, home.value.abs_alt_m) if home else None
        )
        raw = [
            MissionRawItem(
                w.seq, w.frame, w.command, 1 if w.seq == 0 else 0, 1,
                w.param1, w.param2, w.param3, w.param4, w.x, w.y, w.z, 0,
            )
            for w in plan.items
        ]  # fmt: skip
        self.plan = None  # whatever was on board is being replaced
        self.state = None
        try:
            rejection = await self._upload_checked(system, raw, dialect)
        except CommandFailed as exc:
            self.rejection = exc.message
            raise
        self.plan = plan
        self.rejection = rejection
        if rejection is not None:
            raise CommandFailed(
                f"drone '{self.link.id}' rejected the mission ({len(parsed)} items): {rejection}. "
                "It will not be started; change the items and upload again.",
                vehicle_id=self.link.id,
                result="MISSION_REJECTED",
            )
        return len(parsed)

    async def _upload_checked(self, system: System, raw: list[object], dialect: Dialect) -> str | None:
        """Upload; return the autopilot's rejection text if its feasibility check refused the mission
        after accepting the transfer (PX4). A MISSION_ACK error raises CommandFailed."""
        heard: list[str] = []
        verdict = asyncio.Event()

        def listen(item: StatusTextValue) -> None:
            text = item.text.strip()
            if dialect.mission_rejection(text):
                heard.append(text)
                verdict.set()

        self.link.telemetry.on_status_text(listen)
        try:
            # a MISSION_ACK error raises CommandFailed with the result and what the autopilot said
            await self.link.call("upload mission", system.mission_raw.upload_mission(raw), MISSION_TIMEOUT_S)
            if dialect.mission_verdict_s > 0:
                with contextlib.suppress(TimeoutError):
                    await asyncio.wait_for(verdict.wait(), dialect.mission_verdict_s)
        finally:
            self.link.telemetry.remove_status_listener(listen)
        return heard[0] if heard else None

    async def download(self) -> list[MissionItem]:
        """The vehicle's mission as user items 1..N."""
        dialect = self.vehicle.require_dialect()
        system = self.link.require_session()
        raw = await self.link.call(
            "download mission", system.mission_raw.download_mission(), MISSION_TIMEOUT_S
        )
        items, plan = dialect.decode_mission(list(raw))
        self.plan = plan
        return items

    async def clear(self) -> None:
        self.vehicle.require_dialect()
        system = self.link.require_session()
        await self.link.call("clear mission", system.mission_raw.clear_mission(), MISSION_TIMEOUT_S)
        self.plan = WirePlan(items=[], user_to_wire=[])
        self.state = None
        self.rejection = None

    async def start(self) -> None:
        """Run the uploaded mission: in the air, switch to it (AUTO / MISSION); on the ground, the
        dialect's way of arming and starting it. A mission the autopilot rejected is never started."""
        dialect = self.vehicle.require_dialect()
        self.vehicle.require_ready()
        system = self.link.system
        if self.rejection is not None:
            raise CommandFailed(
                f"drone '{self.link.id}' rejected the last mission uploaded to it ({self.rejection}); "
                "it starts none until it accepts one: upload a corrected mission first",
                vehicle_id=self.link.id,
                result="MISSION_REJECTED",
            )
        if self.plan is None:
            await self.download()
        if self.plan is None or not self.plan.user_to_wire:
            raise CommandFailed(
                f"drone '{self.link.id}' has no mission to start; upload one first", vehicle_id=self.link.id
            )
        self.state = None  # a COMPLETE from an earlier run is not this run's
        if self.vehicle.on_ground() is False:
            await self.link.call("start mission", system.mission_raw.start_mission())
            return
        await dialect.start_mission_on_ground(self.link, self.vehicle.arm)

    async def set_current(self, user_index: int) -> None:
        self.vehicle.require_dialect()
        if not isinstance(user_index, int) or isinstance(user_index, bool):
            raise InvalidArgument(f"mission item index must be an integer; got {user_index!r}")
        system = self.link.require_session()
        if self.plan is None:
            await self.download()
        plan = self.plan
        count = len(plan.user_to_wire) if plan else 0
        if plan is None or not 1 <= user_index <= count:
            raise InvalidArgument(f"mission item index must be 1..{count}; got {user_index}")
        await self.link.call(
            "set current mission item", system.mission_raw.set_current_mission_item(plan.wire_seq(user_index))
        )

    async def is_finished(self) -> bool:
        self.vehicle.require_dialect()
        if self.state == MISSION_STATE_COMPLETE:
            return True
        finished = await self.link.call(
            "mission finished", self.link.require_session().mission_raw.is_mission_finished()
        )
        return bool(finished)
