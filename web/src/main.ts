// The instructor console in the browser: log in, watch every station, command one, plot its telemetry,
// follow its events, manage trainees and open results. Talks to `harboursim console` only (same origin).
import uPlot from "uplot";
import { parseDocument } from "yaml";
import { View3D, type BulkMessage, type Looks, type SceneMessage } from "./view3d";
import { DesignerForms, setEventLabels } from "./designer";
import { RouteEditor } from "./routeEditor";
import { TelemetryPlots } from "./telemetry";

import type { AttemptEvent, AttemptItem, CommandInfo, CommandTable, Evolution, EvolutionAttempt, EventMessage, ExerciseCard, FigureWords,
  HandSignal, LiveMessage, Me, PictureMessage, Progress, ReplayInfo, RouteInfo, StateMessage, Station, Team } from "./wire";

const $ = <T extends HTMLElement>(id: string) => document.getElementById(id) as T;
let me: Me | null = null;
let selected = "";
let socket: WebSocket | null = null;
let plots: TelemetryPlots | null = null;
let view: View3D | null = null;
const viewOn = () => $<HTMLInputElement>("view-on").checked;
const subscribe = () => socket?.send(JSON.stringify({ type: "subscribe", station: selected, view: viewOn() }));

// Loaders an event and a click may both start: only the latest call of each draws (an earlier answer arriving
// late would otherwise add its rows beside the newer ones).
const calls = new Map<string, number>();
function latestCall(loader: string): () => boolean {
  const call = (calls.get(loader) ?? 0) + 1;
  calls.set(loader, call);
  return () => calls.get(loader) === call;
}

async function api(path: string, method = "GET", body?: unknown): Promise<{ status: number; data: any }> {
  const headers: Record<string, string> = {};
  if (method !== "GET") {
    headers["Content-Type"] = "application/json";
    if (me) headers["X-CSRF-Token"] = me.csrf;
  }
  const r = await fetch(path, { method, headers, body: body === undefined ? undefined : JSON.stringify(body) });
  let data: any = null;
  try { data = await r.json(); } catch { data = null; }
  return { status: r.status, data };
}

function text(cell: HTMLElement, value: string | number) { cell.textContent = String(value); }

function health(s: Station): string {
  const issues: string[] = [];
  if (!s.keeping_real_time || s.skipped_ticks > 0) issues.push("not keeping real time");
  else if (s.late_ticks > 0) issues.push(`${s.late_ticks} late steps`);
  if (s.devices_missing > 0) issues.push("device lost");
  if (s.physics_warnings > 0) issues.push(`${s.physics_warnings} physics warnings`);
  if (s.diverged) issues.push("physics stopped");
  return issues.length ? issues.join(", ") : (s.state === "running" ? `${s.real_time_factor.toFixed(2)}× real time` : "");
}

// a station's answer naming exercises ("starting sts_discharge"): each by its title
const exercisesByTitle = (message: string) => message.replace(/\b[a-z][a-z0-9]*(_[a-z0-9]+)+\b/g,
  (name) => exerciseCards.some((e) => e.name === name) ? exerciseTitle(name) : name);

// a station's message names its exercise at its end, "(sts_discharge)": by its title
const withExerciseTitle = (message: string) =>
  message.replace(/\(([\w-]+)\)$/, (_, name: string) => `(${exerciseTitle(name)})`);

// the selected station's last attempt as it ended (its idle message: "ready; last: attempt 5 passed, score
// 87.0 (sts_discharge)"), shown at the panel's top until the next attempt starts
function showOutcome(s: Station) {
  const panel = $("attempt-outcome");
  const last = s.state === "idle" ? /^ready; last: (attempt \d+ .*)$/.exec(s.message) : null;
  panel.hidden = !last;
  if (!last) return;
  const words = `Last: ${withExerciseTitle(last[1])}`;
  if (panel.textContent !== words) text(panel, words);
  panel.className = / passed,/.test(last[1]) ? "outcome-passed" : "outcome-other";
}

let idleStations: string[] = [];
function showStations(stations: Station[]) {
  const idle = stations.filter((s) => s.state === "idle").map((s) => s.station);
  if (idle.join(" ") !== idleStations.join(" ")) {
    idleStations = idle;
    showTeamStart();
  }
  const takeover = $<HTMLSelectElement>("takeover-station");
  const chosen = takeover.value;
  takeover.replaceChildren();
  for (const s of stations.filter((s) => s.state === "idle")) takeover.add(new Option(s.station, s.station));
  // the instructor's choice while its station is still free, else the first free one (never none)
  if ([...takeover.options].some((o) => o.value === chosen)) takeover.value = chosen;
  // rows are kept and updated in place (a click on one is never lost to a redraw)
  const body = $("stations").querySelector("tbody")!;
  const seen = new Set<string>();
  for (const s of stations) {
    seen.add(s.station);
    let row = body.querySelector<HTMLTableRowElement>(`tr[data-station="${CSS.escape(s.station)}"]`);
    if (!row) {
      row = document.createElement("tr");
      row.dataset.station = s.station;
      for (let n = 0; n < 10; ++n) row.appendChild(document.createElement("td"));
      row.addEventListener("click", () => select(s.station));
      // by keyboard too: the row takes the focus, Enter selects its station
      row.tabIndex = 0;
      row.addEventListener("keydown", (e) => { if (e.key === "Enter") select(s.station); });
      body.appendChild(row);
    }
    row.classList.toggle("selected", s.station === selected);
    // the selected station gone idle sends no more states: its last one no longer applies (a fault lamp, the
    // figures), so the live line says what the station is now
    if (s.state === "idle") endedAttempt.set(s.station, runningAttempt.get(s.station) ?? 0);
    else if (s.attempt) runningAttempt.set(s.station, s.attempt);
    if (s.station === selected) {
      showOutcome(s);
      showFaultButtons(s.machine);
      selectedTeam = s.state === "idle" ? "" : s.team;
      $("team-actions").hidden = selectedTeam === "";
      text($("team-name"), teamWords(selectedTeam));
    }
    if (s.station === selected && s.state === "idle" && $("live").dataset.state !== "idle") {
      latestState = null;
      $("live").dataset.state = "idle";
      text($("live"), s.message ? `idle: ${withExerciseTitle(s.message)}` : "idle");
      text($("live-faults"), "");
      $("live-faults").hidden = true;
    } else if (s.station === selected && s.state !== "idle") {
      $("live").dataset.state = s.state;
    }
    const values = [s.station, s.state, machineTitle(s.machine),
      s.team ? `${exerciseTitle(s.exercise)} (${teamWords(s.role)} of team ${teamWords(s.team)})` : exerciseTitle(s.exercise), s.trainee,
      s.state === "idle" ? "" : `${s.time_s.toFixed(1)} / ${s.time_limit_s.toFixed(0)} s`,
      s.state === "idle" ? "" : s.score.toFixed(0), s.moves_total ? `${s.moves_done}/${s.moves_total}` : "",
      s.collisions, health(s) || withExerciseTitle(s.message)];
    values.forEach((v, n) => { if (row!.children[n].textContent !== String(v)) text(row!.children[n] as HTMLElement, v); });
    (row.children[1] as HTMLElement).className = `state-${s.state}`;
  }
  for (const row of [...body.querySelectorAll<HTMLTableRowElement>("tr")])
    if (!seen.has(row.dataset.station!)) row.remove();
}

let replay: ReplayInfo | null = null;

