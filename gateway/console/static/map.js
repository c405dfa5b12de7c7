// The fleet map (Leaflet). Without a tile server the map is an azimuthal equidistant projection
// centred on the fleet's home (proj4 + Proj4Leaflet): positions in metres, range rings, a scale bar,
// and nothing fetched from outside. With GATEWAY_CONSOLE_TILES_URL it is Web Mercator over those tiles.
//
// MapView is imperative (Leaflet is); the FleetMap component owns one and hands it every update.

import { h } from "./vendor/preact/preact.mjs";
import { useEffect, useRef } from "./vendor/preact/hooks.mjs";
import htm from "./vendor/htm/htm.module.js";
import { api } from "./api.js";
import { num, stateClass } from "./format.js";

const html = htm.bind(h);
const L = window.L;
const proj4 = window.proj4;

// metres per pixel at each zoom level of the offline map (zoom 0 .. 12)
const RESOLUTIONS = [256, 128, 64, 32, 16, 8, 4, 2, 1, 0.5, 0.25, 0.125, 0.0625];
const RING_RADII_M = [25, 50, 100, 250, 500, 1000, 2500, 5000];
const TRACK_MIN_STEP_M = 0.5;
const MIN_VIEW_HALF_SIZE_M = 30; // fitting never zooms in closer than 60 m across

function localDefinition(origin) {
  return `+proj=aeqd +lat_0=${origin.lat} +lon_0=${origin.lon} +x_0=0 +y_0=0 +datum=WGS84 +units=m +no_defs`;
}

