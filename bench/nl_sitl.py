"""The NL benchmark's fleet on real autopilots: ArduCopter SITL instances in place of the simulator.

``SitlStack`` is ``gateway.localstack.LocalStack`` with its simulator swapped for one ArduCopter SITL per
drone (``eval "$(/work/shared/sitl/install)"`` sets ARDUPILOT_SITL and ARDUPILOT_DEFAULTS), each with its
own system id, on instance numbers whose ports are free, homes 15 m apart on an east-west line at
ArduPilot's CMAC field. The gateway is the same ``fleet-gateway serve`` the simulator stack starts; the
benchmark reads the drones' truth from the gateway's telemetry (SITL has no control API). Every SITL
process is stopped with the stack.
"""

from __future__ import annotations

import contextlib
import os
from collections.abc import Sequence
from pathlib import Path

from gateway.fleet.geo import offset_position
from gateway.localstack import LocalStack, StackError
from tests.helpers.autopilots import HOME, Unavailable, _free_instance, _running, _tcp_free, ardupilot_missing

SPACING_M = 15.0  # between the drones' homes, west to east

# SITL's battery monitor counts down from BATT_CAPACITY (3,300 mAh by default): measured on a run of the
# test half at speed-up 5, bravo was at 0 % by the tenth request and every later takeoff was refused by
# the battery rule. The harness cannot recharge a SITL battery between requests as it does the
# simulator's, so each autopilot gets a capacity no run drains (the requests about battery levels are
# left out on SITL anyway).
BENCH_PARAMS = "BATT_CAPACITY 1000000\n"


def sitl_argv(
    binary: str, defaults: str, instance: int, home: tuple[float, float, float, float], speedup: float
) -> list[str]:
    return [
        binary, "--model", "+", "--speedup", f"{speedup:g}", f"-I{instance}", "--sysid", str(instance),
        "--defaults", defaults, "--home", f"{home[0]:.7f},{home[1]:.7f},{home[2]:g},{home[3]:g}",
    ]  # fmt: skip


class SitlStack(LocalStack):
    """``async with SitlStack(["alpha", "bravo", "charlie"], speedup=5) as s:`` -> ``s.mcp_url``."""

    def __init__(self, drone_ids: Sequence[str], *, speedup: float = 5.0, **kwargs: object) -> None:
        super().__init__(drone_ids, speedup=speedup, ready_timeout_s=240.0, **kwargs)  # type: ignore[arg-type]
        self._autopilots = contextlib.ExitStack()

    async def _start_sim(self) -> None:
        why = ardupilot_missing()
        if why:
            raise StackError(f"--sitl: {why}")
        taken: set[int] = set()
        lat0, lon0, alt0, heading = HOME
        try:
            for k, _drone in enumerate(self.drone_ids):
                lat, lon = offset_position(lat0, lon0, 0.0, (k - (len(self.drone_ids) - 1) / 2) * SPACING_M)
                instance = _free_instance(
                    lambda i: (5760 + 10 * i, 5762 + 10 * i, 5763 + 10 * i), _tcp_free, range(1, 40), taken
                )
                folder = Path(self.workdir) / f"sitl-{instance}"
                folder.mkdir(parents=True, exist_ok=True)
                bench_params = folder / "bench.parm"
                bench_params.write_text(BENCH_PARAMS)
                argv = sitl_argv(
                    os.environ["ARDUPILOT_SITL"],
                    f"{os.environ['ARDUPILOT_DEFAULTS']},{bench_params}",  # later files override earlier
                    instance,
                    (lat, lon, alt0, heading),
                    self.speedup,
                )
                self._autopilots.enter_context(_running(argv, folder, f"arducopter-{instance}", os.environ))
                self.vehicle_urls.append(f"tcpout://127.0.0.1:{5760 + 10 * instance}")
        except Unavailable as e:
            self._autopilots.close()
            raise StackError(f"--sitl: {e}") from e

    async def _stop(self) -> None:
        try:
            await super()._stop()  # the gateway and its sidecars first, then the autopilots
        finally:
            self._autopilots.close()