function select(station: string) {
  selected = station;
  text($("selected"), station);
  const replaying = station.startsWith("replay-");
  $("control-panel").hidden = replaying;
  $("replay-panel").hidden = !replaying;
  $("watch").hidden = false;
  for (const row of $("stations").querySelectorAll("tbody tr"))
    row.classList.toggle("selected", (row as HTMLElement).dataset.station === station);
  plots?.clear();
  $("cab-figure").hidden = true;  // until this station's first picture
  $("events").replaceChildren();
  text($("live"), "");
  subscribe();
}

// The page's frames: every state's figures are kept as they come (10 a second), and what they change on the
// page — the live line, the plot, the 3D view — is drawn together in one frame, at most 10 a second, or 5 where
// the view is light (a page drawn in software pays for each frame it composites). The plots, a minute of data
// drawn anew each time, at most 4 times a second.
const kFrame_ms = 100, kLightFrame_ms = 200, kPlotDraw_ms = 250;
let latestState: StateMessage | null = null;
let nextPlotDraw = 0, lastFrame = 0, frameQueued = false;

function queueFrame() {
  if (frameQueued) return;
  frameQueued = true;
  const wait = lastFrame + ($<HTMLInputElement>("view-light").checked ? kLightFrame_ms : kFrame_ms) - performance.now();
  const draw = () => requestAnimationFrame(() => { frameQueued = false; lastFrame = performance.now(); drawFrame(); });
  if (wait > 0) setTimeout(draw, wait); else draw();
}

// per station, the attempt it last ran, and the attempt it has since ended (gone idle): a state of an ended
// attempt that arrives after the station's idle status (the two topics are not ordered) is stale
const runningAttempt = new Map<string, number>(), endedAttempt = new Map<string, number>();

function keepState(m: StateMessage) {
  if (m.station !== selected) return;
  if (m.attempt <= (endedAttempt.get(m.station) ?? 0)) return;
  plots?.keep(m.time_s, Math.hypot(m.wind_mps[0], m.wind_mps[1]), m.indicators);
  latestState = m;
  queueFrame();
}

function drawFrame() {
  const m = latestState;
  if (!m || m.station !== selected) return;
  const wind = Math.hypot(m.wind_mps[0], m.wind_mps[1]);
  const live = $("live");
  live.dataset.wind = wind.toFixed(2);
  text(live, `t ${m.time_s.toFixed(1)} s${m.held ? " (held)" : ""}   wind ${wind.toFixed(1)} m/s   ` +
    hudText(m.indicators, machineOf.get(m.station) ?? ""));
  // the faults in force, as the cab's fault lamps show them
  const faults = Object.entries(m.indicators).filter(([k, v]) => /^lamp_.*fault$/.test(k) && v !== 0)
    .map(([k]) => k.slice(5).replace(/_/g, " ").toUpperCase());
  text($("live-faults"), faults.length ? `in force: ${faults.join(", ")}` : "");
  $("live-faults").hidden = faults.length === 0;
  if (replay && m.station === replay.station) {
    const scrub = $<HTMLInputElement>("replay-scrub");
    if (document.activeElement !== scrub) scrub.value = String(m.time_s);
    text($("replay-time"), `${m.time_s.toFixed(1)} / ${replay.duration_s.toFixed(1)} s`);
    // a replay that no longer re-simulates what was recorded says so, in words
    if (m.checkpoint_mismatch) showReplayExactness(
      "This replay has left the recording: from here it no longer shows what the trainee had " +
      "(recorded with another build or other machine data).");
  }
  const now = performance.now();
  if (now >= nextPlotDraw || m.held) {
    nextPlotDraw = now + kPlotDraw_ms;
    plots?.draw(selected);
  }
  if (viewOn()) view?.update(m);  // drawn in this same frame
}

// the trainee's cab view as the station draws it, a few times a second
function showPicture(m: PictureMessage) {
  if (m.station !== selected) return;
  const img = $<HTMLImageElement>("cab-picture");
  img.src = `data:image/jpeg;base64,${m.jpeg}`;
  img.dataset.frames = String(Number(img.dataset.frames ?? "0") + 1);
  img.dataset.time = String(m.time_s);
  text($("cab-caption"), `${m.width}×${m.height}, t ${m.time_s.toFixed(1)} s`);
  $("cab-figure").hidden = false;
}

function showReplayExactness(note: string) {
  text($("replay-exactness"), note);
  $("replay-exactness").hidden = note === "";
}

function showEvent(e: EventMessage) {
  if (e.kind === "attempt_end") loadRecords();  // the records table holds every station's attempts
  if (selected && e.station !== selected) return;
  const li = document.createElement("li");
  text(li, `${e.time_s.toFixed(1)} s  ${e.station}  ${e.words}`);
  li.className = `event-${e.kind}`;
  $("events").prepend(li);
}

function connect() {
  socket = new WebSocket(`${location.protocol === "https:" ? "wss" : "ws"}://${location.host}/api/live`);
  socket.onmessage = (message) => {
    const m = JSON.parse(message.data) as LiveMessage;
    if (m.type === "stations") showStations(m.stations);
    else if (m.type === "state") keepState(m);
    else if (m.type === "scene") {
      machineOf.set(m.station, m.machine);
      if (m.station === selected) view?.setScene(m);
    }
    else if (m.type === "bulk") {
      if (m.station === selected && viewOn() && view) { view.setBulk(m); $("view3d").dataset.bulk = String(view.bulkQuadsDrawn()); }
    }
    else if (m.type === "event") showEvent(m);
    else if (m.type === "picture") showPicture(m);
  };
  socket.onopen = () => { if (selected) subscribe(); };
  socket.onclose = () => { if (me) setTimeout(connect, 1000); };
}

async function command(kind: string) {
  const body: Record<string, unknown> = { kind };
  if (kind === "start") {
    body.exercise = $<HTMLSelectElement>("exercise").value;
    body.trainee = $<HTMLSelectElement>("trainee").value;
    body.autopilot = $<HTMLInputElement>("autopilot").checked;
    const route = $<HTMLSelectElement>("start-route").value;
    if (route) { body.route = route; body.exercise = ""; }  // the trainee's next stage of it
    const team = $<HTMLSelectElement>("start-team").value;
    if (team) { body.team = team; body.role = $<HTMLSelectElement>("start-role").value; body.exercise = ""; }
  }
  const result = $("command-result");
  text(result, `${kind}…`);
  const r = await api(`/api/stations/${encodeURIComponent(selected)}/command`, "POST", body);
  result.className = r.status === 200 ? "" : "refused";
  const said = exercisesByTitle(r.status === 200 ? r.data.message : r.data?.error ?? r.data?.message ?? "");
  text(result, r.status === 200 ? `${kind.replace(/-/g, " ")}: ${said}` : `${kind.replace(/-/g, " ")} refused (${r.status}): ${said}`);
}

// hold, resume or stop every running member of the selected station's team session
let selectedTeam = "";
async function teamCommand(kind: string) {
  const result = $("command-result");
  text(result, `team ${kind}…`);
  const r = await api(`/api/teams/${encodeURIComponent(selectedTeam)}/command`, "POST", { kind });
  result.className = r.status === 200 ? "" : "refused";
  const each = (r.data?.stations ?? []).map((x: { station: string; ok: boolean; message: string }) =>
    `${x.station} ${x.ok ? "done" : x.message}`).join(", ");
  text(result, r.status === 200 ? `team ${teamWords(selectedTeam)} ${kind}: ${each}` :
    `team ${kind} refused (${r.status}): ${r.data?.error ?? each}`);
}

