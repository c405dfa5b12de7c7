// The console's panels: fleet table, drone detail, audit stream, flights and replay, dialogs.

import { h } from "./vendor/preact/preact.mjs";
import { useEffect, useMemo, useRef, useState } from "./vendor/preact/hooks.mjs";
import htm from "./vendor/htm/htm.module.js";
import { clock, dateTime, duration, num, situation, stateClass } from "./format.js";

const html = htm.bind(h);

const READ_ONLY = "a viewer token can only watch; actions need an operator token";

// --- fleet table -------------------------------------------------------------------------------------

const COLUMNS = [
  { key: "id", label: "Drone", value: (d) => d.id },
  { key: "state", label: "State", value: (d) => stateClass(d) },
  { key: "mode", label: "Mode", value: (d) => d.flight_mode ?? "" },
  { key: "alt", label: "Alt m", value: (d) => d.position?.alt_rel_m ?? -Infinity },
  { key: "battery", label: "Batt %", value: (d) => d.battery_pct ?? -Infinity },
  { key: "speed", label: "m/s", value: (d) => d.ground_speed_mps ?? -Infinity },
  { key: "operation", label: "Operation", value: (d) => d.operation?.kind ?? "" },
];

export function FleetTable({ vehicles, selectedId, onSelect }) {
  const [sort, setSort] = useState({ key: "id", dir: 1 });
  const [tag, setTag] = useState("");
  const tags = useMemo(() => [...new Set(vehicles.flatMap((d) => d.tags))].sort(), [vehicles]);
  const column = COLUMNS.find((c) => c.key === sort.key);
  const rows = vehicles
    .filter((d) => !tag || d.tags.includes(tag))
    .sort((a, b) => {
      const x = column.value(a);
      const y = column.value(b);
      return (x < y ? -1 : x > y ? 1 : a.id < b.id ? -1 : 1) * sort.dir;
    });
  const header = (c) => html`<th
    class=${"sortable" + (sort.key === c.key ? (sort.dir > 0 ? " asc" : " desc") : "")}
    onClick=${() => setSort(sort.key === c.key ? { key: c.key, dir: -sort.dir } : { key: c.key, dir: 1 })}
    data-sort=${c.key}
  >${c.label}</th>`;
  return html`<section class="panel fleet-table">
    <div class="panel-head">
      <h2>Fleet <span class="count">${rows.length}/${vehicles.length}</span></h2>
      <label class="filter">Tag
        <select value=${tag} onChange=${(e) => setTag(e.target.value)} name="tag-filter">
          <option value="">all</option>
          ${tags.map((t) => html`<option value=${t}>${t}</option>`)}
        </select>
      </label>
    </div>
    <div class="scroll">
      <table>
        <thead><tr>${COLUMNS.map(header)}</tr></thead>
        <tbody>
          ${rows.map(
            (d) => html`<tr
              key=${d.id}
              data-drone=${d.id}
              class=${(d.id === selectedId ? "selected " : "") + "row-" + stateClass(d)}
              onClick=${() => onSelect(d.id)}
            >
              <td><span class=${"dot st-" + stateClass(d)}></span>${d.id}${d.locked ? html` <span class="lockmark" title=${d.locked}>⚿</span>` : ""}
                ${d.tags.length ? html`<div class="tags">${d.tags.map((t) => html`<span class="tag">${t}</span>`)}</div>` : ""}</td>
              <td>${situation(d)}</td>
              <td>${d.flight_mode ?? "–"}</td>
              <td class="num">${num(d.position?.alt_rel_m, 1)}</td>
              <td class="num">${num(d.battery_pct, 0)}</td>
              <td class="num">${num(d.ground_speed_mps, 1)}</td>
              <td>${d.operation ? html`<${OperationBar} op=${d.operation} compact />` : "–"}</td>
            </tr>`,
          )}
        </tbody>
      </table>
    </div>
  </section>`;
}

function OperationBar({ op, compact }) {
  const pct = Math.round((op.progress ?? 0) * 100);
  return html`<div class=${"operation op-" + op.status + (compact ? " compact" : "")} title=${op.message}>
    <span class="op-kind">${op.kind}</span>
    <span class="bar"><span style=${`width:${pct}%`}></span></span>
    <span class="op-status">${op.status === "running" ? `${pct}%` : op.status}</span>
  </div>`;
}

