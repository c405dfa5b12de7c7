"""Boot readiness of an ArduCopter, real SITL or the simulator, seen by a bare MAVLink ground station.

From the vehicle's own clock (``time_boot_ms``, i.e. simulated seconds since boot), when: the GPS has a
3D fix, the EKF origin is set, home is known, SYS_STATUS's pre-arm bit is set (in GUIDED), the EKF says
it has an absolute position (EKF_STATUS_REPORT, what the gateway's "ready" waits for), "EKF3 IMU0 is
using GPS", and the first arming in GUIDED is accepted (tried every 0.25 simulated seconds from the
start, disarmed at once). Also which "Arm: ..." refusals were seen, and when.

Run: .venv/bin/python bench/readiness.py [--real] [--speedup 5] [--runs 3]
(``--real`` needs ``eval "$(../shared/sitl/install)"``; without it the simulator is measured.)
"""

from __future__ import annotations

import argparse
import asyncio
import contextlib
import sys
import tempfile
from collections.abc import AsyncIterator
from dataclasses import dataclass, field
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from pymavlink.dialects.v20 import ardupilotmega as mav

from tests.helpers import autopilots, sim_process
from tests.helpers.raw import RawMavlink, raw_mavlink

GUIDED = 4
PREARM_BIT = 0x10000000  # MAV_SYS_STATUS_PREARM_CHECK
EKF_POS_HORIZ_ABS = 16
EKF_CONST_POS_MODE = 128
ARM_PERIOD_S = 0.25  # simulated seconds between arming attempts
#: message id -> interval (simulated µs): a fine clock (ATTITUDE) and the readiness facts
STREAMS = {30: 50_000, 1: 200_000, 24: 200_000, 193: 200_000, 242: 500_000}
MILESTONES = ("gps_3d", "origin", "home", "prearm", "ekf_abs", "ekf_text", "armed")
LABELS = {
    "gps_3d": "GPS 3D fix",
    "origin": "EKF origin set",
    "home": "home position",
    "prearm": "pre-arm bit (GUIDED)",
    "ekf_abs": "EKF absolute position",
    "ekf_text": '"EKF3 IMU0 is using GPS"',
    "armed": "first GUIDED arm accepted",
}


@dataclass
class Readiness:
    """Milestones in simulated seconds since boot (None: not reached), and arming refusals seen."""

    at: dict[str, float | None] = field(default_factory=lambda: dict.fromkeys(MILESTONES))
    refusals: dict[str, tuple[float, float, int]] = field(default_factory=dict)  # text -> first, last, n
    attempts: int = 0
    sequence: list[tuple[float, float, str]] = field(default_factory=list)  # refusal runs: from, to, text

    def origin_to_arm(self) -> float | None:
        o, a = self.at["origin"], self.at["armed"]
        return None if o is None or a is None else a - o

    def done(self) -> bool:
        return all(v is not None for v in self.at.values())


class _Clock:
    """The vehicle's boot clock: the newest ``time_boot_ms`` heard, in seconds."""

    def __init__(self) -> None:
        self.t: float | None = None

    def see(self, msg: mav.MAVLink_message) -> None:
        ms = getattr(msg, "time_boot_ms", None)
        if ms is not None and msg.get_type() in ("ATTITUDE", "GLOBAL_POSITION_INT", "SYSTEM_TIME"):
            self.t = ms / 1000.0


def _command(command: int, *params: float) -> mav.MAVLink_message:
    """COMMAND_LONG to system 1, component 1."""
    p = [*params, *([0.0] * (7 - len(params)))]
    return mav.MAVLink_command_long_message(1, 1, command, 0, *p)


@contextlib.asynccontextmanager
async def _link(url: str, within_s: float = 30.0) -> AsyncIterator[RawMavlink]:
    """``raw_mavlink`` retried until the autopilot's TCP port accepts."""
    loop = asyncio.get_running_loop()
    deadline = loop.time() + within_s
    while True:
        try:
            cm = raw_mavlink(url)
            client = await cm.__aenter__()
            break
        except OSError:
            if loop.time() > deadline:
                raise
            await asyncio.sleep(0.1)
    try:
        yield client
    finally:
        await cm.__aexit__(None, None, None)