async function replayAction(body: Record<string, unknown>) {
  if (!replay) return;
  const r = await api(`/api/replays/${replay.replay}`, "POST", body);
  if (r.status !== 200) text($("replay-time"), `${body.action}: ${r.data?.error ?? r.status}`);
}

// an attempt, or a team session's every member together on the session's clock
async function openReplay(which: { attempt: number } | { session: string }, at_s = 0) {
  const r = await api("/api/replays", "POST", which);
  if (r.status !== 201) { text($("replay-result"), r.data?.error ?? `error ${r.status}`); return; }
  replay = r.data as ReplayInfo;
  text($("replay-title"), replay.session !== undefined
    ? `team session ${replay.session}: ` + (replay.members ?? []).map((m) =>
      `${m.role} (attempt ${m.attempt}, ${m.trainee}${m.start_s >= 0.05 ? `, from ${m.start_s.toFixed(1)} s` : ""})`).join(", ")
    : `attempt ${replay.attempt}: ${exerciseTitle(replay.exercise)}, ${replay.trainee}`);
  showReplayExactness(replay.exact ? "" : replay.note);
  $("takeover-row").hidden = replay.session !== undefined;  // a member is taken over from its own attempt's replay
  const scrub = $<HTMLInputElement>("replay-scrub");
  scrub.max = String(replay.duration_s);
  scrub.value = "0";
  const list = $("replay-events");
  list.replaceChildren();
  for (const e of replay.events) {
    const li = document.createElement("li");
    text(li, `${e.at_s.toFixed(1)} s  ${e.text}`);
    li.addEventListener("click", () => replayAction({ action: "seek", at_s: Math.max(0, e.at_s - 3) }));
    list.appendChild(li);
  }
  if (!socket) connect();
  select(replay.station);
  await replayAction({ action: "seek", at_s });
  if (at_s > 0) $("replay-panel").scrollIntoView();
}

// The station's indicators as the trainee's HUD shows them (the looks' hud lines: label, unit, decimals,
// lamps lit, words), for its machine.
const machineOf = new Map<string, string>();  // station -> machine kind, from its scene
function hudText(indicators: Record<string, number>, machine: string): string {
  const parts: string[] = [];
  const items = (looks?.hud ?? [])
    .filter((h) => indicators[h.indicator] !== undefined && (!h.machines.length || h.machines.includes(machine)) &&
      !h.except.includes(machine));
  for (const h of items) {
    const v = indicators[h.indicator];
    if (h.shown_while && !((indicators[h.shown_while] ?? 0) > 0.5)) continue;
    if (h.lamp) { if (v > 0.5) parts.push(h.label); continue; }
    if (h.words.length) { parts.push(`${h.label} ${h.words[Math.round(v) - h.words_from] ?? "?"}`); continue; }
    parts.push(`${h.label} ${(v * h.scale).toFixed(h.decimals)}${h.unit ? ` ${h.unit}` : ""}`);
  }
  return parts.join("   ");
}

// One attempt as a debrief: what it was, how it ended, what happened when, and its figures in words.
function showDebrief(d: { id: number; trainee: string; exercise: string; outcome: string; score: number | null;
  events: AttemptEvent[]; figures: { name: string; label: string; text: string; about: string }[];
  deductions: { reason: string; skill: string; count: number; points: number }[]; recording?: string } | null) {
  const box = $("attempt-detail");
  box.replaceChildren();
  if (!d) return;
  const head = document.createElement("h3");
  text(head, `Attempt ${d.id}: ${d.trainee} on ${exerciseTitle(d.exercise)}, ${d.outcome}${d.score === null ? "" : `, score ${d.score.toFixed(1)}`}`);
  box.append(head);
  // what the score took off and why
  if (d.deductions.length) {
    const off = document.createElement("p");
    off.className = "deductions";
    text(off, "Taken off: " + d.deductions.map((x) =>
      `${x.reason}${x.count > 1 ? ` ×${x.count}` : ""} −${Number(x.points.toPrecision(3))} (${x.skill})`).join("; "));
    box.append(off);
  } else if (d.score !== null && d.score >= 100) {
    const none = document.createElement("p");
    text(none, "Nothing taken off.");
    box.append(none);
  }
  // what happened when, each a link to that moment in the replay (instructors; 3 s before it)
  const happened = document.createElement("ul");
  for (const e of d.events) {
    const li = document.createElement("li");
    if (d.recording !== undefined) {
      const go = document.createElement("button");
      go.type = "button";
      go.className = "link";
      text(go, `${e.at_s.toFixed(1)} s`);
      go.title = "replay from 3 s before";
      go.addEventListener("click", () => openReplay({ attempt: d.id }, Math.max(0, e.at_s - 3)));
      li.append(go, `: ${e.text}`);
    } else {
      text(li, `${e.at_s.toFixed(1)} s: ${e.text}`);
    }
    happened.append(li);
  }
  if (d.events.length) box.append(happened);
  const figures = document.createElement("table");
  figures.className = "figures";
  for (const f of d.figures) {
    const tr = document.createElement("tr");
    const th = document.createElement("th"), td = document.createElement("td");
    text(th, f.label);
    text(td, f.text);
    th.title = f.about;
    tr.dataset.figure = f.name;
    tr.append(th, td);
    figures.append(tr);
  }
  box.append(figures);
  if (d.recording) {
    const p = document.createElement("p");
    p.className = "hint";
    text(p, `recording: ${d.recording}`);
    box.append(p);
  }
}

// when an attempt started, in the browser's own date and time format; how long it took (a running one: "")
function startedText(at: string): string {
  const when = new Date(at);
  return Number.isNaN(when.getTime()) ? at : when.toLocaleString(undefined, { dateStyle: "medium", timeStyle: "short" });
}
function durationText(started: string, ended: string): string {
  const s = (Date.parse(ended) - Date.parse(started)) / 1000;
  if (!started || !ended || !Number.isFinite(s) || s < 0) return "";
  return s < 60 ? `${s.toFixed(0)} s` : `${Math.floor(s / 60)} min ${Math.round(s % 60)} s`;
}