// --- drone detail ------------------------------------------------------------------------------------

export function DroneDetail({ drone, map, canAct, ask }) {
  if (!drone) return html`<section class="panel detail empty">Click a drone on the map or in the table.</section>`;
  const local = drone.position && drone.home && map ? map.offset(drone.position, drone.home) : null;
  const op = drone.operation;
  const rows = [
    ["State", situation(drone) + (drone.last_error ? ` (${drone.last_error})` : "")],
    ["Autopilot", `${drone.autopilot ?? "–"}${drone.is_simulator ? " (simulator)" : ""}`],
    ["Position", drone.position ? `${drone.position.lat.toFixed(7)}, ${drone.position.lon.toFixed(7)}` : "–"],
    ["From its home", local ? `E ${num(local.east, 1)} m, N ${num(local.north, 1)} m (${num(Math.hypot(local.east, local.north), 1)} m)` : "–"],
    ["Altitude", drone.position ? `${num(drone.position.alt_rel_m, 1)} m above home (${num(drone.position.alt_amsl_m, 1)} m AMSL)` : "–"],
    ["Heading", num(drone.heading_deg, 0, "°")],
    ["Speed", `${num(drone.ground_speed_mps, 1)} m/s, climb ${num(drone.climb_mps, 1)} m/s`],
    ["Battery", `${num(drone.battery_pct, 0, "%")} · ${num(drone.battery_v, 2, "V")}${drone.battery_stale ? " (stale)" : ""}`],
    ["Mode", `${drone.flight_mode ?? "–"} · ${drone.armed ? "armed" : "disarmed"} · ${drone.in_air ? "in the air" : drone.landed_state ?? "–"}`],
    ["GPS", drone.gps ? `${drone.gps.fix}, ${drone.gps.satellites} satellites` : "–"],
    ["Mission", drone.mission ? `item ${drone.mission.current} of ${drone.mission.total}${drone.mission.finished ? " (finished)" : ""}` : "–"],
    ["Flight", drone.flight_id ? `#${drone.flight_id} (recording)` : "on the ground"],
    ["Data age", drone.position ? `${num(drone.position.age_s, 1)} s${drone.position.stale ? " (stale: link lost?)" : ""}` : "–"],
  ];
  const act = (action, label) =>
    html`<button type="button" class=${"act act-" + action} disabled=${!canAct} title=${canAct ? "" : READ_ONLY}
      onClick=${() => ask({ kind: "drone-action", drone: drone.id, action, label })}>${label}</button>`;
  return html`<section class="panel detail" data-drone=${drone.id}>
    <div class="panel-head">
      <h2><span class=${"dot st-" + stateClass(drone)}></span>${drone.id}${drone.name ? html` <small>${drone.name}</small>` : ""}</h2>
      ${drone.tags.map((t) => html`<span class="tag">${t}</span>`)}
    </div>
    ${drone.locked && html`<div class="lock-note">⚿ ${drone.locked}</div>`}
    <div class="actions">
      ${act("hold", "Hold")} ${act("land", "Land")} ${act("rtl", "Return home")}
      ${drone.taken_over && html`<button type="button" class="act act-release" disabled=${!canAct} title=${canAct ? "" : READ_ONLY}
            onClick=${() => ask({ kind: "release-drone", drone: drone.id })}>Release to agents</button>`}
      ${drone.own_lock
        ? html`<button type="button" class="act act-unlock" disabled=${!canAct} title=${canAct ? "" : READ_ONLY}
            onClick=${() => ask({ kind: "unlock-drone", drone: drone.id })}>Unlock drone</button>`
        : html`<button type="button" class="act act-lock" disabled=${!canAct} title=${canAct ? "" : READ_ONLY}
            onClick=${() => ask({ kind: "lock-drone", drone: drone.id })}>Lock drone</button>`}
    </div>
    ${op && html`<div class="op-detail"><${OperationBar} op=${op} />
      <div class="op-message">${op.message}${op.eta_s != null && op.status === "running" ? ` · ETA ${duration(op.eta_s)}` : ""}</div></div>`}
    <dl class="facts">${rows.map(([k, v]) => html`<dt>${k}</dt><dd>${v}</dd>`)}</dl>
    <h3>Last status texts</h3>
    <ul class="status-texts">
      ${drone.status_texts.length
        ? [...drone.status_texts].reverse().map(
            (s) => html`<li class=${"sev-" + s.severity}><time>${clock(s.t)}</time> <span class="sev">${s.severity}</span> ${s.text}</li>`,
          )
        : html`<li class="none">none yet</li>`}
    </ul>
  </section>`;
}

