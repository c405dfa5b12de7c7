"""Battery: drain while armed, a simple LiPo voltage curve, and ArduPilot's low-battery detection."""

from __future__ import annotations

from dataclasses import dataclass

from pymavlink.dialects.v20 import ardupilotmega as mav

HOVER_CURRENT_A = 27.8  # measured on ArduCopter SITL (+ frame) in hover
IDLE_ARMED_CURRENT_A = 3.0


@dataclass
class Battery:
    capacity_mah: float = 3300.0
    full_voltage: float = 12.6
    cells: int = 3
    consumed_mah: float = 0.0
    consumed_wh: float = 0.0
    current: float = 0.0
    failsafe: str | None = None  # None, "low" or "critical"
    # SITL's default battery (SIM_BATT_CAP_AH 0) keeps its full voltage whatever is consumed; the voltage
    # follows the charge once SIM_BATT_CAP_AH is set or a battery level has been injected.
    follow_charge: bool = False
    _low_since: float | None = None

    @property
    def remaining_pct(self) -> float:
        return max(0.0, min(100.0, 100.0 * (1.0 - self.consumed_mah / self.capacity_mah)))

    @property
    def voltage(self) -> float:
        """Resting voltage from state of charge: 4.2 V/cell full, 3.3 V/cell empty (linear)."""
        if not self.follow_charge:
            return self.full_voltage
        soc = self.remaining_pct / 100.0
        per_cell = 3.3 + 0.9 * soc
        return min(self.full_voltage, per_cell * self.cells)

    def set_remaining(self, pct: float) -> None:
        self.follow_charge = True
        self.consumed_mah = self.capacity_mah * (1.0 - max(0.0, min(100.0, pct)) / 100.0)

    def drain(self, dt: float, armed: bool, flying: bool) -> None:
        self.current = HOVER_CURRENT_A if flying else (IDLE_ARMED_CURRENT_A if armed else 0.0)
        mah = self.current * dt / 3.6
        self.consumed_mah = min(self.capacity_mah, self.consumed_mah + mah)
        self.consumed_wh += self.current * self.voltage * dt / 3600.0

    def charge_state(self) -> int:
        if self.failsafe == "critical":
            return mav.MAV_BATTERY_CHARGE_STATE_CRITICAL
        if self.failsafe == "low":
            return mav.MAV_BATTERY_CHARGE_STATE_LOW
        return mav.MAV_BATTERY_CHARGE_STATE_OK

    def check(self, now: float, low_volt: float, low_mah: float, crit_volt: float, crit_mah: float,
              timer_s: float) -> str | None:  # fmt: skip
        """Returns "low"/"critical" when a new failsafe level is reached (ArduPilot AP_BattMonitor logic).

        Voltage must stay below its threshold for BATT_LOW_TIMER seconds; capacity triggers at once.
        """
        remaining_mah = self.capacity_mah - self.consumed_mah
        crit = (crit_volt > 0 and self.voltage < crit_volt) or (crit_mah > 0 and remaining_mah < crit_mah)
        low = (low_volt > 0 and self.voltage < low_volt) or (low_mah > 0 and remaining_mah < low_mah)
        volt_low = (low_volt > 0 and self.voltage < low_volt) or (crit_volt > 0 and self.voltage < crit_volt)
        if volt_low:
            if self._low_since is None:
                self._low_since = now
        else:
            self._low_since = None
        timer_done = self._low_since is not None and now - self._low_since >= timer_s
        mah_low = (low_mah > 0 and remaining_mah < low_mah) or (crit_mah > 0 and remaining_mah < crit_mah)
        if not (timer_done or mah_low):
            return None
        level = "critical" if crit else ("low" if low else None)
        if level is None or level == self.failsafe or (self.failsafe == "critical"):
            return None
        self.failsafe = level
        return level