// The results table: every attempt the account may see, filtered and sorted as the instructor asks (a
// header's button sorts by it, again reverses), a row opening the attempt's debrief.
let attemptItems: AttemptItem[] = [];
const attemptSort = { column: 0, descending: true };
function attemptCells(a: AttemptItem): (string | number)[] {
  // a team session's member: its role and session beside its exercise
  const exercise = a.team ? `${exerciseTitle(a.exercise)} (${a.team_role} of ${a.team_session})` : exerciseTitle(a.exercise);
  return [a.id, a.trainee, exercise, a.outcome, a.score === null ? "" : a.score.toFixed(1), a.moves,
    a.started_at ? startedText(a.started_at) : "", durationText(a.started_at, a.ended_at),
    a.autopilot ? "autopilot" : "trainee", a.parent === null ? "" : `attempt ${a.parent}`,
    a.exercise_version ? a.exercise_version.slice(0, 8) : ""];
}
// what each column sorts by: numbers as numbers, times as times
function attemptKey(a: AttemptItem, column: number): string | number {
  switch (column) {
    case 0: return a.id;
    case 4: return a.score ?? -1;
    case 5: return a.moves;
    case 6: return a.started_at;
    case 7: return (Date.parse(a.ended_at) - Date.parse(a.started_at)) || 0;
    case 9: return a.parent ?? 0;
    default: return String(attemptCells(a)[column]);
  }
}
function fillFilter(id: string, values: [string, string][]) {
  const select = $<HTMLSelectElement>(id), kept = select.value;
  select.replaceChildren(new Option("all", ""), ...values.map(([value, label]) => new Option(label, value)));
  if (values.some(([value]) => value === kept)) select.value = kept;
}
function showAttempts() {
  const trainee = $<HTMLSelectElement>("filter-trainee").value, exercise = $<HTMLSelectElement>("filter-exercise").value;
  const outcome = $<HTMLSelectElement>("filter-outcome").value, driver = $<HTMLSelectElement>("filter-driver").value;
  const from = $<HTMLInputElement>("filter-from").value;  // yyyy-mm-dd, the browser's day
  const shown = attemptItems.filter((a) => (!trainee || a.trainee === trainee) && (!exercise || a.exercise === exercise) &&
    (!outcome || a.outcome === outcome) && (!driver || (driver === "autopilot") === a.autopilot) &&
    (!from || (a.started_at !== "" && new Date(a.started_at) >= new Date(`${from}T00:00`))));
  const { column, descending } = attemptSort;
  shown.sort((x, y) => {
    const a = attemptKey(x, column), b = attemptKey(y, column);
    const order = typeof a === "number" && typeof b === "number" ? a - b : String(a).localeCompare(String(b));
    return (descending ? -order : order) || y.id - x.id;
  });
  const body = $("attempts").querySelector("tbody")!;
  body.replaceChildren();
  for (const a of shown) {
    const row = document.createElement("tr");
    for (const v of attemptCells(a)) { const td = document.createElement("td"); text(td, v); row.appendChild(td); }
    row.tabIndex = 0;
    const open = async () => {
      const detail = await api(`/api/attempts/${a.id}`);
      showDebrief(detail.data);
      $("attempt-actions").hidden = me?.role === "trainee";
      $("open-replay").dataset.attempt = String(a.id);
      $("open-session-replay").hidden = !a.team_session;
      $("open-session-replay").dataset.session = a.team_session;
    };
    row.addEventListener("click", open);
    row.addEventListener("keydown", (e) => { if (e.key === "Enter") open(); });
    body.appendChild(row);
  }
  $("attempts").querySelectorAll("thead th").forEach((th, k) =>
    th.setAttribute("aria-sort", k !== column ? "none" : descending ? "descending" : "ascending"));
  text($("attempts-shown"), `${shown.length} of ${attemptItems.length} attempts`);
}

async function loadRecords() {
  const latest = latestCall("records");
  const [attempts, exercises] = await Promise.all([api("/api/attempts"), api("/api/exercises")]);
  if (!latest()) return;
  exerciseCards = exercises.data ?? [];
  attemptItems = attempts.data ?? [];
  fillFilter("filter-trainee", [...new Set(attemptItems.map((a) => a.trainee))].sort().map((t) => [t, t]));
  fillFilter("filter-exercise", [...new Set(attemptItems.map((a) => a.exercise))]
    .map((e): [string, string] => [e, exerciseTitle(e)]).sort((x, y) => x[1].localeCompare(y[1])));
  fillFilter("filter-outcome", [...new Set(attemptItems.map((a) => a.outcome))].sort().map((o) => [o, o]));
  showAttempts();
  if (!me || me.role === "trainee") return;
  const trainees = await api("/api/trainees");
  if (!latest()) return;
  for (const id of ["trainee", "takeover-trainee", "rename-trainee", "progress-trainee", "compare-with"]) {
    const select = $<HTMLSelectElement>(id);
    const kept = select.value;
    select.replaceChildren();
    if (id === "compare-with") select.add(new Option("nobody", ""));
    for (const t of trainees.data ?? []) select.add(new Option(`${t.id} (${t.name})`, t.id));
    if ([...select.options].some((o) => o.value === kept)) select.value = kept;
  }
  showTeamStart();  // its trainees' choices
  for (const id of ["exercise", "design-base"]) fillExerciseSelect($<HTMLSelectElement>(id));
  showExerciseAbout();
  await loadClass();
}

// The commands an instructor gives a station, from the console's table (names, labels, values with ranges):
// every command but the session's (drawn with its exercise, trainee, route and team fields) gets its button here,
// with a field for each value it takes.
let commandTable: CommandInfo[] = [];
const COMMAND_ROWS: Record<string, string> = { weather: "commands-weather", fault: "commands-fault",
  stop: "commands-fault", restart: "commands-fault", sound: "commands-sound", signal: "commands-signal" };
function drawCommands(table: CommandTable) {
  const commands = table.commands;
  commandTable = commands;
  for (const id of new Set(Object.values(COMMAND_ROWS)))
    for (const e of [...$(id).querySelectorAll(".command")]) e.remove();
  for (const c of commands) {
    const row = COMMAND_ROWS[c.group];
    if (!row) continue;
    if (c.values.some((v) => v.hand_signal)) {  // a button for each hand signal, the signaller drawn giving it
      for (const s of table.signals) $(row).append(signalButton(c.name, s), " ");
      continue;
    }
    const box = document.createElement("span");
    box.className = "command";
    box.dataset.name = c.name;
    c.values.forEach((v, k) => {
      const input = document.createElement("input");
      input.id = `command-${c.name}-${k}`;
      if (v.words) {
        input.type = "text";
        input.maxLength = v.max;
      } else {
        input.type = "number";
        input.min = String(v.min);
        input.max = String(v.max);
        input.step = String(v.step);
        input.value = String(v.initial);
      }
      const label = document.createElement("label");
      label.append(`${v.what} `, input, v.unit ? ` ${v.unit === "deg" ? "°" : v.unit}` : "");
      box.append(label, " ");
    });
    const button = document.createElement("button");
    button.dataset.kind = c.name;
    button.textContent = c.label;
    if (c.group === "stop") button.className = "emergency";
    button.addEventListener("click", () => command([c.name, ...c.values.map((_, k) =>
      $<HTMLInputElement>(`command-${c.name}-${k}`).value)].join(":")));
    box.append(button);
    $(row).append(box, " ");
  }
  setEventLabels(Object.fromEntries(commands.filter((c) => c.file_name)
    .map((c) => [c.file_name, c.label.toLowerCase()])));
}

// A hand signal's button: the signaller as the cab shows them (the strokes' metres, y up), and the words.
function signalButton(kind: string, s: HandSignal): HTMLElement {
  const svgNs = "http://www.w3.org/2000/svg";
  const svg = document.createElementNS(svgNs, "svg");
  svg.setAttribute("viewBox", "-1.2 -1.95 2.4 2.35");  // the cab panel's extent, y flipped
  svg.setAttribute("aria-hidden", "true");
  for (const stroke of s.strokes) {
    const line = document.createElementNS(svgNs, "polyline");
    const points: string[] = [];
    for (let k = 0; k + 1 < stroke.length; k += 2) points.push(`${stroke[k]},${-stroke[k + 1]}`);
    line.setAttribute("points", points.join(" "));
    svg.append(line);
  }
  const button = document.createElement("button");
  button.className = "command signal";
  button.dataset.name = kind;
  button.dataset.signal = s.name;
  button.title = s.how;
  const words = document.createElement("span");
  words.textContent = s.words;
  button.append(svg, words);
  button.addEventListener("click", () => command(`${kind}:${s.name}`));
  return button;
}

