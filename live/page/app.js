// The rollsense live view: plots the present trial from the run's event stream
// (rollsense run --live), or the trials of a recorded dataset (rollsense view).
// Our own small canvas plotter: no library, no network beyond this server.
"use strict";

const COLOURS = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#17becf", "#8c564b", "#e377c2"];
const $ = (id) => document.getElementById(id);

// One trial as plotted: time and one array per series of each plot.
function emptyTrial(header) {
  return {
    header, t: [],
    series: {
      channels: header.channels.map(() => []),
      angles: header.joints.map(() => []),
      currents: (header.currents || header.joints).map(() => []),
    },
  };
}

let present = null;   // the trial drawn in full colour
let previous = null;  // the one before, faded behind it
let dirty = false;

// Draw the series `key` of the present and previous trials on `canvas`.
function plot(canvas, key, names, unit) {
  const ctx = canvas.getContext("2d");
  const W = canvas.width, H = canvas.height, left = 72, right = 150, top = 8, bottom = 22;
  ctx.clearRect(0, 0, W, H);
  const trials = [previous, present].filter((tr) => tr && tr.series[key] && tr.series[key].length);
  let tmax = 1e-9, lo = Infinity, hi = -Infinity, points = 0;
  for (const tr of trials) {
    if (tr.t.length) tmax = Math.max(tmax, tr.t[tr.t.length - 1]);
    for (const s of tr.series[key]) for (const v of s) if (v !== null) { lo = Math.min(lo, v); hi = Math.max(hi, v); }
  }
  if (!isFinite(lo)) { lo = 0; hi = 1; }
  if (hi - lo < 1e-9) { hi += 0.5; lo -= 0.5; }
  const x = (t) => left + (W - left - right) * t / tmax;
  const y = (v) => top + (H - top - bottom) * (1 - (v - lo) / (hi - lo));
  // Axes with their ranges and units.
  ctx.strokeStyle = "#999"; ctx.fillStyle = "#444"; ctx.font = "11px sans-serif"; ctx.lineWidth = 1;
  ctx.strokeRect(left, top, W - left - right, H - top - bottom);
  ctx.textAlign = "right";
  ctx.fillText(hi.toPrecision(4), left - 4, top + 10);
  ctx.fillText(lo.toPrecision(4), left - 4, H - bottom);
  // In brackets, so the unit is not read as a tick value between the two.
  ctx.fillText("[" + unit + "]", left - 4, (H - bottom) / 2 + 4);
  ctx.textAlign = "center";
  ctx.fillText("0 s", left, H - 6);
  ctx.fillText(tmax.toFixed(1) + " s", W - right, H - 6);
  for (const tr of trials) {
    ctx.globalAlpha = tr === present ? 1 : 0.25;
    tr.series[key].forEach((s, i) => {
      ctx.strokeStyle = COLOURS[i % COLOURS.length]; ctx.lineWidth = 1.5;
      ctx.beginPath();
      let pen = false;
      for (let k = 0; k < s.length; ++k) {
        if (s[k] === null) { pen = false; continue; }
        if (pen) ctx.lineTo(x(tr.t[k]), y(s[k])); else ctx.moveTo(x(tr.t[k]), y(s[k]));
        pen = true;
        if (tr === present) ++points;
      }
      ctx.stroke();
    });
  }
  ctx.globalAlpha = 1; ctx.textAlign = "left";
  names.forEach((n, i) => { ctx.fillStyle = COLOURS[i % COLOURS.length]; ctx.fillText(n, W - right + 8, top + 12 + 14 * i); });
  canvas.dataset.points = String(points);
}