// --- audit -------------------------------------------------------------------------------------------

function AuditRow({ row, fresh }) {
  const [open, setOpen] = useState(false);
  return html`<tr class=${`audit-row outcome-${row.outcome}${fresh ? " fresh" : ""}`} data-audit-id=${row.id} onClick=${() => setOpen(!open)}>
      <td><time title=${row.t}>${clock(row.t)}</time></td>
      <td>${row.source}</td>
      <td class="who" title=${row.session_key || ""}>${row.principal || "–"}</td>
      <td>${row.vehicle_id || (row.arguments?.drone_ids ? "fleet" : "–")}</td>
      <td class="action">${row.action}</td>
      <td><span class=${"outcome " + row.outcome}>${row.outcome}</span></td>
      <td class="reason">${row.error || ""}</td>
      <td class="num">${row.duration_ms != null ? Math.round(row.duration_ms) + " ms" : ""}</td>
    </tr>
    ${open && html`<tr class="audit-args"><td colspan="8"><pre>${JSON.stringify(row.arguments, null, 1)}</pre></td></tr>`}`;
}

export function AuditTable({ rows, freshIds = new Set(), empty = "No calls yet." }) {
  return html`<table class="audit">
    <thead><tr><th>Time</th><th>Via</th><th>Who</th><th>Drone</th><th>Call</th><th>Outcome</th><th>Reason</th><th>Took</th></tr></thead>
    <tbody>
      ${rows.length ? rows.map((row) => html`<${AuditRow} key=${row.id} row=${row} fresh=${freshIds.has(row.id)} />`) : html`<tr><td colspan="8" class="none">${empty}</td></tr>`}
    </tbody>
  </table>`;
}

export function AuditPanel({ rows, freshIds }) {
  const [only, setOnly] = useState("all");
  const shown = rows.filter((r) => only === "all" || (only === "problems" ? r.outcome === "refused" || r.outcome === "error" : r.source === only));
  return html`<section class="panel audit-panel">
    <div class="panel-head">
      <h2>Audit <span class="count">live</span></h2>
      <label class="filter">Show
        <select value=${only} onChange=${(e) => setOnly(e.target.value)} name="audit-filter">
          <option value="all">every call</option>
          <option value="problems">refused and failed</option>
          <option value="mcp">agents (MCP)</option>
          <option value="rest">operators (REST)</option>
          <option value="console">operators (console)</option>
        </select>
      </label>
    </div>
    <div class="scroll"><${AuditTable} rows=${shown} freshIds=${freshIds} /></div>
  </section>`;
}

// --- flights and replay ------------------------------------------------------------------------------

export function FlightsPanel({ flights, onReplay, onRefresh, loading }) {
  return html`<section class="panel flights">
    <div class="panel-head">
      <h2>Flights</h2>
      <button type="button" class="small" onClick=${onRefresh} disabled=${loading}>Refresh</button>
    </div>
    <div class="scroll">
      <table>
        <thead><tr><th>#</th><th>Drone</th><th>Started</th><th>Took</th><th>Distance</th><th>Max alt</th><th>Battery</th><th></th></tr></thead>
        <tbody>
          ${flights.length
            ? flights.map(
                (f) => html`<tr key=${f.id} data-flight=${f.id}>
                  <td>${f.id}</td><td>${f.vehicle_id}</td><td>${dateTime(f.started_at)}</td>
                  <td>${f.ended_at ? duration(f.duration_s) : html`<em>flying</em>`}</td>
                  <td class="num">${num(f.distance_m, 0, "m")}</td><td class="num">${num(f.max_alt_rel_m, 1, "m")}</td>
                  <td class="num">${num(f.battery_used_pct, 0, "%")}</td>
                  <td><button type="button" class="small replay-button" onClick=${() => onReplay(f)}>Replay</button></td>
                </tr>`,
              )
            : html`<tr><td colspan="8" class="none">${loading ? "Loading…" : "No flights recorded yet."}</td></tr>`}
        </tbody>
      </table>
    </div>
  </section>`;
}