// The exercises as people pick them: by title, grouped by machine, with what each asks of the trainee.
let exerciseCards: ExerciseCard[] = [];
// a route stage's, a team's or a team role's id in words ("single_lift": "single lift")
const stageWords = (id: string) => id.replace(/_/g, " ");
const teamWords = stageWords;
const exerciseTitle = (name: string) => exerciseCards.find((e) => e.name === name)?.title ?? name;
const machineTitle = (kind: string) => exerciseCards.find((e) => e.machine === kind)?.machine_title ?? kind;
// The fault buttons of the parts the selected station's machine has (its type's faults; a machine no exercise
// card names: every button, the station refusing what it lacks).
function showFaultButtons(machine: string) {
  const faults = exerciseCards.find((e) => e.machine === machine)?.faults;
  for (const c of commandTable.filter((c) => c.group === "fault")) {
    const box = document.querySelector<HTMLElement>(`.command[data-name="${c.name}"]`);
    if (!box) continue;
    // clearing faults: where the machine has some
    box.hidden = faults !== undefined && (c.name === "clear-faults" ? faults.length === 0 : !faults.includes(c.name));
  }
}
function fillExerciseSelect(select: HTMLSelectElement) {
  const kept = select.value;
  select.replaceChildren();
  const machines = [...new Set(exerciseCards.map((e) => e.machine))];
  for (const machine of machines) {
    const group = document.createElement("optgroup");
    group.label = machineTitle(machine);
    for (const e of exerciseCards.filter((x) => x.machine === machine))
      group.append(new Option(e.title ?? e.name, e.name));
    select.append(group);
  }
  if (exerciseCards.some((e) => e.name === kept)) select.value = kept;
}
function showExerciseAbout() {
  // with a team chosen, what each of its roles runs (the exercise chosen is not run then)
  const team = teams.find((t) => t.name === $<HTMLSelectElement>("start-team").value);
  if (team?.roles) {
    text($("exercise-about"), `Team ${teamWords(team.name)}: ${team.roles.map((r) =>
      `${teamWords(r.role)}, ${exerciseTitle(r.exercise)}`).join("; ")}.`);
    return;
  }
  const e = exerciseCards.find((x) => x.name === $<HTMLSelectElement>("exercise").value);
  text($("exercise-about"), !e ? "" : e.error ? `cannot be started: ${e.error}` : !e.title ? "" :
    `${e.objective} ${e.difficulty ? e.difficulty[0].toUpperCase() + e.difficulty.slice(1) : ""}, about ${e.expected_min} min.`);
}

let routes: RouteInfo[] = [];

// A trainee's progress on each route they are enrolled in: a table of stages with their state.
async function loadProgress() {
  const trainee = me?.role === "trainee" ? me.trainee : $<HTMLSelectElement>("progress-trainee").value;
  const box = $("progress");
  const latest = latestCall("progress");
  if (!trainee) { box.replaceChildren(); return; }
  const r = await api(`/api/progress?trainee=${encodeURIComponent(trainee)}`);
  if (!latest()) return;
  box.replaceChildren();
  if (r.status !== 200) { text(box, r.data?.error ?? `error ${r.status}`); return; }
  const stageSelect = $<HTMLSelectElement>("decision-stage");
  stageSelect.replaceChildren();
  const progress = r.data as Progress;
  for (const enrolled of progress.routes) {
    const route = routes.find((x) => x.id === enrolled.route);
    const title = document.createElement("h3");
    text(title, `${route?.name ?? enrolled.route}: ${enrolled.complete ? "complete" : enrolled.next ? `next ${stageWords(enrolled.next)}` :
      "no stage open: an instructor decides"}`);
    const table = document.createElement("table");
    table.className = "progress";
    table.dataset.route = enrolled.route;
    const head = document.createElement("tr");
    for (const h of ["goal", "stage", "exercise", "state", "passes", "attempts", "best"]) {
      const th = document.createElement("th"); text(th, h); head.appendChild(th);
    }
    table.appendChild(head);
    for (const sp of enrolled.stages) {
      const stage = route?.stages.find((x) => x.id === sp.stage);
      const row = document.createElement("tr");
      row.dataset.stage = sp.stage;
      row.className = `state-${sp.state}`;
      for (const v of [stage?.goal ?? "", stageWords(sp.stage), exerciseTitle(stage?.exercise ?? ""),
        sp.state + (sp.signed_off ? " (signed off)" : ""),
        `${sp.passes}/${stage?.repetitions ?? "?"}`, `${sp.attempts}/${sp.attempts_allowed}`,
        sp.best_score === null ? "" : sp.best_score.toFixed(1)]) {
        const td = document.createElement("td"); text(td, v); row.appendChild(td);
      }
      table.appendChild(row);
      stageSelect.add(new Option(`${route?.name ?? enrolled.route}: ${stageWords(sp.stage)}`, `${enrolled.route}/${sp.stage}`));
    }
    box.append(title, table);
  }
  if (progress.routes.length === 0) text(box, `${trainee} is enrolled in no route`);
  await loadEvolution(trainee);
}

const number = (v: number | null | undefined, digits = 1) => v === null || v === undefined ? "" : v.toFixed(digits);
function row(values: (string | number)[]): HTMLTableRowElement {
  const tr = document.createElement("tr");
  for (const v of values) { const td = document.createElement("td"); text(td, v); tr.appendChild(td); }
  return tr;
}

