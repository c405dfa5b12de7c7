// Small display helpers: numbers with units, times, and the state class that colours a drone.

export function num(value, digits = 1, unit = "") {
  if (value === null || value === undefined || Number.isNaN(value)) return "–";
  const text = (Math.abs(value) < 0.5 * 10 ** -digits ? 0 : value).toFixed(digits);
  return unit ? `${text} ${unit}` : text;
}

export function clock(value) {
  if (value === null || value === undefined) return "–";
  const date = typeof value === "number" ? new Date(value * 1000) : new Date(value);
  return date.toLocaleTimeString([], { hour12: false });
}

export function dateTime(value) {
  if (!value) return "–";
  const date = new Date(value);
  return `${date.toLocaleDateString()} ${date.toLocaleTimeString([], { hour12: false })}`;
}

export function duration(seconds) {
  if (seconds === null || seconds === undefined) return "–";
  const s = Math.round(seconds);
  const m = Math.floor(s / 60);
  return m ? `${m} min ${s % 60} s` : `${s} s`;
}

const RETURNING_MODES = new Set(["RETURN_TO_LAUNCH", "RTL", "LAND", "SMART_RTL"]);

// One word for a drone's situation; the CSS gives each its colour (see console.css, .st-*).
export function stateClass(drone) {
  if (["registered", "connecting", "failed"].includes(drone.state) || !drone.position) {
    return drone.state === "failed" ? "failed" : "offline";
  }
  if (drone.state === "link_lost" || drone.position.stale) return "stale";
  if (drone.in_air) return RETURNING_MODES.has(drone.flight_mode) ? "returning" : "air";
  if (drone.armed) return "armed";
  return drone.state === "ready" ? "ground" : "connected";
}

export const STATE_LABELS = {
  offline: "not connected",
  failed: "failed",
  stale: "link lost",
  connected: "connected, not ready",
  ground: "ready, on the ground",
  armed: "armed on the ground",
  air: "flying",
  returning: "landing / returning",
};

export function situation(drone) {
  const cls = stateClass(drone);
  if (cls === "offline") return drone.initialising ? `waiting: ${drone.initialising}` : drone.state;
  return STATE_LABELS[cls];
}
