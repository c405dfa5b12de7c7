"""The simulator half of ``bench/sim_vs_real.py``: the comparison script flies the simulator through the
gateway with the steps it flies real ArduCopter with, and the simulator stays within the script's
tolerance of the real figures it recorded (``bench/sim_vs_real.json``). Figures are simulated seconds
from the vehicle's own clock; what a busy machine still moves is the gateway's own round trips, which
take wall time and so cost the speed-up times more simulated time: the busier the machine, the slower the
simulator runs here (the suite's load scale), so that they cost what they cost on an idle one. Under
load (a scale of 1.5-2 at the end of a full run) one took 10.2 simulated s at 10x against real
ArduCopter's 8.8-8.9 s."""

from __future__ import annotations

import json
import sys
from pathlib import Path

BENCH = Path(__file__).resolve().parents[2] / "bench"
sys.path.insert(0, str(BENCH))

import sim_vs_real  # noqa: E402

from tests.helpers.timing import scaled  # noqa: E402

SPEEDUP = 10.0  # on an idle machine the gateway's round trips cost ~0.2 simulated s each: within tolerance


async def test_the_simulator_flies_the_comparison_within_tolerance_of_real_arducopter() -> None:
    speedup = SPEEDUP / scaled(1.0)  # a busy machine: slower simulated time, the same per round trip
    sim = await sim_vs_real.measure(False, speedup, flights=1, readiness_runs=1, progress=lambda _m: None)
    assert set(sim.flights) == set(sim_vs_real.STEPS), sim.flights
    assert set(sim.ready) == set(sim_vs_real.MILESTONES), sim.ready

    recorded = json.loads(sim_vs_real.FIGURES.read_text())
    real = sim_vs_real.Side(recorded["flights"], recorded["ready"])
    assert set(real.flights) == set(sim_vs_real.STEPS) and set(real.ready) == set(sim_vs_real.MILESTONES)
    assert sim_vs_real.differences(sim, real) == [], (
        f"the simulator left the tolerance of real ArduCopter (recorded {recorded['date']}); fix gateway/sim "
        "or, if the real autopilot changed, measure again with bench/sim_vs_real.py --write"
    )