// A trainee's evolution over their finished attempts: the score and the three skills, or any one stored figure
// (with another trainee's for comparison); where their best on it stands in the cohort; a comparison table.
let evolutionPlot: uPlot | null = null;
async function loadEvolution(trainee: string) {
  const latest = latestCall("evolution");
  const query = `trainee=${encodeURIComponent(trainee)}`;
  $<HTMLAnchorElement>("csv").href = `/api/attempts.csv?${query}`;
  $<HTMLAnchorElement>("report-html").href = `/api/reports/trainee?${query}`;
  $<HTMLAnchorElement>("report-pdf").href = `/api/reports/trainee.pdf?${query}`;
  const figure = $<HTMLSelectElement>("evolution-figure");
  const other = me?.role === "trainee" ? "" : $<HTMLSelectElement>("compare-with").value;
  const [r, o] = await Promise.all([api(`/api/evolution?${query}`),
    other ? api(`/api/evolution?trainee=${encodeURIComponent(other)}`) : Promise.resolve(null)]);
  if (!latest()) return;
  evolutionPlot?.destroy();
  evolutionPlot = null;
  const body = $("cohort").querySelector("tbody")!;
  body.replaceChildren();
  if (r.status !== 200) return;
  const attempts = (r.data as Evolution).attempts;
  const theirs = o?.status === 200 ? (o.data as Evolution).attempts : [];
  // the figures this trainee has: the selector keeps the one chosen
  const chosen = figure.value;
  const words = (r.data as Evolution).figures;
  const wordsOf = (name: string): FigureWords => words[name] ?? { label: name, unit: "", scale: 1, about: "" };
  const labelOf = (name: string) => { const w = wordsOf(name); return w.unit ? `${w.label} [${w.unit}]` : w.label; };
  const names = [...new Set(attempts.flatMap((a) => Object.keys(a.metrics)))]
    .sort((x, y) => labelOf(x).localeCompare(labelOf(y)));
  figure.replaceChildren(new Option("score and skills", ""), new Option("score", "score"),
    ...names.map((n) => new Option(labelOf(n), n)));
  figure.value = names.includes(chosen) || chosen === "score" ? chosen : "";
  const n = Math.max(attempts.length, theirs.length);
  const index = Array.from({ length: n }, (_, k) => k + 1);
  // each figure in the unit people read it in
  const valueOf = (a: EvolutionAttempt | undefined, f: string) => {
    const stored = a === undefined ? undefined : f === "score" ? a.score : a.metrics[f];
    return stored === undefined ? null : stored * wordsOf(f).scale;
  };
  let series: uPlot.Series[], data: (number | null)[][];
  if (figure.value === "") {
    series = [{ label: "score", stroke: "#1a237e", width: 2 }, { label: "safety", stroke: "#c62828" },
      { label: "precision", stroke: "#2e7d32" }, { label: "productivity", stroke: "#ef6c00" }];
    data = [index.map((k) => attempts[k - 1]?.score ?? null),
      ...["safety", "precision", "productivity"].map((s) => index.map((k) => attempts[k - 1]?.skills[s] ?? null))];
  } else {
    series = [{ label: `${trainee}: ${labelOf(figure.value)}`, stroke: "#1a237e", width: 2 }];
    data = [index.map((k) => valueOf(attempts[k - 1], figure.value))];
    if (other) {
      series.push({ label: other, stroke: "#ef6c00", width: 2, dash: [6, 4] });
      data.push(index.map((k) => valueOf(theirs[k - 1], figure.value)));
    }
  }
  const fixedRange = figure.value === "" || figure.value === "score" || figure.value.startsWith("skill_");
  evolutionPlot = new uPlot({ width: 640, height: 220,
    scales: { x: { time: false }, y: fixedRange ? { range: [0, 100] } : { auto: true } },
    axes: [{ incrs: [1, 2, 5, 10, 20, 50, 100] }, {}], series: [{ label: "attempt" }, ...series] },
    [index, ...data] as uPlot.AlignedData, $("evolution"));
  $("evolution").dataset.attempts = String(attempts.length);
  $("evolution").dataset.figure = figure.value;
  const shown = figure.value === "" ? "score" : figure.value;
  for (const c of (r.data as Evolution).standings) {
    if (c.figure !== shown) continue;
    const tr = row([exerciseTitle(c.exercise), c.exercise_version.slice(0, 8), c.label, c.best_text,
      c.higher_better ? "higher" : "lower", c.trainees, c.place_words]);
    tr.dataset.exercise = c.exercise;
    body.appendChild(tr);
  }
  await loadComparison(trainee, other, shown);
}

// Two trainees' bests side by side on one figure (or on every figure, for the score and skills view).
async function loadComparison(a: string, b: string, figure: string) {
  const table = $("comparison");
  table.hidden = !b;
  const body = table.querySelector("tbody")!;
  const latest = latestCall("comparison");
  if (!b) { body.replaceChildren(); return; }
  const r = await api(`/api/compare?a=${encodeURIComponent(a)}&b=${encodeURIComponent(b)}`);
  if (!latest()) return;
  body.replaceChildren();
  text($("compare-a"), a);
  text($("compare-b"), b);
  if (r.status !== 200) { body.appendChild(row([r.data?.error ?? `error ${r.status}`])); return; }
  for (const c of r.data.figures as { exercise: string; exercise_version: string; figure: string; label: string;
    higher_better: boolean; a: number | null; b: number | null; a_text: string; b_text: string }[]) {
    if (figure !== "score" ? c.figure !== figure : !(c.figure === "score" || c.figure.startsWith("skill_"))) continue;
    const ahead = c.a === null || c.b === null ? "" : c.a === c.b ? "tie" :
      (c.a > c.b) === c.higher_better ? a : b;
    body.appendChild(row([exerciseTitle(c.exercise), c.exercise_version.slice(0, 8), c.label, c.a_text, c.b_text, ahead]));
  }
}

// Every trainee's line: attempts, passes, best and recent score, trend, skills, routes.
async function loadClass() {
  const body = $("class").querySelector("tbody")!;
  const latest = latestCall("class");
  const x = await api("/api/xapi");
  if (x.status === 200)
    text($("xapi-status"), `xAPI statements: ${x.data.queued} queued, ${x.data.sent} sent, ${x.data.rejected} rejected` +
      (x.data.lrs ? ` (to ${x.data.lrs}${x.data.last ? `; last: ${x.data.last}` : ""})` : " (no LRS configured: harboursim console --lrs URL)"));
  const r = await api("/api/class");
  if (!latest() || r.status !== 200) return;
  body.replaceChildren();
  for (const t of r.data) {
    const routesText = t.routes.map((x: { route: string; passed: number; stages: number; complete: boolean; next: string | null }) =>
      `${routes.find((r) => r.id === x.route)?.name ?? x.route} ${x.passed}/${x.stages}` +
      `${x.complete ? " done" : x.next ? ` → ${stageWords(x.next)}` : " blocked"}`).join("; ");
    const tr = row([t.trainee, t.name, t.attempts, `${t.passed}/${t.finished}`, number(t.best_score),
      number(t.recent_score), t.trend === null ? "" : (t.trend >= 0 ? "+" : "") + t.trend.toFixed(1),
      number(t.recent_skills.safety), number(t.recent_skills.precision), number(t.recent_skills.productivity), routesText]);
    tr.dataset.trainee = t.trainee;
    tr.addEventListener("click", () => {
      $<HTMLSelectElement>("progress-trainee").value = t.trainee;
      loadProgress();
      $("routes-panel").scrollIntoView();
    });
    body.appendChild(tr);
  }
}

// The team sessions a station can join as one of their roles (its exercise then the role's).

let teams: Team[] = [];
async function loadTeams() {
  teams = (await api("/api/teams")).data ?? [];
  const select = $<HTMLSelectElement>("start-team");
  select.replaceChildren(new Option("none: alone", ""));
  for (const t of teams) if (t.roles) select.add(new Option(teamWords(t.name), t.name));
  showTeamRoles();
}
function showTeamRoles() {
  const team = teams.find((t) => t.name === $<HTMLSelectElement>("start-team").value);
  const select = $<HTMLSelectElement>("start-role");
  select.replaceChildren();
  for (const r of team?.roles ?? []) select.add(new Option(`${teamWords(r.role)}: ${exerciseTitle(r.exercise)}`, r.role));
  select.disabled = !team;
  // a member runs its role's exercise: the exercise and the route are not chosen then
  $<HTMLSelectElement>("exercise").disabled = !!team;
  $<HTMLSelectElement>("start-route").disabled = !!team;
  showTeamStart();
  showExerciseAbout();
}