// Index of the last track sample at or before time t (ms); the samples' times are sorted.
export function sampleAt(times, t) {
  let lo = 0;
  let hi = times.length - 1;
  if (hi < 0 || t <= times[0]) return 0;
  while (lo < hi) {
    const mid = (lo + hi + 1) >> 1;
    if (times[mid] <= t) lo = mid;
    else hi = mid - 1;
  }
  return lo;
}

export function ReplayPanel({ replay, setIndex, onClose }) {
  const [playing, setPlaying] = useState(false);
  const [speed, setSpeed] = useState(4);
  const timer = useRef(null);
  const props = replay.feature?.properties;
  const times = useMemo(() => (props ? props.times.map((t) => Date.parse(t)) : []), [replay.feature]);
  const count = times.length;
  useEffect(() => {
    if (!playing) return undefined;
    timer.current = setInterval(() => {
      setIndex((i) => {
        if (i >= count - 1) {
          setPlaying(false);
          return i;
        }
        return i + 1;
      });
    }, 1000 / speed);
    return () => clearInterval(timer.current);
  }, [playing, speed, count]);
  const i = Math.min(replay.index, Math.max(0, count - 1));
  const now = times[i];
  const timeline = [
    ...replay.texts.map((s) => ({ t: Date.parse(s.t), kind: "text", key: "s" + s.id, item: s })),
    ...replay.audit.map((a) => ({ t: Date.parse(a.t), kind: "audit", key: "a" + a.id, item: a })),
  ].sort((a, b) => a.t - b.t);
  const f = replay.flight;
  return html`<section class="panel replay">
    <div class="panel-head">
      <h2>Replay of flight #${f.id} <small>${f.vehicle_id}, ${dateTime(f.started_at)}</small></h2>
      <button type="button" class="small" onClick=${onClose}>Close replay</button>
    </div>
    ${count === 0
      ? html`<p class="none">This flight has no recorded track.</p>`
      : html`<div class="replay-controls">
          <button type="button" class="small play" onClick=${() => {
            if (i >= count - 1) setIndex(0);
            setPlaying(!playing);
          }}>${playing ? "Pause" : "Play"}</button>
          <input type="range" min="0" max=${count - 1} value=${i} onInput=${(e) => setIndex(Number(e.target.value))} name="replay-position" />
          <select value=${speed} onChange=${(e) => setSpeed(Number(e.target.value))} name="replay-speed">
            ${[1, 2, 4, 8, 16].map((s) => html`<option value=${s}>${s}×</option>`)}
          </select>
          <span class="replay-time">${clock(props.times[i])} · ${num(props.alt_rel_m[i], 1, "m")} · ${num(props.battery_pct[i], 0, "%")}</span>
        </div>`}
    <div class="scroll">
      <ul class="timeline">
        ${timeline.length
          ? timeline.map(
              (e) => html`<li key=${e.key} class=${(e.t <= now ? "past " : "") + (e.kind === "audit" ? "outcome-" + e.item.outcome : "sev-" + e.item.severity.toLowerCase())}
                onClick=${() => setIndex(sampleAt(times, e.t))}>
                <time>${clock(e.item.t)}</time>
                ${e.kind === "audit"
                  ? html`<span class="kind">call</span> <b>${e.item.action}</b> by ${e.item.principal || "–"} <span class=${"outcome " + e.item.outcome}>${e.item.outcome}</span>${e.item.error ? html` <span class="reason">${e.item.error}</span>` : ""}`
                  : html`<span class="kind">${e.item.severity.toLowerCase()}</span> ${e.item.text}`}
              </li>`,
            )
          : html`<li class="none">No status texts or calls during this flight.</li>`}
      </ul>
    </div>
  </section>`;
}

// --- dialogs -----------------------------------------------------------------------------------------

const STOP_ACTIONS = [
  ["hold", "Hold where they are"],
  ["land", "Land where they are"],
  ["rtl", "Return to launch"],
];

