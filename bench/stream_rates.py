"""Telemetry rates at rest: what the gateway asks each autopilot for, against what arrives.

One drone, disarmed on the ground, a real ArduCopter SITL (``eval "$(../shared/sitl/install)"``; real time)
or with ``--sim`` the project's simulator. Once the drone is ready and has settled, the updates the
gateway's cache received per stream are counted over a window (``/metrics``,
``fleet_gateway_telemetry_messages_total``) and set beside the rate asked for
(``gateway.link.telemetry_feed.STREAM_RATES_HZ``, sent as MAV_CMD_SET_MESSAGE_INTERVAL by MAVSDK's
set_rate_*), with the CPU of the gateway and of the drone's sidecar over the same window. Streams the
gateway takes from another (heading from the attitude, in_air from the landed state, armed and the
flight mode from the HEARTBEAT) are listed with the stream they come with.
"""

from __future__ import annotations

import asyncio
import contextlib
import sys
import tempfile
import time
from collections.abc import AsyncIterator
from pathlib import Path
from typing import Any

import common
import scale

sys.path.insert(0, str(common.ROOT))

from gateway.link.telemetry_feed import STREAM_RATES_HZ

WINDOW_S = 30.0
SETTLE_S = 10.0
#: cache streams that come with another stream (or the HEARTBEAT) instead of a rate of their own
FOLLOWS = {
    "heading_deg": "attitude_euler",
    "attitude": "attitude_euler",
    "velocity_ned": "position",
    "in_air": "landed_state",
    "armed": "HEARTBEAT (1 Hz, not asked for)",
    "flight_mode": "HEARTBEAT (1 Hz, not asked for)",
    "imu": "raw_imu on ArduPilot, imu on PX4",
    "rc_status": "SYS_STATUS and RC_CHANNELS (MAVSDK sets no rate for it)",
}


@contextlib.asynccontextmanager
async def one_drone(use_sim: bool, wd: Path) -> AsyncIterator[common.Gateway]:
    if use_sim:
        async with common.sim(1, speedup=1.0, workdir=wd) as sim_, common.gateway(sim_, workdir=wd) as gw:
            yield gw
        return
    from tests.helpers.autopilots import arducopter, ardupilot_missing

    missing = ardupilot_missing()
    if missing:
        raise SystemExit(f'no ArduCopter SITL: {missing} (eval "$(../shared/sitl/install)", or --sim)')
    with arducopter(wd / "sitl", speedup=1.0, sysid=1, taken=set()) as ap:
        sim_ = common.Sim(
            proc=None, urls=[ap.url], sysids=[1], udp_urls=[None], control_url="", log=wd / "none"
        )  # type: ignore[arg-type]
        async with common.gateway(sim_, workdir=wd) as gw:
            yield gw


async def measure(use_sim: bool) -> dict[str, Any]:
    with tempfile.TemporaryDirectory(prefix="stream-rates-") as tmp:
        wd = Path(tmp)
        (wd / "sitl").mkdir()
        async with one_drone(use_sim, wd) as gw:
            waited, states = await common.wait_states(gw, "ready", 240.0)
            if states.get(gw.drone_ids[0]) != "ready":
                raise SystemExit(f"the drone was not ready after {waited:.0f} s: {states}\n{gw.log_tail()}")
            await asyncio.sleep(SETTLE_S)  # the rates requested at session start have taken effect
            sidecars = await gw.sidecar_pids()
            gw_cpu, sc_cpu = common.CpuMeter([gw.pid]), common.CpuMeter(sidecars)
            c0 = await scale.message_counts(gw)
            gw_cpu.start()
            sc_cpu.start()
            t0 = time.monotonic()
            await asyncio.sleep(WINDOW_S)
            c1 = await scale.message_counts(gw)
            elapsed = time.monotonic() - t0
            return {
                "source": "simulator" if use_sim else "ArduCopter SITL",
                "rates": {k: (v - c0.get(k, 0.0)) / elapsed for k, v in sorted(c1.items())},
                "gw_cpu": gw_cpu.percent(),
                "sc_cpu": sc_cpu.percent(),
            }


def render(r: dict[str, Any]) -> str:
    rows = []
    for name, got in r["rates"].items():
        if name in ("status_text", "mission_progress") and got == 0:
            continue
        asked = STREAM_RATES_HZ.get(name)
        source = FOLLOWS.get(name)
        if asked is None and source in STREAM_RATES_HZ:
            asked = STREAM_RATES_HZ[source]
        rows.append([name, "-" if asked is None else f"{asked:g}", f"{got:.2f}", source or name])
    return "\n".join(
        [
            f"{r['source']}, one drone at rest, {WINDOW_S:g} s window after {SETTLE_S:g} s settling; load "
            f"average {r['load']}. Gateway {r['gw_cpu']:.2f} % of a core (all of it, with its fixed "
            f"costs), sidecar {r['sc_cpu']:.2f} %.",
            "",
            common.table(["cache stream", "asked, Hz", "received per s", "set by"], rows),
        ]
    )


def main() -> int:
    p = common.parser(__doc__.splitlines()[0])
    p.add_argument("--sim", action="store_true", help="the project's simulator instead of ArduCopter SITL")
    args = p.parse_args()
    result = asyncio.run(measure(args.sim))
    result["load"] = Path("/proc/loadavg").read_text().split()[0]  # at the end of the window
    print(render(result))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