// The whole team started as one: a free station and a trainee for each role, one button. The choices made are
// kept while the idle stations change.
function showTeamStart() {
  const team = teams.find((t) => t.name === $<HTMLSelectElement>("start-team").value);
  const box = $("team-start");
  const kept = new Map([...box.querySelectorAll<HTMLSelectElement>("select")].map((s) => [s.id, s.value]));
  box.replaceChildren();
  box.hidden = !team?.roles;
  if (!team?.roles) return;
  box.append("the whole team: ");
  team.roles.forEach((r, k) => {
    const station = document.createElement("select");
    station.id = `team-start-station-${r.role}`;
    station.setAttribute("aria-label", `${teamWords(r.role)}'s station`);
    for (const s of idleStations) station.add(new Option(s, s));
    const keptStation = kept.get(station.id);
    station.value = idleStations.includes(keptStation ?? "") ? keptStation! : idleStations[k] ?? "";
    const trainee = document.createElement("select");
    trainee.id = `team-start-trainee-${r.role}`;
    trainee.setAttribute("aria-label", `${teamWords(r.role)}'s trainee`);
    for (const o of $<HTMLSelectElement>("trainee").options) trainee.add(new Option(o.text, o.value));
    // the one chosen here before while it is still offered, else the panel's trainee
    const keptTrainee = kept.get(trainee.id);
    trainee.value = [...trainee.options].some((o) => o.value === keptTrainee) ? keptTrainee! : $<HTMLSelectElement>("trainee").value;
    const role = document.createElement("span");
    role.append(`${teamWords(r.role)} on `, station, " for ", trainee);
    box.append(role, " ");
  });
  const go = document.createElement("button");
  go.id = "team-start-go";
  go.textContent = "Start the team";
  go.disabled = idleStations.length < team.roles.length;
  go.addEventListener("click", () => startTeam(team));
  box.append(go);
}
async function startTeam(team: Team) {
  const members = (team.roles ?? []).map((r) => ({ role: r.role,
    station: $<HTMLSelectElement>(`team-start-station-${r.role}`).value,
    trainee: $<HTMLSelectElement>(`team-start-trainee-${r.role}`).value }));
  const result = $("command-result");
  text(result, `team ${teamWords(team.name)} start…`);
  const r = await api(`/api/teams/${encodeURIComponent(team.name)}/start`, "POST",
    { members, autopilot: $<HTMLInputElement>("autopilot").checked });
  result.className = r.status === 200 ? "" : "refused";
  const each = (r.data?.stations ?? []).map((x: { station: string; ok: boolean; message: string }) =>
    `${x.station} ${x.ok ? "done" : x.message}`).join(", ");
  text(result, r.status === 200 ? `team ${teamWords(team.name)} started: ${each}` :
    `team start refused (${r.status}): ${r.data?.error ?? each}`);
}

// The routes (the centre's and the shipped ones) wherever they are chosen.
let routeEditor: RouteEditor | null = null;
async function loadRoutes() {
  routes = (await api("/api/routes")).data ?? [];
  for (const id of ["route", "start-route"]) {
    const select = $<HTMLSelectElement>(id), kept = select.value;
    select.replaceChildren();
    if (id === "start-route") select.add(new Option("none: the exercise chosen", ""));
    for (const r of routes) select.add(new Option(id === "route" ? r.name : `${r.name}: next stage`, r.id));
    if ([...select.options].some((o) => o.value === kept)) select.value = kept;
  }
  if (me?.role !== "trainee") await routeEditor?.refresh(routes);
}

// The exercise designer: load an exercise's YAML, check it with the simulator's loader and preview its world,
// save it (a new version).
let designView: View3D | null = null;
let looks: Looks | null = null;
let designForms: DesignerForms | null = null;
let designTimer = 0;
let designRequest = 0;  // the latest check or save: an earlier check's late answer is dropped
// a check (and preview) shortly after the design last changed
// (the verdict shown is of the text before: it says so at once)
const checkSoon = (ms: number) => {
  clearTimeout(designTimer);
  designTimer = window.setTimeout(() => designerAction("check"), ms);
  $("design-result").className = "";
  text($("design-result"), "changed: checking…");
};
async function designerAction(action: "check" | "save") {
  const result = $("design-result");
  result.className = "";
  text(result, action === "check" ? "checking…" : "saving…");
  clearTimeout(designTimer);  // this text is what is checked (or saved) now
  const request = ++designRequest;
  const r = await api(`/api/designer/${action}`, "POST", { text: $<HTMLTextAreaElement>("design-text").value });
  if (action === "check" && request !== designRequest) return;  // a save's answer is always told
  const ok = r.status === 200 || r.status === 201;
  result.className = ok ? "" : "refused";
  if (!ok) { text(result, `${action} refused (${r.status}): ${r.data?.error}`); return; }
  if (action === "save") {
    text(result, `saved ${r.data.exercise}, version ${r.data.version}`);
    await loadRecords();  // the exercise lists
    await routeEditor?.refresh(routes);
    return;
  }
  text(result, `${r.data.exercise}: valid (version ${r.data.version} when saved)`);
  designForms?.setForm(r.data.form);
  text($("design-summary"), `machine ${r.data.machine}, ${r.data.containers} containers, ${r.data.moves} moves, ` +
    `${r.data.events} scripted events\ntime limit ${r.data.time_limit_s} s, pass ${r.data.pass_score}, wind ${r.data.wind_mps} m/s`);
  if (!designView && looks) designView = new View3D($("design-view"), $("design-plan"), $("design-plan-labels"), looks);
  designView?.setScene(r.data.scene as SceneMessage);
  designView?.update(r.data.state);
  if (r.data.bulk) designView?.setBulk(r.data.bulk as BulkMessage);
  $("design-view").dataset.bulk = String(designView?.bulkQuadsDrawn() ?? 0);
  $("design-view").dataset.entities = String(designView?.visibleEntities() ?? 0);
  $("design-view").dataset.jacks = JSON.stringify(designView?.jackEnds() ?? []);
}

async function enter(who: Me) {
  me = who;
  $("login-view").hidden = true;
  $("main-view").hidden = false;
  $("logout").hidden = false;
  text($("who"), `${who.name} (${who.role})`);
  document.body.dataset.role = who.role;  // a signaller's page: the stations, their views and the signals only
  const signaller = who.role === "signaller";
  for (const e of document.querySelectorAll<HTMLElement>(".instructor-only"))
    e.hidden = who.role === "trainee" || e.id === "control-panel" || e.id === "attempt-actions" ||
      (signaller && e.id !== "stations-panel");
  for (const id of ["records-panel", "routes-panel"]) $(id).hidden = signaller;
  if (!signaller) {
    await loadRecords();
    await loadRoutes();
    await loadProgress();
  }
  if (who.role === "trainee") return;
  if (!signaller) await loadTeams();
  const commandsReply = await api("/api/commands");
  if (commandsReply.status === 200) drawCommands(commandsReply.data as CommandTable);
  plots = new TelemetryPlots($("plot"));
  const looksReply = await api("/api/looks");
  if (looksReply.status === 200) {
    looks = looksReply.data as Looks;
    view = new View3D($("view3d"), $("plan"), $("plan-labels"), looks);
    $<HTMLInputElement>("view-light").checked = view.isLight();  // light where drawn in software
  }
  (window as unknown as { harbourView: View3D | null }).harbourView = view;  // for the browser tests
  connect();
}