function draw() {
  dirty = false;
  if (!present) return;
  const h = present.header;
  // "1" is how the dataset format writes a ratio without a unit (the MPL115A's scaled counts).
  const units = [...new Set(h.channel_units.filter((u) => u).map((u) => (u === "1" ? "no unit" : u)))].join(", ") || "value";
  plot($("plot-channels"), "channels", h.channels, units);
  // Fingers turn in deg, the palm and the winch move in mm: when both are
  // plotted, each curve names its unit. A recorded dataset does not say.
  const jointUnits = h.joint_units || [];
  const distinct = [...new Set(jointUnits)];
  const jointNames = distinct.length > 1 ? h.joints.map((n, i) => `${n} [${jointUnits[i]}]`) : h.joints;
  const jointUnit = distinct.join(", ") || "deg or mm";
  $("cap-angles").textContent = `joint positions (${jointUnit})`;
  plot($("plot-angles"), "angles", jointNames, jointUnit);
  if (h.currents) plot($("plot-currents"), "currents", h.currents, h.current_unit || "mA");
  $("n-samples").textContent = String(present.t.length);
}
function redraw() { if (!dirty) { dirty = true; requestAnimationFrame(draw); } }

function describeTrial(h) {
  return `trial ${h.id} — object ${h.object}, speed ${h.speed}, repetition ${h.repetition}`;
}
function seconds(s) {
  if (s === null || s === undefined) return "?";
  return s >= 3600 ? (s / 3600).toFixed(1) + " h" : s >= 60 ? (s / 60).toFixed(1) + " min" : s.toFixed(0) + " s";
}
function count(id, n) { $(id).textContent = String(Number($(id).textContent) + n); }

// The header's notice: what the page waits for, or why it stopped ("" hides it).
function notice(text, bad) {
  $("notice").textContent = text;
  $("notice").hidden = !text;
  $("notice").className = bad ? "bad" : "";
}
const failed = (e) => notice(`${e.message}: reload the page to try again`, true);

// ---------------------------------------------------------------- busy ------
// The server serves a few viewers at once and answers any more with 503 and
// Retry-After (live/src/live/http_server.cpp). fetch() resolves on a 503 like
// on any answer, and EventSource gives up for good on one, so a page that met
// a full server stayed blank until reloaded. Instead it waits as the server
// asks, says so meanwhile, and asks again.
const RETRY_DEFAULT_S = 2, RETRY_MAX_S = 30;

// fetch(url, options) until the server has room: the answer when it is ok;
// any other answer or a network error throws, saying what it was.
async function get(url, options) {
  for (let waited = false; ; waited = true) {
    const r = await fetch(url, options).catch((e) => { throw new Error(`${url}: ${e.message}`); });
    if (r.ok) {
      if (waited) notice("");
      return r;
    }
    const text = (await r.text()).trim();  // empty for HEAD
    if (r.status !== 503) throw new Error(`${url}: ${r.status} ${r.statusText}` + (text ? ` (${text})` : ""));
    // Seconds (an HTTP date, which this server never sends, gets the default);
    // capped, so a wrong header cannot park the page for hours.
    const after = Number(r.headers.get("Retry-After"));
    const s = after > 0 ? Math.min(after, RETRY_MAX_S) : RETRY_DEFAULT_S;
    const most = text.match(/(\d+) viewers at once/);  // the server's "8 viewers at once at most: ..."
    notice(`busy: ${most ? most[1] + " viewers at most" : "no room for another viewer"}, retrying in ${s} s`);
    await new Promise((wake) => setTimeout(wake, s * 1000));
  }
}

