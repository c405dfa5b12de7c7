// The operator console: who you are, the live stream, and the page's layout and actions.
//
// Every action is a call to the gateway's REST API (the same routes, checks and audit as curl):
// the page never talks to a drone by itself.

import { h, render } from "./vendor/preact/preact.mjs";
import { useCallback, useEffect, useRef, useState } from "./vendor/preact/hooks.mjs";
import htm from "./vendor/htm/htm.module.js";
import { api, ApiError, getToken, setToken, streamEvents } from "./api.js";
import { FleetMap } from "./map.js";
import { AuditPanel, ConfirmDialog, DroneDetail, FleetTable, FlightsPanel, LoginForm, ReplayPanel } from "./panels.js";

const CALLS_BEFORE_ARMING_MS = 60000;

const html = htm.bind(h);

const AUDIT_KEEP = 500;
const STALE_STREAM_S = 3;
const FRESH_MS = 4000;

function useAudit() {
  const [rows, setRows] = useState([]);
  const [freshIds, setFresh] = useState(new Set());
  const add = useCallback((items, backlog) => {
    setRows((old) => {
      const byId = new Map(old.map((r) => [r.id, r]));
      for (const item of items) byId.set(item.id, item);
      return [...byId.values()].sort((a, b) => b.id - a.id).slice(0, AUDIT_KEEP);
    });
    if (!backlog && items.length) {
      const ids = items.map((i) => i.id);
      setFresh((old) => new Set([...old, ...ids]));
      setTimeout(() => setFresh((old) => new Set([...old].filter((id) => !ids.includes(id)))), FRESH_MS);
    }
  }, []);
  return { rows, freshIds, add, reset: () => setRows([]) };
}