function describe(request) {
  switch (request.kind) {
    case "drone-action":
      return { title: `${request.label}: ${request.drone}`, text: `Send "${request.action}" to ${request.drone} now? It replaces what the drone is doing.`, confirm: request.label };
    case "lock-drone":
      return { title: `Lock ${request.drone}`, text: `Agents' commands to ${request.drone} will be refused with your reason until an operator unlocks it.`, confirm: "Lock drone", reason: true };
    case "unlock-drone":
      return { title: `Unlock ${request.drone}`, text: `Agents may command ${request.drone} again (a fleet lock still applies).`, confirm: "Unlock drone" };
    case "release-drone":
      return { title: `Release ${request.drone}`, text: `A pilot or ground station took ${request.drone}. Release it only when they are done with it: agents may command it again (other locks stay).`, confirm: "Release drone" };
    case "lock-fleet":
      return { title: "Lock the fleet", text: "Agents' commands to every drone will be refused with your reason until an operator unlocks the fleet.", confirm: "Lock fleet", reason: true };
    case "unlock-fleet":
      return { title: "Unlock the fleet", text: "Agents may command the drones again (drone locks stay).", confirm: "Unlock fleet" };
    case "stop":
      return { title: "Emergency stop", text: "Every airborne drone is told at once:", confirm: "STOP THE FLEET", stop: true };
    default:
      return { title: request.kind, text: "", confirm: "OK" };
  }
}

export function ConfirmDialog({ request, onConfirm, onCancel, busy }) {
  const dialog = useRef(null);
  const [reason, setReason] = useState("");
  const [action, setAction] = useState("hold"); // the REST default
  const [lock, setLock] = useState(true);
  const d = describe(request);
  useEffect(() => {
    const el = dialog.current;
    if (el && !el.open) el.showModal();
    const cancel = (e) => {
      e.preventDefault();
      onCancel();
    };
    el.addEventListener("cancel", cancel);
    return () => el.removeEventListener("cancel", cancel);
  }, []);
  const submit = (e) => {
    e.preventDefault();
    if (d.reason && !reason.trim()) return;
    onConfirm({ reason: reason.trim(), action, lock });
  };
  return html`<dialog ref=${dialog} class=${"confirm " + (d.stop ? "danger" : "")} data-kind=${request.kind}>
    <form method="dialog" onSubmit=${submit}>
      <h2>${d.title}</h2>
      <p>${d.text}</p>
      ${d.stop &&
      html`<fieldset class="stop-actions">
          ${STOP_ACTIONS.map(
            ([value, label]) => html`<label><input type="radio" name="stop-action" value=${value} checked=${action === value} onChange=${() => setAction(value)} /> ${label}</label>`,
          )}
          <label class="lock-too"><input type="checkbox" name="stop-lock" checked=${lock} onChange=${(e) => setLock(e.target.checked)} /> Lock the fleet first, so agents cannot resume</label>
        </fieldset>`}
      ${d.reason &&
      html`<label class="reason-field">Reason (agents and operators see it)
          <input name="reason" required maxlength="500" value=${reason} onInput=${(e) => setReason(e.target.value)} placeholder="e.g. battery swap, people on the field" autofocus />
        </label>`}
      <div class="buttons">
        <button type="button" class="cancel" onClick=${onCancel} disabled=${busy}>Cancel</button>
        <button type="submit" class=${"confirm-button" + (d.stop ? " danger" : "")} disabled=${busy || (d.reason && !reason.trim())}>${d.confirm}</button>
      </div>
    </form>
  </dialog>`;
}

export function LoginForm({ message, onLogin }) {
  const [token, setToken] = useState("");
  return html`<main class="login">
    <form onSubmit=${(e) => {
      e.preventDefault();
      if (token.trim()) onLogin(token.trim());
    }}>
      <h1>fleet-gateway console</h1>
      <p>This gateway needs an operator token (to act) or a viewer token (to watch).</p>
      ${message && html`<p class="error">${message}</p>`}
      <label>Token <input type="password" name="token" autocomplete="current-password" value=${token} onInput=${(e) => setToken(e.target.value)} autofocus /></label>
      <button type="submit">Open the console</button>
      <p class="hint">The token stays in this browser tab (sessionStorage) and is sent only in the Authorization header.</p>
    </form>
  </main>`;
}