// ---------------------------------------------------------------- live ------
// ?events=N: stop following the stream after N events, leaving the page as it
// is then (a snapshot: a headless browser's --dump-dom or --screenshot waits
// for every connection to end).
function live() {
  const limit = Number(new URLSearchParams(location.search).get("events")) || Infinity;
  let received = 0, source = null;
  const handlers = [];
  const on = (name, fn) => handlers.push([name, fn]);
  const connect = () => {
    source = new EventSource("events");
    for (const [name, fn] of handlers)
      source.addEventListener(name, (e) => {
        count("n-events", 1);
        fn(JSON.parse(e.data));
        if (++received >= limit) { source.close(); draw(); }
      });
    // A broken connection EventSource opens again by itself (readyState
    // CONNECTING). An answer other than a stream closes it for good without
    // saying which: HEAD of the same URL tells, waiting while the server is
    // full, and then the page connects anew (a late joiner is sent the run,
    // trial and state again; the same trial is not started over).
    source.onerror = () => {
      if (source.readyState === EventSource.CLOSED) get("events", { method: "HEAD" }).then(connect, failed);
    };
  };
  on("run", (r) => {
    $("run").textContent = `${r.script} on ${r.profile}: ${r.outcome}` + (r.message ? ` — ${r.message}` : "");
    $("run").className = r.outcome === "failed" || r.outcome === "cancelled" ? "bad" : "";
    if (r.outcome !== "running") source.close();
  });
  on("trial", (h) => {
    if (present && present.header.serial === h.serial) return;  // the same trial again (reconnect)
    h.currents = h.joints;
    previous = present;
    present = emptyTrial(h);
    count("n-trials", 1);
    $("trial-title").textContent = describeTrial(h);
    redraw();
  });
  on("sample", (s) => {
    if (!present || s.serial !== present.header.serial) return;
    $("latest-trial").textContent = String(s.serial);
    $("latest-n").textContent = String(s.n);
    present.t.push(s.t);
    s.c.forEach((v, i) => present.series.channels[i].push(v));
    s.a.forEach((v, i) => present.series.angles[i] && present.series.angles[i].push(v));
    s.i.forEach((v, i) => present.series.currents[i] && present.series.currents[i].push(v));
    redraw();
  });
  on("progress", (p) => {
    $("progress").textContent = `${p.done} of ${p.total} ${p.label}` + (p.done < p.total ? `, about ${seconds(p.eta_s)} left` : "");
  });
  on("status", (s) => { $("step").textContent = s.step; });
  on("state", (s) => {
    $("modes").textContent = Object.entries(s.modes).map(([j, m]) => `${j}: ${m}`).join("; ");
    const controllers = Object.entries(s.controllers);
    $("controllers").textContent = controllers.length ? controllers.map(([c, on]) => `${c} ${on ? "on" : "off"}`).join("; ") : "none";
    $("estop").textContent = s.estop || "released";
    $("estop").className = s.estop ? "bad" : "";
    $("faults").textContent = s.faults.length ? s.faults.map((f) => `${f.device}${f.joint ? " (" + f.joint + ")" : ""}: ${f.reason}`).join("; ") : "none";
    $("faults").className = s.faults.length ? "bad" : "";
  });
  on("result", (r) => {
    const ranked = Object.entries(r.scores).sort((a, b) => b[1] - a[1]).slice(0, 3);
    $("result").textContent = `${r.trial}: ${r.object} (` + ranked.map(([c, v]) => `${c} ${v.toFixed(2)}`).join(", ") + ")";
  });
  on("lag", (l) => count("n-lost", l.missed));
  connect();
}

// ---------------------------------------------------------------- view ------
async function view(info) {
  $("mode").textContent = `dataset ${info.dataset}`;
  $("run").textContent = `${info.trials} trials recorded with profile ${info.profile}`;
  $("fig-currents").hidden = true;
  $("side").hidden = true;
  $("trials").hidden = false;
  const trials = await (await get("dataset/trials.json")).json();
  const list = $("trial-list");
  for (const tr of trials) {
    const li = document.createElement("li");
    li.textContent = tr.id;
    li.title = `object ${tr.object}, speed ${tr.speed}, ${tr.samples} samples`;
    li.onclick = () => show(tr.id, li).catch(failed);
    list.appendChild(li);
  }
  if (trials.length) await show(trials[0].id, list.firstChild);
}
async function show(id, li) {
  const d = await (await get("dataset/trial/" + encodeURIComponent(id) + ".json")).json();
  document.querySelectorAll("nav li.selected").forEach((e) => e.classList.remove("selected"));
  li.classList.add("selected");
  previous = present;
  present = { header: d, t: d.time, series: { channels: d.c, angles: d.a } };
  count("n-trials", 1);
  $("trial-title").textContent = describeTrial(d);
  redraw();
}

get("info.json").then((r) => r.json()).then((info) => (info.mode === "view" ? view(info) : live())).catch(failed);
