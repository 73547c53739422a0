// The status page's script: it reads the gateway's event stream (/api/events, the status once
// a second and the tags of each open exchange) and draws the page from it, with text nodes only
// (names come from the configuration and must never be read as markup).

#include "eip2mqtt/app/status/status_page.hpp"

namespace eip2mqtt::app::status::detail {

const std::string_view page_script = R"js("use strict";
const PAGE_SIZE = 100;
const state = { status: null, open: new Map(), sort: "name", up: true, page: 0, stream: null };

function el(tag, text, cls) {
  const node = document.createElement(tag);
  if (text !== undefined && text !== null) node.textContent = String(text);
  if (cls) node.className = cls;
  return node;
}

function durationText(ms) {
  return ms < 10000 ? (ms / 1000).toFixed(1) + " s" : Math.round(ms / 1000) + " s";
}

function ageText(ms) {
  if (ms === null || ms === undefined) return "never";
  return durationText(ms) + " ago";
}

function timeText(ms) {
  return ms ? new Date(ms).toLocaleString() : "-";
}

function valueText(value) {
  if (Array.isArray(value)) return "[" + value.map(valueText).join(", ") + "]";
  if (typeof value === "number" && !Number.isInteger(value)) return value.toPrecision(6);
  return String(value);
}

/// Why a consumed exchange is not ok, in a few words; "" when it is.
function reasonOf(state, exchange) {
  const timeout = exchange.timeout_ms ? " (timeout " + exchange.timeout_ms / 1000 + " s)" : "";
  switch (state) {
    case "waiting": return "no datagram yet" + timeout;
    case "stale": return "no datagram for " + durationText(exchange.last_seen_age_ms) + timeout;
    case "signature_mismatch": return "the producer's configuration signature is not the one configured";
    case "length_mismatch": return "its datagrams' length is not the one configured";
    default: return "";
  }
}

function row(exchange) {
  const s = exchange.status || {};
  return {
    name: exchange.name, direction: exchange.direction, state: s.state || "",
    reason: reasonOf(s.state, exchange),
    rate: exchange.datagrams_per_s || 0,
    age: exchange.last_seen_age_ms === undefined ? -1 : exchange.last_seen_age_ms,
    missed: s.missed || 0, restarts: s.restarts || 0, clock: s.clock || "", exchange: exchange
  };
}

function connect() {
  if (state.stream) state.stream.close();
  const names = Array.from(state.open.keys()).map(encodeURIComponent).join(",");
  const stream = new EventSource("/api/events" + (names ? "?open=" + names : ""));
  state.stream = stream;
  const live = document.getElementById("live");
  stream.addEventListener("status", (event) => {
    state.status = JSON.parse(event.data);
    live.textContent = "live";
    live.className = "live";
    draw();
  });
  stream.addEventListener("exchange", (event) => {
    const exchange = JSON.parse(event.data);
    if (state.open.has(exchange.name)) state.open.set(exchange.name, exchange);
    draw();
  });
  stream.addEventListener("unavailable", () => {
    live.textContent = "gateway busy";
    live.className = "live off";
  });
  stream.onerror = () => {
    live.textContent = "disconnected";
    live.className = "live off";
  };
}

function drawFacts(gateway) {
  document.getElementById("gateway-id").textContent = gateway.id;
  const m = gateway.metrics || {};
  const facts = [
    ["version", gateway.version],
    ["uptime", (m.uptime_s || 0) + " s"],
    ["configuration", gateway.config.file + " (loaded " + timeText(gateway.config.loaded_at) +
      ", " + gateway.config.reloads + " reload(s))"],
    ["MQTT", (gateway.mqtt.connected ? "connected" : "not connected") + ", " +
      gateway.mqtt.connects + " connection(s) made, " + gateway.mqtt.connection_losses + " lost"],
    ["brokers", gateway.mqtt.brokers.map((b) => b.url + (b.connected ? " (connected)" : ""))
      .join(", ")],
    ["publications", (m.published || 0) + " made, " + (m.buffered || 0) + " waiting"]
  ];
  if (m.history) facts.push(["store and forward", m.history.entries + " entries waiting"]);
  for (const c of gateway.connections || []) {
    facts.push(["MQTT " + c.name, (c.connected ? "connected to " + c.broker : "not connected") +
      ", " + c.published + " published, " + c.buffered + " waiting" +
      (c.journaled === null ? "" : ", " + c.journaled + " journaled")]);
  }
  const sp = gateway.sparkplug;
  if (sp) {
    facts.push(["Sparkplug", sp.group_id + "/" + sp.edge_node_id + ": " +
      (sp.born ? "born" : "not born") + (sp.bd_seq === null ? "" : ", bdSeq " + sp.bd_seq) +
      ", " + sp.devices_born + " of " + sp.devices + " devices born" +
      (sp.primary_host === null ? "" : ", host " + sp.primary_host + " " +
        (sp.host_online ? "online" : "offline")) + ", " + sp.node_births + " node birth(s)"]);
  }
  const r = gateway.role;
  if (r) {
    facts.push(["hot-standby pair", r.pair + ": " + r.role + ", epoch " + r.epoch +
      (r.lease_left_ms === null ? "" : ", lease " + (r.lease_left_ms / 1000).toFixed(1) + " s left")]);
  }
  const list = document.getElementById("facts");
  list.replaceChildren();
  for (const [name, value] of facts) {
    list.append(el("dt", name), el("dd", value));
  }
}

/// The last 10 minutes of a tag, drawn between their lowest and highest value.
function sparkline(points) {
  const ns = "http://www.w3.org/2000/svg";
  const svg = document.createElementNS(ns, "svg");
  svg.setAttribute("width", "120");
  svg.setAttribute("height", "24");
  svg.setAttribute("class", "spark");
  const values = points.filter((v) => v !== null);
  if (values.length === 0) return svg;
  const low = Math.min(...values);
  const high = Math.max(...values);
  const span = high - low || 1;
  const xy = [];
  points.forEach((v, i) => {
    if (v !== null) {
      xy.push((i * 118 / (points.length - 1) + 1).toFixed(1) + "," +
        (22 - (v - low) / span * 20).toFixed(1));
    }
  });
  const line = document.createElementNS(ns, "polyline");
  line.setAttribute("points", xy.join(" "));
  line.setAttribute("fill", "none");
  line.setAttribute("stroke", "currentColor");
  const title = document.createElementNS(ns, "title");
  title.textContent = "last 10 min: " + valueText(low) + " to " + valueText(high);
  svg.append(line, title);
  return svg;
}

function tagTable(exchange) {
  const table = el("table");
  const head = el("tr");
  for (const name of ["tag", "value", "unit", "quality", "time", "last 10 min"]) {
    head.append(el("th", name));
  }
  table.append(head);
  for (const tag of exchange.tags || []) {
    const line = el("tr");
    const sample = tag.sample;
    line.append(el("td", tag.name), el("td", sample ? valueText(sample.value) : "-", "number"),
      el("td", tag.unit || ""),
      el("td", sample ? sample.quality : "no value", sample ? "quality-" + sample.quality : ""),
      el("td", sample ? timeText(sample.timestamp) : "-"));
    const spark = el("td", tag.sparkline ? null : "-");
    if (tag.sparkline) spark.append(sparkline(tag.sparkline));
    line.append(spark);
    table.append(line);
  }
  return table;
}

function sortedRows() {
  const search = document.getElementById("search").value.toLowerCase();
  const rows = (state.status ? state.status.exchanges : []).map(row)
    .filter((r) => r.name.toLowerCase().includes(search));
  const key = state.sort;
  rows.sort((a, b) => (a[key] < b[key] ? -1 : a[key] > b[key] ? 1 : 0) * (state.up ? 1 : -1));
  return rows;
}

function drawExchanges() {
  const rows = sortedRows();
  const pages = Math.max(1, Math.ceil(rows.length / PAGE_SIZE));
  state.page = Math.min(state.page, pages - 1);
  document.getElementById("count").textContent = rows.length + " exchange(s)";
  document.getElementById("page").textContent = "page " + (state.page + 1) + " of " + pages;
  const body = document.querySelector("#exchange-table tbody");
  body.replaceChildren();
  for (const r of rows.slice(state.page * PAGE_SIZE, (state.page + 1) * PAGE_SIZE)) {
    const line = el("tr", null, "exchange " + (r.state === "ok" || r.state === "producing" ? "ok"
      : r.state === "waiting" ? "waiting" : "bad"));
    line.dataset.name = r.name;
    const stateText = r.state + (r.reason ? ": " + r.reason : "");
    line.append(el("td", r.name), el("td", r.direction), el("td", stateText, "state"),
      el("td", r.rate.toFixed(1), "number"),
      el("td", r.direction === "consume" ? ageText(r.exchange.last_seen_age_ms) : "-"),
      el("td", r.missed, "number"), el("td", r.restarts, "number"), el("td", r.clock));
    line.addEventListener("click", () => toggle(r.name));
    body.append(line);
    const open = state.open.get(r.name);
    if (open) {
      const cell = el("td");
      cell.colSpan = 8;
      cell.append(tagTable(open));
      const tags = el("tr", null, "tags");
      tags.append(cell);
      body.append(tags);
    }
  }
}

function drawWrites(writes) {
  const body = document.querySelector("#write-table tbody");
  body.replaceChildren();
  for (const w of writes) {
    const result = w.result === null ? "pending" : w.result;
    const line = el("tr", null, "write " + (result === "ok" || result.startsWith("ok,") ? "ok"
      : result === "pending" || result === "handed to the other unit" ? "waiting" : "bad"));
    line.append(el("td", timeText(w.time)), el("td", w.origin), el("td", w.target),
      el("td", w.values), el("td", result, "result"));
    body.append(line);
  }
}

function drawWarnings(warnings) {
  const list = document.getElementById("warning-list");
  list.replaceChildren();
  for (const line of warnings) list.append(el("li", line));
}

function draw() {
  if (!state.status) return;
  drawFacts(state.status.gateway);
  drawExchanges();
  drawWrites(state.status.writes || []);
  drawWarnings(state.status.warnings || []);
}

function toggle(name) {
  if (state.open.has(name)) state.open.delete(name);
  else state.open.set(name, { name: name, tags: [] });
  // The open exchanges are the page's address too: a link opens them again.
  const names = Array.from(state.open.keys()).map(encodeURIComponent).join(",");
  history.replaceState(null, "", names ? "#open=" + names : location.pathname);
  connect();
  draw();
}

function openFromAddress() {
  const match = /^#open=(.*)$/.exec(location.hash);
  if (!match) return;
  for (const name of match[1].split(",")) {
    if (name) state.open.set(decodeURIComponent(name), { name: decodeURIComponent(name), tags: [] });
  }
}

document.addEventListener("DOMContentLoaded", () => {
  for (const th of document.querySelectorAll("#exchange-table th")) {
    th.addEventListener("click", () => {
      state.up = state.sort === th.dataset.key ? !state.up : true;
      state.sort = th.dataset.key;
      for (const other of document.querySelectorAll("#exchange-table th")) {
        other.className = other === th ? (state.up ? "sorted up" : "sorted") : "";
      }
      draw();
    });
  }
  document.getElementById("search").addEventListener("input", () => { state.page = 0; draw(); });
  document.getElementById("previous").addEventListener("click", () => {
    state.page = Math.max(0, state.page - 1);
    draw();
  });
  document.getElementById("next").addEventListener("click", () => { state.page += 1; draw(); });
  openFromAddress();
  connect();
});
)js";

}  // namespace eip2mqtt::app::status::detail