function escapeHtml(text) {
  return String(text).replace(/[&<>"']/g, (c) => ({ "&": "&amp;", "<": "&lt;", ">": "&gt;", '"': "&quot;", "'": "&#39;" })[c]);
}

function droneIconHtml(drone, selected) {
  const cls = stateClass(drone);
  const heading = drone.heading_deg ?? 0;
  const lock = drone.locked ? '<span class="lockmark" title="locked">⚿</span>' : "";
  const alt = drone.position ? num(drone.position.alt_rel_m, 1, "m") : "–";
  const battery = drone.battery_pct === null || drone.battery_pct === undefined ? "–" : `${Math.round(drone.battery_pct)}%`;
  return (
    `<div class="drone st-${cls}${selected ? " selected" : ""}${drone.locked ? " locked" : ""}" data-drone="${escapeHtml(drone.id)}">` +
    `<svg class="arrow" viewBox="-12 -12 24 24" style="transform: rotate(${heading}deg)">` +
    '<path d="M0,-11 L8,9 L0,4 L-8,9 Z"/></svg>' +
    `<div class="label"><b>${escapeHtml(drone.id)}</b>${lock} <span class="mode">${escapeHtml(drone.flight_mode ?? "–")}</span>` +
    `<br><span class="alt">${alt}</span> · <span class="batt">${battery}</span></div>` +
    "</div>"
  );
}

// Takes a drone's layer off the map and forgets its entry (entries: drone id -> entry, whose field
// holds the layer: "marker" of a drone's marker, "line" of its track).
function dropLayer(entries, id, field) {
  const entry = entries.get(id);
  if (entry) {
    entry[field].remove();
    entries.delete(id);
  }
}

// A control on the map at position ("topright", ...) whose element make() builds when it is added.
function addControl(map, position, make) {
  const Control = L.Control.extend({ onAdd: make });
  new Control({ position }).addTo(map);
}

function latLngOf(position) {
  return L.latLng(position.lat, position.lon);
}

export class MapView {
  constructor(element, { origin, tilesUrl, tilesAttribution, onSelect }) {
    this.origin = origin;
    this.onSelect = onSelect;
    this.local = proj4(localDefinition(origin)); // WGS84 <-> metres east/north of the origin
    const options = { zoomSnap: 0.25, attributionControl: Boolean(tilesUrl) };
    if (tilesUrl) {
      this.map = L.map(element, { ...options, maxZoom: 20 });
      L.tileLayer(tilesUrl, { maxZoom: 20, attribution: tilesAttribution || "" }).addTo(this.map);
    } else {
      const crs = new L.Proj.CRS("FLEET:LOCAL", localDefinition(origin), { resolutions: RESOLUTIONS, origin: [0, 0] });
      this.map = L.map(element, { ...options, crs, minZoom: 0, maxZoom: RESOLUTIONS.length - 1 });
      element.classList.add("offline-map");
    }
    this.map.setView([origin.lat, origin.lon], tilesUrl ? 17 : 8);
    L.control.scale({ imperial: false, maxWidth: 160 }).addTo(this.map);
    this._addCursorReadout();
    this._addFitButton();
    this.rings = L.layerGroup().addTo(this.map);
    this.fences = L.layerGroup().addTo(this.map);
    this.homes = L.layerGroup().addTo(this.map);
    this.trackLayer = L.layerGroup().addTo(this.map);
    this.replayLayer = L.layerGroup().addTo(this.map);
    this.droneLayer = L.layerGroup().addTo(this.map);
    this.markers = new Map(); // drone id -> {marker, html}
    this.tracks = new Map(); // drone id -> {flightId, line, last}
    this.homeKeys = "";
    this.fitted = false;
    this._setFollowing(true); // keep every drone in view, until the operator pans or zooms by hand
    this._fitting = false;
    this.map.on("dragstart", () => this._setFollowing(false));
    this.map.on("zoomstart", () => this._fitting || this._setFollowing(false));
    this.vehicles = [];
    this._drawRings();
  }

  destroy() {
    this.map.remove();
  }

  // Metres east and north of `from` (default: the map's origin) to `to`; both {lat, lon}.
  offset(to, from = null) {
    const a = this.toLocal({ lat: to.lat, lng: to.lon });
    const b = from ? this.toLocal({ lat: from.lat, lng: from.lon }) : { east: 0, north: 0 };
    return { east: a.east - b.east, north: a.north - b.north };
  }

  toLocal(latlng) {
    const [east, north] = this.local.forward([latlng.lng, latlng.lat]);
    return { east, north };
  }

  fromLocal(east, north) {
    const [lon, lat] = this.local.inverse([east, north]);
    return L.latLng(lat, lon);
  }

  _drawRings() {
    const style = { color: "#8a99a8", weight: 1, opacity: 0.55, interactive: false };
    for (const radius of RING_RADII_M) {
      const points = [];
      for (let deg = 0; deg <= 360; deg += 5) {
        const rad = (deg * Math.PI) / 180;
        points.push(this.fromLocal(radius * Math.sin(rad), radius * Math.cos(rad)));
      }
      L.polyline(points, { ...style, dashArray: "4 6" }).addTo(this.rings);
      L.marker(this.fromLocal(0, radius), {
        interactive: false,
        icon: L.divIcon({ className: "ring-label", html: `${radius >= 1000 ? radius / 1000 + " km" : radius + " m"}`, iconSize: [50, 14], iconAnchor: [-3, 7] }),
      }).addTo(this.rings);
    }
    const far = RING_RADII_M[RING_RADII_M.length - 1];
    L.polyline([this.fromLocal(0, -far), this.fromLocal(0, far)], style).addTo(this.rings);
    L.polyline([this.fromLocal(-far, 0), this.fromLocal(far, 0)], style).addTo(this.rings);
    L.marker(this.fromLocal(0, 0), {
      interactive: false,
      icon: L.divIcon({ className: "north-label", html: "N ↑", iconSize: [30, 14], iconAnchor: [-4, 30] }),
    }).addTo(this.rings);
  }

  _addCursorReadout() {
    addControl(this.map, "bottomright", () => {
      const div = L.DomUtil.create("div", "cursor-readout");
      div.textContent = "metres from the fleet's home";
      div.title = "the map's origin: the first home position the gateway knew";
      this.map.on("mousemove", (e) => {
        const { east, north } = this.toLocal(e.latlng);
        div.textContent = `E ${num(east, 0)} m · N ${num(north, 0)} m from the fleet's home`;
      });
      return div;
    });
  }

  _addFitButton() {
    addControl(this.map, "topright", () => {
      const button = L.DomUtil.create("button", "map-button");
      button.type = "button";
      button.textContent = "Fit fleet";
      button.title = "Zoom to every drone and home";
      L.DomEvent.disableClickPropagation(button);
      L.DomEvent.on(button, "click", () => {
        this._setFollowing(true);
        this.fit();
      });
      this.fitButton = button;
      return button;
    });
  }

  _setFollowing(on) {
    this.following = on;
    if (this.fitButton) {
      this.fitButton.textContent = on ? "Following fleet" : "Fit fleet";
      this.fitButton.classList.toggle("following", on);
    }
  }

  _fleetPoints() {
    const points = [];
    for (const drone of this.vehicles) {
      if (drone.position) points.push(latLngOf(drone.position));
      if (drone.home) points.push(latLngOf(drone.home));
    }
    return points;
  }

  fit() {
    const points = this._fleetPoints();
    if (!points.length) return;
    const centre = L.latLngBounds(points).getCenter();
    const { east, north } = this.toLocal(centre);
    points.push(this.fromLocal(east - MIN_VIEW_HALF_SIZE_M, north - MIN_VIEW_HALF_SIZE_M));
    points.push(this.fromLocal(east + MIN_VIEW_HALF_SIZE_M, north + MIN_VIEW_HALF_SIZE_M));
    this._fitting = true;
    try {
      this.map.fitBounds(L.latLngBounds(points).pad(0.15), { animate: false });
    } finally {
      this._fitting = false;
    }
  }

  setFleet(vehicles, selectedId) {
    this.vehicles = vehicles;
    const seen = new Set();
    for (const drone of vehicles) {
      seen.add(drone.id);
      this._updateTrack(drone);
      if (!drone.position) {
        dropLayer(this.markers, drone.id, "marker");
        continue;
      }
      const htmlText = droneIconHtml(drone, drone.id === selectedId);
      const latlng = latLngOf(drone.position);
      let entry = this.markers.get(drone.id);
      if (!entry) {
        const marker = L.marker(latlng, { icon: this._icon(htmlText), keyboard: false, title: drone.id });
        marker.on("click", () => this.onSelect(drone.id));
        marker.addTo(this.droneLayer);
        entry = { marker, html: htmlText };
        this.markers.set(drone.id, entry);
      } else {
        entry.marker.setLatLng(latlng);
        if (entry.html !== htmlText) {
          entry.marker.setIcon(this._icon(htmlText));
          entry.html = htmlText;
        }
      }
      entry.marker.setZIndexOffset(drone.id === selectedId ? 1000 : 0);
    }
    for (const id of [...this.markers.keys()]) if (!seen.has(id)) dropLayer(this.markers, id, "marker");
    for (const id of [...this.tracks.keys()]) if (!seen.has(id)) dropLayer(this.tracks, id, "line");
    this._drawHomes(vehicles);
    if (this.following) {
      const points = this._fleetPoints();
      const view = this.map.getBounds().pad(-0.05);
      if (points.length && (!this.fitted || !points.every((p) => view.contains(p)))) {
        this.fit();
        this.fitted = true;
      }
    }
  }

  _icon(htmlText) {
    return L.divIcon({ className: "drone-icon", html: htmlText, iconSize: [26, 26], iconAnchor: [13, 13] });
  }

  _drawHomes(vehicles) {
    const homes = vehicles.filter((d) => d.home);
    const key = homes.map((d) => `${d.id}:${d.home.lat.toFixed(6)},${d.home.lon.toFixed(6)}`).join("|");
    if (key === this.homeKeys) return;
    this.homeKeys = key;
    this.homes.clearLayers();
    for (const drone of homes) {
      L.marker(latLngOf(drone.home), {
        interactive: true,
        keyboard: false,
        title: `home of ${drone.id}`,
        icon: L.divIcon({ className: "home-icon", html: "H", iconSize: [14, 14], iconAnchor: [7, 7] }),
      }).addTo(this.homes);
    }
  }

  // The track of each drone's current flight: what was recorded before the page opened (fetched once),
  // then every new position from the stream.
  _updateTrack(drone) {
    const flightId = drone.flight_id;
    let track = this.tracks.get(drone.id);
    if (track && track.flightId !== flightId) {
      dropLayer(this.tracks, drone.id, "line");
      track = null;
    }
    if (!flightId || !drone.position) return;
    if (!track) {
      const line = L.polyline([], { className: "flight-track", weight: 2, interactive: false }).addTo(this.trackLayer);
      track = { flightId, line, last: null };
      this.tracks.set(drone.id, track);
      api(`/flights/${flightId}/track.geojson`)
        .then((feature) => {
          if (this.tracks.get(drone.id) !== track || !feature.geometry) return;
          const coords = feature.geometry.type === "Point" ? [feature.geometry.coordinates] : feature.geometry.coordinates;
          const earlier = coords.map(([lon, lat]) => L.latLng(lat, lon));
          track.line.setLatLngs([...earlier, ...track.line.getLatLngs()]);
        })
        .catch(() => {});
    }
    const here = latLngOf(drone.position);
    if (!track.last || this.map.distance(track.last, here) >= TRACK_MIN_STEP_M) {
      track.line.addLatLng(here);
      track.last = here;
    }
  }

  setGeofences(collection) {
    this.fences.clearLayers();
    if (!collection || !collection.features) return;
    L.geoJSON(collection, {
      style: (feature) =>
        feature.properties.kind === "keep_out"
          ? { className: "fence keep-out", color: "#c0392b", weight: 2, fillOpacity: 0.15 }
          : { className: "fence keep-in", color: "#1e8449", weight: 2, dashArray: "8 5", fillOpacity: 0.03 },
      onEachFeature: (feature, layer) => {
        const p = feature.properties;
        // Leaflet puts tooltip strings into innerHTML: escape the operator-given names
        const text = `${p.kind === "keep_out" ? "keep out" : "keep in"}: ${p.name}${p.vehicle_id ? ` (${p.vehicle_id})` : ""}`;
        layer.bindTooltip(escapeHtml(text));
      },
    }).addTo(this.fences);
  }

  // A past flight: its whole track, and a marker where the drone was at the replay's current sample.
  setReplay(replay) {
    if (!replay || !replay.feature || !replay.feature.geometry) {
      this.replayLayer.clearLayers();
      this.replayKey = null;
      return;
    }
    const coords = replay.feature.geometry.type === "Point" ? [replay.feature.geometry.coordinates] : replay.feature.geometry.coordinates;
    const points = coords.map(([lon, lat]) => L.latLng(lat, lon));
    const key = replay.feature.id;
    if (this.replayKey !== key) {
      this.replayLayer.clearLayers();
      this.replayKey = key;
      this._setFollowing(false); // look at the replay, not at the live fleet
      L.polyline(points, { className: "replay-track", weight: 3, interactive: false }).addTo(this.replayLayer);
      L.circleMarker(points[0], { radius: 5, className: "replay-start" }).bindTooltip("take-off").addTo(this.replayLayer);
      this.replayMarker = L.marker(points[0], { interactive: false, icon: this._icon("") }).addTo(this.replayLayer);
      this._fitting = true;
      this.map.fitBounds(L.latLngBounds(points).pad(0.3), { maxZoom: this.map.getMaxZoom() - 2, animate: false });
      this._fitting = false;
    }
    const i = Math.max(0, Math.min(points.length - 1, replay.index));
    const props = replay.feature.properties;
    const sample = {
      id: props.vehicle_id,
      position: { lat: points[i].lat, lon: points[i].lng, alt_rel_m: props.alt_rel_m[i], stale: false },
      heading_deg: props.heading_deg[i],
      battery_pct: props.battery_pct[i],
      flight_mode: "replay",
      in_air: true,
      state: "ready",
    };
    this.replayMarker.setLatLng(points[i]);
    this.replayMarker.setIcon(this._icon(droneIconHtml(sample, false).replace("st-air", "st-replay")));
  }
}

export function FleetMap({ origin, config, vehicles, selectedId, onSelect, geofences, replay, onReady }) {
  const element = useRef(null);
  const view = useRef(null);
  const onSelectRef = useRef(onSelect);
  onSelectRef.current = onSelect;

  useEffect(() => {
    if (!origin || view.current) return undefined;
    view.current = new MapView(element.current, {
      origin,
      tilesUrl: config.tiles_url,
      tilesAttribution: config.tiles_attribution,
      onSelect: (id) => onSelectRef.current(id),
    });
    window.fleetMap = view.current; // for the browser tests and the curious operator
    onReady(view.current);
    return undefined;
  }, [origin]);

  useEffect(() => () => view.current && view.current.destroy(), []);

  useEffect(() => {
    if (view.current) view.current.setFleet(vehicles, selectedId);
  });
  useEffect(() => {
    if (view.current) view.current.setGeofences(geofences);
  }, [geofences, view.current]);
  useEffect(() => {
    if (view.current) view.current.setReplay(replay);
  }, [replay, view.current]);

  return html`<div class="map-wrap">
    <div class="map" ref=${element}></div>
    ${!origin && html`<div class="map-waiting">Waiting for a drone's home position…</div>`}
  </div>`;
}