function wire() {
  $("login-form").addEventListener("submit", async (e) => {
    e.preventDefault();
    const r = await api("/api/login", "POST", { name: $<HTMLInputElement>("login-name").value,
      password: $<HTMLInputElement>("login-password").value });
    if (r.status === 200) enter(r.data);
    else text($("login-error"), r.data?.error ?? `error ${r.status}`);
  });
  $("logout").addEventListener("click", async () => {
    await api("/api/logout", "POST", {});
    me = null;
    socket?.close();
    location.reload();
  });
  for (const b of document.querySelectorAll<HTMLButtonElement>("button[data-kind]"))
    b.addEventListener("click", () => command(b.dataset.kind!));
  for (const b of document.querySelectorAll<HTMLButtonElement>("button[data-team-kind]"))
    b.addEventListener("click", () => teamCommand(b.dataset.teamKind!));
  const value = (id: string) => $<HTMLInputElement>(id).value;
  $("view-on").addEventListener("change", () => { $("views").hidden = !viewOn(); if (selected) subscribe(); });
  $("view-light").addEventListener("change", () => view?.setLight($<HTMLInputElement>("view-light").checked));
  $("view-ground").addEventListener("click", () => view?.fromTheGround());
  $("start-team").addEventListener("change", showTeamRoles);
  $("exercise").addEventListener("change", showExerciseAbout);
  // the theme: the one picked here last, else the system's
  const dark = () => document.documentElement.dataset.theme === "dark" ||
    (!document.documentElement.dataset.theme && matchMedia("(prefers-color-scheme: dark)").matches);
  const showTheme = () => text($("theme"), dark() ? "light theme" : "dark theme");
  const picked = localStorage.getItem("theme");
  if (picked === "dark" || picked === "light") document.documentElement.dataset.theme = picked;
  showTheme();
  $("theme").addEventListener("click", () => {
    const next = dark() ? "light" : "dark";
    document.documentElement.dataset.theme = next;
    localStorage.setItem("theme", next);
    showTheme();
  });
  for (const id of ["filter-trainee", "filter-exercise", "filter-outcome", "filter-driver", "filter-from"])
    $(id).addEventListener("change", showAttempts);
  $("attempts").querySelectorAll("thead th").forEach((th, k) => {
    const button = document.createElement("button");
    button.type = "button";
    button.className = "sort";
    button.append(...th.childNodes);
    th.append(button);
    button.addEventListener("click", () => {
      attemptSort.descending = attemptSort.column === k ? !attemptSort.descending : k === 0 || k === 4 || k === 6;
      attemptSort.column = k;
      showAttempts();
    });
  });
  $("open-replay").addEventListener("click", () => openReplay({ attempt: Number($("open-replay").dataset.attempt) }));
  $("open-session-replay").addEventListener("click", () =>
    openReplay({ session: $("open-session-replay").dataset.session ?? "" }));
  const speed = () => Number($<HTMLSelectElement>("replay-speed").value);
  $("replay-play").addEventListener("click", () => replayAction({ action: "play", speed: speed() }));
  $("replay-pause").addEventListener("click", () => replayAction({ action: "pause" }));
  $("replay-speed").addEventListener("change", () => replayAction({ action: "play", speed: speed() }));
  $("replay-scrub").addEventListener("change", () =>
    replayAction({ action: "seek", at_s: Number($<HTMLInputElement>("replay-scrub").value) }));
  $("take-over").addEventListener("click", async () => {
    if (!replay) return;
    const station = $<HTMLSelectElement>("takeover-station").value;
    text($("takeover-result"), "taking over…");
    const r = await api(`/api/replays/${replay.replay}`, "POST", { action: "take-over", station,
      trainee: $<HTMLSelectElement>("takeover-trainee").value, autopilot: $<HTMLInputElement>("takeover-autopilot").checked });
    text($("takeover-result"), r.status === 200 ? `${station}: ${r.data.message}` : `refused (${r.status}): ${r.data?.error ?? r.data?.message}`);
    if (r.status === 200) select(station);
  });
  $("replay-close").addEventListener("click", async () => {
    await replayAction({ action: "close" });
    replay = null;
    $("replay-panel").hidden = true;
    $("watch").hidden = true;
    selected = "";
  });
  $("rename-form").addEventListener("submit", async (e) => {
    e.preventDefault();
    const r = await api("/api/trainees", "PATCH", { id: $<HTMLSelectElement>("rename-trainee").value, name: value("rename-name") });
    text($("rename-result"), r.status === 200 ? `${r.data.id} is now ${r.data.name}` : r.data?.error ?? `error ${r.status}`);
    if (r.status === 200) loadRecords();
  });
  $("enrol-form").addEventListener("submit", async (e) => {
    e.preventDefault();
    const r = await api("/api/enrolments", "POST", { trainee: $<HTMLSelectElement>("progress-trainee").value,
      route: $<HTMLSelectElement>("route").value });
    text($("enrol-result"), r.status === 201 ? "enrolled" : r.status === 200 ? "already enrolled" : r.data?.error ?? `error ${r.status}`);
    loadProgress();
    loadClass();
  });
  $("show-progress").addEventListener("click", () => loadProgress());
  $("design-load").addEventListener("click", async () => {
    const name = $<HTMLSelectElement>("design-base").value;
    const r = await api(`/api/designer/source?exercise=${encodeURIComponent(name)}`);
    if (r.status === 200) {
      // a shipped exercise is an example: the centre's copy gets a title of its own (people pick by title,
      // so two alike are refused)
      let source: string = r.data.text;
      const title = parseDocument(source).getIn(["exercise", "about", "title"]);
      if (!r.data.designed && typeof title === "string") {  // the line rewritten, the rest kept as it is
        const taken = new Set(exerciseCards.map((e) => e.title?.toLowerCase()));
        let copy = `${title} (centre copy)`;
        for (let n = 2; taken.has(copy.toLowerCase()); ++n) copy = `${title} (centre copy ${n})`;
        source = source.replace(/^(\s+title:).*$/m, `$1 ${JSON.stringify(copy)}`);
      }
      $<HTMLTextAreaElement>("design-text").value = source;
      designForms?.readSource();
      checkSoon(0);
    }
    text($("design-result"), r.status === 200 ? `loaded ${name}${r.data.designed ? " (designed here)" : " (shipped: save it under a new exercise.name)"}`
      : r.data?.error ?? `error ${r.status}`);
  });
  designForms = new DesignerForms($("design-forms"), $<HTMLTextAreaElement>("design-text"), () => checkSoon(400));
  // the forms follow the text at once (a form edit right after typing edits what was typed); the check waits
  $("design-text").addEventListener("input", () => {
    designForms?.readSource();
    checkSoon(800);
  });
  routeEditor = new RouteEditor(api, loadRoutes);
  $("design-check").addEventListener("click", () => designerAction("check"));
  $("design-save").addEventListener("click", () => designerAction("save"));
  for (const id of ["evolution-figure", "compare-with"])
    $(id).addEventListener("change", () => {
      const trainee = me?.role === "trainee" ? me.trainee : $<HTMLSelectElement>("progress-trainee").value;
      if (trainee) loadEvolution(trainee);
    });
  $("decision-form").addEventListener("submit", async (e) => {
    e.preventDefault();
    const [route, stage] = $<HTMLSelectElement>("decision-stage").value.split("/");
    const r = await api("/api/decisions", "POST", { trainee: $<HTMLSelectElement>("progress-trainee").value, route, stage,
      action: $<HTMLSelectElement>("decision-action").value, reason: value("decision-reason") });
    text($("decision-result"), r.status === 201 ? "recorded" : r.data?.error ?? `error ${r.status}`);
    loadProgress();
    loadClass();
  });
  $("trainee-form").addEventListener("submit", async (e) => {
    e.preventDefault();
    const r = await api("/api/trainees", "POST", { id: value("new-trainee-id"), name: value("new-trainee-name") });
    text($("trainee-result"), r.status === 201 ? `added ${r.data.id}` : r.data?.error ?? `error ${r.status}`);
    if (r.status === 201) loadRecords();
  });
}

async function main() {
  wire();
  const r = await api("/api/me");
  if (r.status === 200) enter(r.data);
  else $("login-view").hidden = false;
}
main();