function Console({ config, onLogout }) {
  const [fleet, setFleet] = useState(null);
  const [origin, setOrigin] = useState(null);
  const [geofences, setGeofences] = useState(null);
  const [stream, setStream] = useState({ state: "connecting" });
  const [lastFleetAt, setLastFleetAt] = useState(0);
  const [now, setNow] = useState(Date.now());
  const [selectedId, setSelected] = useState(null);
  const [tab, setTab] = useState("fleet");
  const [request, setRequest] = useState(null);
  const [busy, setBusy] = useState(false);
  const [notices, setNotices] = useState([]);
  const [flights, setFlights] = useState([]);
  const [flightsLoading, setFlightsLoading] = useState(false);
  const [replay, setReplay] = useState(null);
  const [mapView, setMapView] = useState(null);
  const audit = useAudit();
  const flightIds = useRef("");
  const canAct = config.role === "operator";

  const notify = useCallback((kind, text) => {
    const id = Math.random();
    setNotices((old) => [...old.slice(-4), { id, kind, text }]);
    setTimeout(() => setNotices((old) => old.filter((n) => n.id !== id)), kind === "error" ? 12000 : 6000);
  }, []);

  useEffect(() => {
    const abort = new AbortController();
    streamEvents({
      signal: abort.signal,
      onState: (state, detail) => {
        setStream({ state, detail });
        if (state === "unauthorized") onLogout("The gateway no longer accepts this token.");
      },
      onEvent: (name, data) => {
        if (name === "fleet") {
          setFleet(data);
          setLastFleetAt(Date.now());
          if (data.origin) setOrigin((o) => o || data.origin);
        } else if (name === "audit") {
          audit.add(data.items, data.backlog);
        } else if (name === "geofences") {
          setGeofences(data);
        }
      },
    });
    const tick = setInterval(() => setNow(Date.now()), 1000);
    return () => {
      abort.abort();
      clearInterval(tick);
    };
  }, []);

  const loadFlights = useCallback(async () => {
    setFlightsLoading(true);
    try {
      setFlights((await api("/flights?limit=100")).items);
    } catch (error) {
      notify("error", `Flights: ${error.message}`);
    } finally {
      setFlightsLoading(false);
    }
  }, []);

  // a flight started or ended somewhere: the list changes
  const currentFlights = fleet ? fleet.vehicles.map((d) => d.flight_id ?? "").join(",") : "";
  useEffect(() => {
    if (tab === "flights" && currentFlights !== flightIds.current) loadFlights();
    flightIds.current = currentFlights;
  }, [currentFlights, tab]);

  const openReplay = useCallback(async (flight) => {
    try {
      const until = flight.ended_at || new Date().toISOString();
      // a call is audited when it is sent, so the takeoff or mission start that began the flight comes
      // before its arming (up to the gateway's 60 s wait for a drone to become armable)
      const since = new Date(Date.parse(flight.started_at) - CALLS_BEFORE_ARMING_MS).toISOString();
      const query = new URLSearchParams({ vehicle_id: flight.vehicle_id, since, until, include_fleet: "true", limit: "1000" });
      const [feature, texts, rows] = await Promise.all([
        api(`/flights/${flight.id}/track.geojson`),
        api(`/flights/${flight.id}/statustexts`),
        api(`/audit?${query}`),
      ]);
      setReplay({ flight, feature, texts: texts.items, audit: rows.items, index: 0 });
    } catch (error) {
      notify("error", `Replay of flight ${flight.id}: ${error.message}`);
    }
  }, []);

  const perform = async (choice) => {
    const r = request;
    const calls = {
      "drone-action": () => api(`/vehicles/${r.drone}/${r.action}`, { method: "POST" }),
      "lock-drone": () => api(`/vehicles/${r.drone}/lock`, { method: "POST", body: { reason: choice.reason } }),
      "unlock-drone": () => api(`/vehicles/${r.drone}/lock`, { method: "DELETE" }),
      "release-drone": () => api(`/vehicles/${r.drone}/takeover`, { method: "DELETE" }),
      "lock-fleet": () => api("/fleet/lock", { method: "POST", body: { reason: choice.reason } }),
      "unlock-fleet": () => api("/fleet/lock", { method: "DELETE" }),
      stop: () => api("/fleet/stop", { method: "POST", body: { action: choice.action, lock: choice.lock } }),
    };
    setBusy(true);
    try {
      const result = await calls[r.kind]();
      if (r.kind === "stop") {
        const sent = result.results.filter((x) => x.outcome === "sent").map((x) => x.vehicle_id);
        const others = (outcome) =>
          result.results
            .filter((x) => x.outcome === outcome)
            .map((x) => `${x.vehicle_id} (${x.message})`)
            .join(", ");
        const failed = others("failed");
        const unreached = others("unreached");
        const skipped = others("skipped");
        const unstored = result.fleet_lock && result.fleet_lock.stored === false;
        notify(
          failed || unreached ? "error" : "ok",
          `Emergency stop (${result.action}): sent to ${sent.join(", ") || "no drone in the air"}` +
            (skipped ? `; skipped ${skipped}` : "") +
            (unreached ? `; NOT REACHED (nothing sent): ${unreached}` : "") +
            (failed ? `; FAILED on ${failed}` : "") +
            (unstored ? "; the fleet lock holds but is stored only when the database is back" : ""),
        );
      } else if (r.kind === "drone-action") {
        notify("ok", `${r.label} sent to ${r.drone}`);
      } else {
        notify("ok", `${r.kind.replace("-", " ")} done`);
      }
      setRequest(null);
    } catch (error) {
      notify("error", error instanceof ApiError ? `${error.code}: ${error.message}` : String(error));
      if (error.status === 401) onLogout("The gateway no longer accepts this token.");
    } finally {
      setBusy(false);
    }
  };

  const vehicles = fleet ? fleet.vehicles : [];
  const selected = vehicles.find((d) => d.id === selectedId) || null;
  const age = lastFleetAt ? (now - lastFleetAt) / 1000 : null;
  const live = stream.state === "live" && age !== null && age < STALE_STREAM_S;
  const fleetLock = fleet && fleet.fleet_lock;
  const ask = (req) => setRequest(req);

  return html`<div class="console">
    <header class="topbar">
      <h1>fleet-gateway</h1>
      <span class=${"link " + (live ? "live" : "down")} title=${stream.detail || ""} data-stream=${stream.state}>
        ${live ? "● live" : stream.state === "live" ? `● no data for ${Math.round(age)} s` : `● ${stream.state}${stream.detail ? ": " + stream.detail : ""}`}
      </span>
      ${fleetLock
        ? html`<span class="fleet-lock" data-locked="true">⚿ Fleet locked by ${fleetLock.by}: ${fleetLock.reason}</span>`
        : html`<span class="fleet-lock unlocked" data-locked="false">Fleet unlocked</span>`}
      <span class="spacer"></span>
      ${fleetLock
        ? html`<button type="button" class="unlock-fleet" disabled=${!canAct} onClick=${() => ask({ kind: "unlock-fleet" })}>Unlock fleet</button>`
        : html`<button type="button" class="lock-fleet" disabled=${!canAct} onClick=${() => ask({ kind: "lock-fleet" })}>Lock fleet</button>`}
      <button type="button" class="estop" disabled=${!canAct} title=${canAct ? "Emergency stop: lock the fleet, then hold, land or return every airborne drone" : "needs an operator token"}
        onClick=${() => ask({ kind: "stop" })}>EMERGENCY STOP</button>
      <span class="who" title=${"role: " + config.role}>${config.principal} · ${config.role}</span>
      ${getToken() && html`<button type="button" class="small logout" onClick=${() => onLogout(null)}>Log out</button>`}
    </header>
    <div class="body">
      <div class="left">
        <${FleetMap} origin=${origin} config=${config} vehicles=${vehicles} selectedId=${selectedId} onSelect=${setSelected} geofences=${geofences}
          replay=${replay} onReady=${setMapView} />
        <div class="legend">
          ${["ground", "armed", "air", "returning", "stale", "offline", "failed"].map((s) => html`<span><span class=${"dot st-" + s}></span>${{ ground: "on the ground", armed: "armed", air: "flying", returning: "landing / RTL", stale: "link lost", offline: "not connected", failed: "failed" }[s]}</span>`)}
          <span><span class="swatch track"></span>current flight</span>
          <span><span class="swatch replay"></span>replay</span>
        </div>
        <${AuditPanel} rows=${audit.rows} freshIds=${audit.freshIds} />
      </div>
      <div class="right">
        <nav class="tabs">
          <button type="button" class=${tab === "fleet" ? "active" : ""} onClick=${() => setTab("fleet")} data-tab="fleet">Fleet</button>
          <button type="button" class=${tab === "flights" ? "active" : ""} onClick=${() => { setTab("flights"); loadFlights(); }} data-tab="flights">Flights</button>
        </nav>
        ${tab === "fleet"
          ? html`<${FleetTable} vehicles=${vehicles} selectedId=${selectedId} onSelect=${setSelected} />
              <${DroneDetail} drone=${selected} map=${mapView} canAct=${canAct} ask=${ask} />`
          : html`${replay
                ? html`<${ReplayPanel} replay=${replay} setIndex=${(f) => setReplay((r) => r && { ...r, index: typeof f === "function" ? f(r.index) : f })} onClose=${() => setReplay(null)} />`
                : ""}
              <${FlightsPanel} flights=${flights} loading=${flightsLoading} onRefresh=${loadFlights} onReplay=${openReplay} />`}
      </div>
    </div>
    ${request && html`<${ConfirmDialog} request=${request} busy=${busy} onConfirm=${perform} onCancel=${() => setRequest(null)} />`}
    <div class="notices">${notices.map((n) => html`<div key=${n.id} class=${"notice " + n.kind}>${n.text}</div>`)}</div>
  </div>`;
}

function App() {
  const [config, setConfig] = useState(null);
  const [login, setLogin] = useState(null); // null: not asked; {message}: the login form

  const check = useCallback(async () => {
    try {
      setConfig(await api("/console"));
      setLogin(null);
    } catch (error) {
      if (error.status === 401) {
        const hadToken = Boolean(getToken());
        setToken(null);
        const message = hadToken ? "That token was not accepted: use an operator or viewer token." : null;
        setLogin((old) => ({ message, attempt: (old?.attempt ?? 0) + 1 }));
      } else {
        setLogin({ message: `The gateway did not answer: ${error.message}. Reload to try again.` });
      }
    }
  }, []);

  useEffect(() => {
    check();
  }, []);

  if (config) {
    return html`<${Console} config=${config} onLogout=${(message) => {
      setToken(null);
      setConfig(null);
      setLogin({ message });
    }} />`;
  }
  if (login) {
    return html`<${LoginForm} key=${login.attempt} message=${login.message} onLogin=${(token) => {
      setToken(token);
      check();
    }} />`;
  }
  return html`<main class="login"><p>Connecting to the gateway…</p></main>`;
}

render(html`<${App} />`, document.getElementById("app"));
