// Talking to the gateway: the bearer token, REST calls, and the live event stream.
//
// The token stays in this tab's sessionStorage (gone when the tab closes) and travels only in the
// Authorization header: never in a URL, so it cannot end up in an access log or a proxy's log.
// The stream is read with fetch (EventSource cannot send headers) and parsed by eventsource-parser.

import { EventSourceParserStream } from "./vendor/eventsource-parser/stream.js";

const TOKEN_KEY = "fleet-gateway.console.token";
const SILENCE_MS = 10000;
export const API = "/api/v1";

export function getToken() {
  return sessionStorage.getItem(TOKEN_KEY);
}

export function setToken(token) {
  if (token) sessionStorage.setItem(TOKEN_KEY, token);
  else sessionStorage.removeItem(TOKEN_KEY);
}

// Every request says it comes from the console, so the audit and the command path name that door.
function headers(extra = {}) {
  const token = getToken();
  const marked = { ...extra, "X-Fleet-Door": "console" };
  return token ? { ...marked, Authorization: `Bearer ${token}` } : marked;
}

export class ApiError extends Error {
  constructor(status, code, message) {
    super(message);
    this.status = status;
    this.code = code;
  }
}

// One REST call; the gateway's JSON error ({"error": {"code", "message"}}) becomes an ApiError.
export async function api(path, { method = "GET", body, signal } = {}) {
  const init = { method, signal, cache: "no-store", headers: headers() };
  if (body !== undefined) {
    init.body = JSON.stringify(body);
    init.headers = headers({ "Content-Type": "application/json" });
  }
  const response = await fetch(API + path, init);
  const text = await response.text();
  let data = null;
  try {
    data = text ? JSON.parse(text) : null;
  } catch {
    data = null;
  }
  if (!response.ok) {
    const err = (data && data.error) || {};
    throw new ApiError(response.status, err.code || `http_${response.status}`, err.message || text || response.statusText);
  }
  return data;
}

const sleep = (ms, signal) =>
  new Promise((resolve) => {
    const timer = setTimeout(resolve, ms);
    signal?.addEventListener("abort", () => {
      clearTimeout(timer);
      resolve();
    });
  });

// Read /api/v1/events until `signal` aborts, reconnecting with backoff. onEvent(name, data) gets every
// event; onState(state, detail) hears "connecting", "live", "retrying" (with the reason) and
// "unauthorized" (the token was refused: the stream stops).
export async function streamEvents({ onEvent, onState, signal }) {
  let delay = 500;
  while (!signal.aborted) {
    onState("connecting");
    // one attempt: ended by the caller, or by SILENCE_MS without a byte (a connection that hangs
    // silently, e.g. behind a proxy, is dropped and opened again; the gateway sends every 0.5 s)
    const attempt = new AbortController();
    const stop = () => attempt.abort();
    signal.addEventListener("abort", stop);
    let silence = setTimeout(stop, SILENCE_MS);
    const heard = () => {
      clearTimeout(silence);
      silence = setTimeout(stop, SILENCE_MS);
    };
    try {
      const response = await fetch(API + "/events", { headers: headers(), signal: attempt.signal, cache: "no-store" });
      if (response.status === 401 || response.status === 403) {
        onState("unauthorized");
        return;
      }
      if (!response.ok) throw new Error(`the gateway answered HTTP ${response.status}`);
      const reader = response.body
        .pipeThrough(new TextDecoderStream())
        .pipeThrough(new EventSourceParserStream({ onComment: heard }))
        .getReader();
      let first = true;
      for (;;) {
        const { value, done } = await reader.read();
        if (done) break;
        heard();
        if (first) {
          onState("live");
          delay = 500;
          first = false;
        }
        let data = null;
        try {
          data = JSON.parse(value.data);
        } catch {
          continue;
        }
        onEvent(value.event || "message", data);
      }
      if (!signal.aborted) onState("retrying", "the stream ended");
    } catch (error) {
      if (signal.aborted) return;
      onState("retrying", attempt.signal.aborted ? "no data from the gateway" : String(error.message || error));
    } finally {
      clearTimeout(silence);
      signal.removeEventListener("abort", stop);
    }
    await sleep(delay, signal);
    delay = Math.min(delay * 2, 5000);
  }
}
