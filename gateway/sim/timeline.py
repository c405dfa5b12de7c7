"""The boot milestones of a simulated ArduCopter (below the vehicle and its boot sequence)."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Timeline:
    """Boot milestones of ArduCopter SITL (simulated seconds since boot). Measured with
    ``bench/readiness.py --real`` on ArduCopter 4.7-dev SITL (see docs/simulator.md): the same at
    speed-up 1 and 5 within 0.2 s except ``accels_ok`` and ``prearm_ok``, about 0.6 s later at 5."""

    boot_done: float = 1.8
    baro: float = 1.93
    ready: float = 2.45
    mag_ok: float = 2.6  # compass and battery monitor healthy
    rc7: float = 2.75
    ekf_init: float = 4.46
    tilt: float = 5.8  # from here the EKF has attitude and an altitude estimate
    yaw_align: float = 5.9
    gps_detect: float = 9.8
    gps_fix: float = 10.1  # 3D fix (GPS_RAW_INT fix_type >= 3; MAVSDK: global/local position ok)
    accels_ok: float = 12.6  # "Accels inconsistent" until here, then "Gyros inconsistent"
    origin: float = 20.0
    origin2: float = 20.2
    prearm_ok: float = 22.8  # gyros consistent: armable in STABILIZE
    ekf_gps: float = 41.6  # "EKF3 IMU0 is using GPS": armable in GUIDED, LOITER, AUTO...