async def probe(url: str, speedup: float, within_s: float = 120.0) -> Readiness:
    """Connect to a freshly started autopilot and record its readiness milestones (see module doc)."""
    r = Readiness()
    clock = _Clock()
    loop = asyncio.get_running_loop()
    deadline = loop.time() + within_s / speedup + 20.0
    async with _link(url) as gcs:
        seen: set[int] = set()
        next_request_at = 0.0
        index = 0
        mode: int | None = None
        next_mode_at = 0.0
        next_arm_t = 0.0
        arm_pending_since: float | None = None
        while loop.time() < deadline and not r.done():
            await asyncio.sleep(0.01)
            batch = gcs.received[index:]
            index += len(batch)
            for _wall, msg in batch:
                seen.add(msg.get_msgId())
                clock.see(msg)
                t = clock.t
                kind = msg.get_type()
                if kind == "HEARTBEAT" and msg.get_srcComponent() == 1:
                    mode = msg.custom_mode
                if t is None:
                    continue
                if kind == "GPS_RAW_INT" and msg.fix_type >= 3:
                    r.at["gps_3d"] = r.at["gps_3d"] or t
                elif kind == "GPS_GLOBAL_ORIGIN":
                    r.at["origin"] = r.at["origin"] or t
                elif kind == "HOME_POSITION":
                    r.at["home"] = r.at["home"] or t
                elif kind == "SYS_STATUS" and mode == GUIDED:
                    if msg.onboard_control_sensors_health & PREARM_BIT:
                        r.at["prearm"] = r.at["prearm"] or t
                elif kind == "EKF_STATUS_REPORT":
                    if msg.flags & EKF_POS_HORIZ_ABS and not msg.flags & EKF_CONST_POS_MODE:
                        r.at["ekf_abs"] = r.at["ekf_abs"] or t
                elif kind == "STATUSTEXT":
                    text = msg.text.rstrip("\0")
                    if "origin set" in text:
                        r.at["origin"] = r.at["origin"] or t
                    if "is using GPS" in text:
                        r.at["ekf_text"] = r.at["ekf_text"] or t
                    if text.startswith("Arm: "):
                        first, _last, n = r.refusals.get(text, (t, t, 0))
                        r.refusals[text] = (first, t, n + 1)
                        if r.sequence and r.sequence[-1][2] == text:
                            r.sequence[-1] = (r.sequence[-1][0], t, text)
                        else:
                            r.sequence.append((t, t, text))
                elif kind == "COMMAND_ACK" and msg.command == 400 and arm_pending_since is not None:
                    arm_pending_since = None
                    if msg.result == mav.MAV_RESULT_ACCEPTED and r.at["armed"] is None:
                        r.at["armed"] = t
                        gcs.send(_command(400, 0))
            if loop.time() >= next_request_at:  # requests sent while the autopilot starts can be lost
                for msg_id, interval in STREAMS.items():
                    if msg_id not in seen:
                        gcs.send(_command(511, msg_id, interval))
                next_request_at = loop.time() + 1.0
            t = clock.t
            if t is None:
                continue
            if mode != GUIDED and loop.time() >= next_mode_at:  # always accepted while disarmed
                gcs.send(_command(176, 1, GUIDED))
                next_mode_at = loop.time() + 1.0
            if arm_pending_since is not None and loop.time() - arm_pending_since > 2.0:
                arm_pending_since = None  # lost: try again
            if mode == GUIDED and r.at["armed"] is None and arm_pending_since is None and t >= next_arm_t:
                gcs.send(_command(400, 1))
                r.attempts += 1
                arm_pending_since = loop.time()
                next_arm_t = t + ARM_PERIOD_S
    return r


async def run_real(speedup: float) -> Readiness:
    with tempfile.TemporaryDirectory(prefix="readiness-") as folder:
        with autopilots.arducopter(Path(folder), speedup=speedup) as ap:
            return await probe(ap.url, speedup)


async def run_sim(speedup: float) -> Readiness:
    async with sim_process(1, speedup=speedup) as sim:
        return await probe(sim.urls[0], speedup)


def spread(values: list[float]) -> str:
    if not values:
        return "n/a"
    lo, hi = f"{min(values):.1f}", f"{max(values):.1f}"
    return lo if lo == hi else f"{lo}-{hi}"


def report(title: str, runs: list[Readiness]) -> str:
    lines = [f"{title} ({len(runs)} runs; simulated seconds since boot)"]
    for key in MILESTONES:
        lines.append(f"  {LABELS[key]:28} {spread([v for r in runs if (v := r.at[key]) is not None])}")
    delays = [d for r in runs if (d := r.origin_to_arm()) is not None]
    lines.append(f"  {'origin -> first GUIDED arm':28} {spread(delays)}")
    texts: dict[str, list[tuple[float, float]]] = {}
    for r in runs:
        for text, (first, last, _n) in r.refusals.items():
            texts.setdefault(text, []).append((first, last))
    for text, spans in sorted(texts.items(), key=lambda kv: min(f for f, _ in kv[1])):
        first, last = spread([f for f, _ in spans]), spread([la for _, la in spans])
        lines.append(f"  refused {text!r}: from {first} to {last}")
    return "\n".join(lines)


async def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--real", action="store_true", help="real ArduCopter SITL instead of the simulator")
    p.add_argument("--speedup", type=float, default=5.0)
    p.add_argument("--runs", type=int, default=3)
    p.add_argument("--parallel", type=int, default=1, help="runs at once")
    args = p.parse_args()
    run = run_real if args.real else run_sim
    sem = asyncio.Semaphore(args.parallel)

    async def one() -> Readiness:
        async with sem:
            return await run(args.speedup)

    runs = await asyncio.gather(*(one() for _ in range(args.runs)))
    for r in runs:
        print({k: (None if v is None else round(v, 2)) for k, v in r.at.items()}, "attempts", r.attempts)
        print("   ", "; ".join(f"{a:.1f}-{b:.1f} {text}" for a, b, text in r.sequence))
    print(report(f"{'ArduCopter SITL' if args.real else 'simulator'} at speed-up {args.speedup:g}", runs))


if __name__ == "__main__":
    asyncio.run(main())
