// The console's API on its error paths, two consoles commanding one station, and a station process killed
// mid-exercise (lost, its attempt stored). Usage: node console_api.mjs HARBOURSIM DOMAIN
import { Harness, sleep, webSocket, frame } from "./harness.mjs";
import { MESSAGE_OF_TYPE, wireErrors } from "./wire.mjs";
import { randomBytes } from "node:crypto";
import { mkdtempSync } from "node:fs";
import { tmpdir } from "node:os";
import net from "node:net";
import path from "node:path";

const [app, domain] = process.argv.slice(2);
const dir = mkdtempSync(path.join(tmpdir(), "harbour-api-"));
const db = `sqlite3://db=${dir}/records.db`;
const h = new Harness(app);
const check = h.check.bind(h), run = h.run.bind(h), start = h.start.bind(h), until = h.until.bind(h);
const consoleAt = (name) => h.console(db, domain, name);
async function login(base, name, password) {
  const r = await fetch(base + "api/login", { method: "POST", headers: { "Content-Type": "application/json" }, body: JSON.stringify({ name, password }) });
  const cookie = (r.headers.get("set-cookie") ?? "").split(";")[0];
  const body = await r.json();
  return { status: r.status, cookie, csrf: body.csrf };
}
function client(base, who) {
  return async (p, method = "GET", body, headers = {}) => {
    const h = { Cookie: who.cookie, ...headers };
    if (method !== "GET") { h["Content-Type"] ??= "application/json"; h["X-CSRF-Token"] ??= who.csrf; }
    const r = await fetch(base + p, { method, headers: h, body: typeof body === "string" ? body : body && JSON.stringify(body) });
    let data = null;
    try { data = await r.json(); } catch { /* not JSON */ }
    return { status: r.status, data };
  };
}
function raw(port, text) {
  return new Promise((resolve) => {
    const s = net.connect(Number(port), "127.0.0.1", () => s.end(text));
    let got = "";
    s.on("data", (d) => { got += d; });
    s.on("close", () => resolve(got));
    s.on("error", () => resolve(got));
  });
}

try {
  run(["trainees", "add", "carl", "Carl Nyberg", "--db", db]);
  // two finished attempts for the evolution and the cohort (the same autopilot: the same score, a tie)
  run(["trainees", "add", "=dora", "Dora Lind", "--db", db]);
  for (const who of ["carl", "=dora"]) run(["run", "--exercise", "sts_discharge", "--autopilot", "--trainee", who, "--db", db]);
  run(["accounts", "add", "ines", "--role", "instructor", "--db", db], "ines-password\n");
  run(["accounts", "add", "dora", "--role", "trainee", "--trainee", "=dora", "--db", db], "dora-password\n");
  const [baseA, portA] = await consoleAt("console-a");
  const [baseB] = await consoleAt("console-b");
  const station = start(["station", "--serve", "--name", "api-1", "--domain", domain, "--db", db, "--window", "off"]);

  // logins: wrong ones are counted, and the sixth in a minute is refused before the password is checked
  for (let n = 0; n < 5; ++n) check((await login(baseA, "ines", "nope")).status === 401, `wrong password ${n + 1}: 401`);
  check((await login(baseA, "ines", "ines-password")).status === 429, "then even the right one waits: 429");
  const whoB = await login(baseB, "ines", "ines-password");
  check(whoB.status === 200, "console B lets ines in (its own counter)");
  const b = client(baseB, whoB);

  // bad requests change nothing and say why
  const cases = [
    ["not JSON", "api/trainees", "POST", "{ nope", 400],
    ["deeply nested", "api/trainees", "POST", "[".repeat(100) + "]".repeat(100), 400],
    ["a JSON array", "api/trainees", "POST", "[1,2]", 400],
    ["a field of the wrong type", "api/trainees", "POST", { id: 7, name: "x" }, 400],
    ["a field missing", "api/trainees", "POST", { id: "dora" }, 400],
    ["control characters", "api/trainees", "POST", { id: "a\u0001b", name: "x" }, 400],
    ["an unknown station", "api/stations/nowhere/command", "POST", { kind: "hold" }, 404],
    ["a command without kind", "api/stations/api-1/command", "POST", {}, 400],
    ["a command the table lacks", "api/stations/api-1/command", "POST", { kind: "gale" }, 400],
    ["an unknown team started", "api/teams/nope/start", "POST", { members: [] }, 404],
    ["a team started without its tractor", "api/teams/sts_and_tractor/start", "POST", { members: [{ role: "crane", station: "api-1" }] }, 400],
    ["a team role given twice", "api/teams/sts_and_tractor/start", "POST", { members: [{ role: "crane", station: "api-1" }, { role: "crane", station: "x" }] }, 400],
    ["a team member on an unknown station", "api/teams/sts_and_tractor/start", "POST", { members: [{ role: "crane", station: "api-1" }, { role: "tractor", station: "nowhere" }] }, 404],
    ["a team's members on one station", "api/teams/sts_and_tractor/start", "POST", { members: [{ role: "crane", station: "api-1" }, { role: "tractor", station: "api-1" }] }, 400],
    ["a value past the table's range", "api/stations/api-1/command", "POST", { kind: "wind:80:270:0.1" }, 400],
    ["start for an unknown trainee", "api/stations/api-1/command", "POST", { kind: "start", exercise: "sts_discharge", trainee: "zed" }, 400],
    ["start as a member of an unknown team", "api/stations/api-1/command", "POST", { kind: "start", team: "nope", role: "crane" }, 404],
    ["start as a role the team lacks", "api/stations/api-1/command", "POST", { kind: "start", team: "sts_and_tractor", role: "signaller" }, 400],
    ["start as a team's member with an exercise too", "api/stations/api-1/command", "POST", { kind: "start", team: "sts_and_tractor", role: "crane", exercise: "sts_discharge" }, 400],
    ["an unknown API", "api/nothing", "GET", undefined, 404],
    ["an attempt id that is no number", "api/attempts/x1", "GET", undefined, 400],
    ["a missing attempt", "api/attempts/999", "GET", undefined, 404],
    ["renaming an unknown trainee", "api/trainees", "PATCH", { id: "zed", name: "Zed" }, 404],
    ["renaming to control characters", "api/trainees", "PATCH", { id: "carl", name: "C\u001b[31marl" }, 400],
    ["renaming without a name", "api/trainees", "PATCH", { id: "carl" }, 400],
    ["enrolling in an unknown route", "api/enrolments", "POST", { trainee: "carl", route: "sts_advanced" }, 404],
    ["enrolling an unknown trainee", "api/enrolments", "POST", { trainee: "zed", route: "sts_basic" }, 404],
    ["enrolling without a route", "api/enrolments", "POST", { trainee: "carl" }, 400],
    ["a decision before enrolment", "api/decisions", "POST", { trainee: "carl", route: "sts_basic", stage: "single_lift", action: "retry", reason: "x" }, 409],
    ["a decision on an unknown stage", "api/decisions", "POST", { trainee: "carl", route: "sts_basic", stage: "flying", action: "retry", reason: "x" }, 400],
    ["a decision of an unknown kind", "api/decisions", "POST", { trainee: "carl", route: "sts_basic", stage: "single_lift", action: "promote", reason: "x" }, 400],
    ["a decision without a reason", "api/decisions", "POST", { trainee: "carl", route: "sts_basic", stage: "single_lift", action: "retry", reason: "" }, 400],
    ["progress of nobody", "api/progress", "GET", undefined, 400],
    ["progress of an unknown trainee", "api/progress?trainee=zed", "GET", undefined, 404],
  ];
  await until("the station is seen", async () => (await b("api/stations")).data?.some((s) => s.station === "api-1"));
  for (const [what, p, method, body, want] of cases) {
    const r = await b(p, method, body);
    check(r.status === want && typeof r.data?.error === "string", `${what}: ${r.status} (${r.data?.error})`);
  }
  const teams = await b("api/teams");
  check(teams.status === 200 && teams.data.some((t) => t.name === "sts_and_tractor" &&
    t.roles.map((r) => `${r.role}:${r.exercise}`).join(" ") === "crane:sts_discharge tractor:tractor_mafi_park"),
    `the teams and their roles: ${JSON.stringify(teams.data)}`);
  // the command table the panel is drawn from: every command once, its values' ranges the simulation's
  const reply = (await b("api/commands")).data;
  const table = reply?.commands ?? [];
  const wind = table.find((t) => t.name === "wind");
  const cloud = table.find((t) => t.name === "cloud");
  check(table.length === 25 && new Set(table.map((t) => t.name)).size === 25 &&
    cloud?.group === "weather" && cloud.values.map((v) => `${v.what} ${v.min}-${v.max} ${v.unit}`).join() === "cloud cover 0-8 oktas" &&
    table.find((t) => t.name === "signal")?.values[0]?.hand_signal === true && reply.signals.length === 14 &&
    table.find((t) => t.name === "limiter-fault")?.file_name === "limiter_fault" &&
    wind?.group === "weather" && wind.values.map((v) => `${v.what} ${v.min}-${v.max}`).join(", ") ===
      "wind speed 0-50, wind from 0-360, turbulence intensity 0-1",
    `the command table: ${table.map((t) => t.name).join(" ")}; wind ${JSON.stringify(wind?.values)}`);
  check((await b("api/trainees", "POST", { id: "x", name: "y" }, { "X-CSRF-Token": "forged" })).status === 403, "a forged CSRF token: 403");
  check((await b("api/trainees", "POST", "id=x", { "Content-Type": "application/x-www-form-urlencoded" })).status === 415, "a form post: 415");
  check((await fetch(baseB + "api/stations")).status === 401, "no session: 401");
  check((await fetch(baseB + "api/looks")).status === 401, "no session, no looks: 401");
  const big = await b("api/trainees", "POST", JSON.stringify({ id: "x", name: "y".repeat(70000) }));
  check(big.status === 413, `a 70 kB body: ${big.status}`);
  const garbage = await raw(portA, "GARBAGE\r\n\r\n");
  check(/^HTTP\/1\.1 400/.test(garbage), `a request line that is no HTTP: ${garbage.split("\r\n")[0]}`);
  const truncated = await raw(portA, "POST /api/login HTTP/1.1\r\nContent-Length: 50\r\nContent-Type: application/json\r\n\r\n{\"na");
  check(truncated === "" || /^HTTP\/1\.1 4/.test(truncated), `a truncated body: ${truncated.split("\r\n")[0] || "closed"}`);
  check((await b("api/trainees")).data.length === 2, "none of them added a trainee");
  check((await b("api/trainees")).data.find((t) => t.id === "carl").name === "Carl Nyberg", "nor renamed one");
  const renamed = await b("api/trainees", "PATCH", { id: "carl", name: "Carl Nyberg Berg" });
  check(renamed.status === 200 && (await b("api/trainees")).data.find((t) => t.id === "carl").name === "Carl Nyberg Berg",
    `an instructor renames a trainee: ${renamed.status}`);
  check((await b("api/audit")).data.some((a) => a.action === "rename_trainee" && a.target === "carl"), "the rename is audited");
  // trainees are picked by name: a second trainee of carl's name (any case) is refused, saying whose it is
  const twin = await b("api/trainees", "POST", { id: "carl2", name: "carl nyberg berg" });
  check(twin.status === 400 && /is trainee 'carl''s/.test(twin.data?.error ?? "") &&
    !(await b("api/trainees")).data.some((t) => t.id === "carl2"),
    `a second trainee of the same name is refused (${twin.status}: ${twin.data?.error})`);

  // evolution: carl's finished attempt with its skills; tied with dora's best: first of two, tied (the 50th
  // percentile by mid-rank, which read as middling to an instructor)
  const evolution = (await b("api/evolution?trainee=carl")).data;
  check(evolution.attempts.length === 1 && evolution.attempts[0].score === 100 && evolution.attempts[0].skills.safety === 100
    && /^[0-9a-f]{16}$/.test(evolution.attempts[0].exercise_version),
    `carl's evolution: one finished attempt with score, skills and exercise version (${JSON.stringify(evolution.attempts)})`);
  check(evolution.cohort.length === 1 && evolution.cohort[0].trainees === 2 && evolution.cohort[0].percentile === 50 &&
    evolution.cohort[0].place === 1 && evolution.cohort[0].tied === 1 && evolution.cohort[0].place_words === "1st of 2 (tied)",
    `carl against the cohort on sts_discharge: 2 trainees, tied first (${JSON.stringify(evolution.cohort)})`);
  check((await b("api/evolution")).status === 400 && (await b("api/evolution?trainee=zed")).status === 404,
    "evolution of nobody 400, of an unknown trainee 404");
  const csv = await fetch(baseB + "api/attempts.csv", { headers: { Cookie: whoB.cookie } });
  const csvBytes = Buffer.from(await csv.arrayBuffer());
  check(csvBytes.subarray(0, 3).equals(Buffer.from([0xef, 0xbb, 0xbf])), "the CSV starts with a UTF-8 byte-order mark");
  const lines = csvBytes.subarray(3).toString("utf8").trim().split("\r\n");
  check(csv.status === 200 && csv.headers.get("content-type").startsWith("text/csv") && lines.length === 3 &&
    lines[0].startsWith("id,trainee,exercise,exercise_version"), `the attempts as CSV: a header and two rows (${lines.length} lines)`);
  check(lines.some((l) => l.includes(`"'=dora"`)) && !lines.some((l) => l.includes(`,"=dora"`)),
    "a cell a spreadsheet would run as a formula is defused with an apostrophe");

  // training routes: the shipped ones, an enrolment, the progress it gives and an instructor's decision
  const routes = (await b("api/routes")).data;
  check(routes.length === 5 && routes.find((r) => r.id === "sts_basic")?.stages[0].id === "single_lift",
    `five routes, sts_basic starting with single_lift (${routes.map((r) => r.id)})`);
  check((await b("api/enrolments", "POST", { trainee: "carl", route: "sts_basic" })).status === 201, "carl enrolled: 201");
  check((await b("api/enrolments", "POST", { trainee: "carl", route: "sts_basic" })).status === 200, "enrolled again: 200");
  let progress = (await b("api/progress?trainee=carl")).data.routes;
  check(progress.length === 1 && progress[0].next === "single_lift" && progress[0].stages[1].state === "locked",
    `carl's next stage is single_lift, deck_discharge locked (${JSON.stringify(progress[0]?.stages?.slice(0, 2))})`);
  const decided = await b("api/decisions", "POST", { trainee: "carl", route: "sts_basic", stage: "single_lift",
    action: "sign_off", reason: "certified on the quay crane" });
  progress = (await b("api/progress?trainee=carl")).data.routes;
  check(decided.status === 201 && progress[0].stages[0].state === "passed" && progress[0].next === "deck_discharge",
    `a sign-off passes the stage and opens the next (${decided.status}, next ${progress[0].next})`);
  check(progress[0].decisions[0]?.reason === "certified on the quay crane" && progress[0].decisions[0]?.account === "ines",
    "the decision is stored with its reason and who");
  check((await b("api/audit")).data.some((a) => a.action === "sign_off" && a.target === "carl sts_basic/single_lift"),
    "the decision is audited");

  // the cohort views: every figure's standing, a trainee id that needs percent-encoding, the class, a comparison
  const dora = await b("api/evolution?trainee=%3Ddora");
  check(dora.status === 200 && dora.data.trainee === "=dora" && dora.data.attempts.length === 1,
    `a percent-encoded trainee id is decoded (${dora.status} ${dora.data?.trainee})`);
  const collisions = evolution.standings.find((s) => s.figure === "collisions");
  check(collisions?.higher_better === false && collisions.percentile === 50 && collisions.trainees === 2 &&
    evolution.standings.some((s) => s.figure === "skill_safety" && s.higher_better),
    `standings on every figure, with its direction (collisions: ${JSON.stringify(collisions)})`);
  check(Object.keys(evolution.attempts[0].metrics).includes("time_s"), "each attempt carries every stored metric");
  const overview = (await b("api/class")).data;
  const carlLine = overview.find((t) => t.trainee === "carl");
  check(overview.length === 2 && carlLine.best_score === 100 && carlLine.finished === 1 && carlLine.trend === null &&
    carlLine.routes[0]?.route === "sts_basic" && carlLine.routes[0]?.passed === 1 && carlLine.name === "Carl Nyberg Berg",
    `the class overview: two lines, carl's best 100, one stage of sts_basic passed (${JSON.stringify(carlLine)})`);
  const compared = await b("api/compare?a=carl&b=%3Ddora");
  const scoreLine = compared.data?.figures?.find((f) => f.figure === "score");
  check(compared.status === 200 && scoreLine?.a === 100 && scoreLine?.b === 100,
    `carl and dora compared: both 100 on the score (${JSON.stringify(scoreLine)})`);
  check((await b("api/compare?a=carl")).status === 400 && (await b("api/compare?a=carl&b=zed")).status === 404,
    "a comparison with one trainee 400, with an unknown one 404");
  const reportPage = await fetch(baseB + "api/reports/trainee?trainee=carl", { headers: { Cookie: whoB.cookie } });
  const reportHtml = await reportPage.text();
  check(reportPage.status === 200 && reportPage.headers.get("content-type").startsWith("text/html") &&
    reportHtml.includes("Trainee report: Carl Nyberg Berg") && reportHtml.includes("<svg"),
    `carl's report page: HTML with his name and the plots (${reportPage.status})`);
  let printed = false;
  const printing = Promise.all(["api/reports/trainee.pdf?trainee=carl", "api/reports/class.pdf"].map((p) =>
    fetch(baseB + p, { headers: { Cookie: whoB.cookie } }))).then((r) => { printed = true; return r; });
  const during = await b("api/stations");
  check(during.status === 200 && !printed, "the console answers while chromium prints");
  const pdfs = await printing;
  const pdfBytes = await Promise.all(pdfs.map(async (r) => Buffer.from(await r.arrayBuffer())));
  check(pdfs.every((r) => r.status === 200 && r.headers.get("content-type") === "application/pdf") &&
    pdfBytes.every((bytes) => bytes.subarray(0, 5).toString() === "%PDF-"),
    `carl's and the class report as PDF, printed at once (${pdfs.map((r) => r.status)})`);
  check((await b("api/reports/nobody")).status === 404 && (await b("api/reports/trainee?trainee=zed")).status === 404,
    "an unknown report 404, a report on an unknown trainee 404");
  const doraWho = await login(baseB, "dora", "dora-password");
  const d = client(baseB, doraWho);
  const own = await fetch(baseB + "api/reports/trainee", { headers: { Cookie: doraWho.cookie } });
  check(own.status === 200 && (await own.text()).includes("Trainee report: Dora Lind"), `a trainee gets their own report (${own.status})`);
  const refused = await Promise.all(["api/reports/trainee?trainee=carl", "api/reports/class", "api/reports/class.pdf",
    "api/class", "api/compare?a=carl&b=%3Ddora", "api/evolution?trainee=carl", "api/designer/source?exercise=sts_discharge"]
    .map(async (p) => (await d(p)).status));
  const design = await d("api/designer/check", "POST", { text: "exercise: {name: x}" });
  check(refused.every((s) => s === 403) && design.status === 403,
    `a trainee is refused others' reports, the class, comparisons and the designer: ${refused}, ${design.status}`);
  const designErrors = await Promise.all([b("api/designer/check", "POST", { text: 5 }), b("api/designer/check", "POST", {}),
    b("api/designer/check", "POST", { text: "exercise: [" }), b("api/designer/source?exercise=../../etc/passwd"),
    b("api/designer/nothing", "POST", { text: "" })]);
  check(designErrors.map((r) => r.status).join() === "400,400,422,404,404",
    `the designer's bad requests: ${designErrors.map((r) => `${r.status} ${r.data?.error}`).join("; ")}`);
  // the designer's forms come from the machine's type: the faults it has the parts for, a truck lane where
  // trucks come to it
  const forms = {};
  for (const name of ["sts_discharge", "mhc_hook_lift", "tractor_free_practice", "reach_stacker_stack"]) {
    const source = await b(`api/designer/source?exercise=${name}`);
    forms[name] = (await b("api/designer/check", "POST", { text: source.data.text })).data?.form;
  }
  const offered = (name) => forms[name]?.event_kinds?.join(",");
  check(offered("sts_discharge") === "gust,hoist_brake_fault,landed_sensor_fault" &&
    offered("mhc_hook_lift") === "gust,hoist_brake_fault,limiter_fault" && offered("tractor_free_practice") === "gust" &&
    offered("reach_stacker_stack") === "gust,landed_sensor_fault,limiter_fault",
    `the designer offers each machine the faults it has: ${Object.keys(forms).map((n) => `${n} ${offered(n)}`).join("; ")}`);
  check(forms.sts_discharge?.serves_trucks === true && forms.mhc_hook_lift?.serves_trucks === false &&
    forms.reach_stacker_stack?.serves_trucks === true, "truck lanes are offered where trucks come");
  // the route editor: a trainee is refused; bad requests say why and write nothing
  const routeRefused = await Promise.all([d("api/routes/source?route=sts_basic"),
    d("api/routes/check", "POST", { id: "x", text: "name: x" })]);
  const routeErrors = await Promise.all([b("api/routes/check", "POST", { text: "name: x" }),
    b("api/routes/check", "POST", { id: "x", text: 5 }), b("api/routes/check", "POST", { id: "../escape", text: "name: x" }),
    b("api/routes/save", "POST", { id: "broken", text: "goals: [" }), b("api/routes/source?route=../../etc/passwd"),
    b("api/routes/check", "POST", "{ nope"), b("api/routes/nothing", "POST", { id: "x", text: "" })]);
  check(routeRefused.every((r) => r.status === 403) && routeErrors.map((r) => r.status).join() === "400,400,422,422,404,400,404" &&
    routeErrors[2].data.error.includes("file name") && (await b("api/routes")).data.length === 5,
    `the route editor's bad requests: ${routeErrors.map((r) => `${r.status} ${r.data?.error}`).join("; ")}`);

  // the live socket: refused without a login; random, truncated and oversized messages answered or the
  // socket closed, the console unharmed
  check((await webSocket(portA, "hs_session=forged")).status === 401, "a live socket without a login: 401");
  const portB = baseB.match(/:(\d+)\//)[1];
  const live = await webSocket(portB, whoB.cookie);
  check(live.status === 101, `a live socket: ${live.status}`);
  await until("it gets the stations at once", () => live.messages.some((m) => m.type === "stations"));
  live.socket.write(frame("{ nope"));
  live.socket.write(frame(JSON.stringify({ type: "subscribe", station: 5 })));
  live.socket.write(frame(JSON.stringify({ type: "dance" })));
  live.socket.write(frame(JSON.stringify({ type: "subscribe", station: "api-1", view: "yes" })));
  live.socket.write(frame(JSON.stringify({ type: "subscribe", station: "api-1", view: true })));
  await until("each bad message gets an error, the good one its answer", () =>
    live.messages.filter((m) => m.type === "error").length === 4 &&
    live.messages.some((m) => m.type === "subscribed" && m.view === true));
  const looks = await b("api/looks");
  check(looks.status === 200 && looks.data.visuals["sts.gantry"]?.parts.length > 5 && looks.data.scenery.length > 0,
    "the 3D view's looks are served (the image generator's data/visuals/harbour.yaml)");
  let fuzzed = 0;
  for (let n = 0; n < 200; ++n) {
    const ws = await webSocket(portB, whoB.cookie);
    const bytes = randomBytes(1 + Math.floor(Math.random() * 300));
    const kind = n % 4;
    if (kind === 0) ws.socket.write(frame(bytes));                                 // random text frame
    else if (kind === 1) ws.socket.write(frame(bytes).subarray(0, 3 + (n % 7)));  // truncated frame
    else if (kind === 2) ws.socket.write(bytes);                                  // not a frame at all
    else ws.socket.write(frame(JSON.stringify({ type: "subscribe", station: bytes.toString("latin1") }).slice(0, 40 + (n % 30))));
    ws.socket.end();
    fuzzed++;
  }
  const huge = await webSocket(portB, whoB.cookie);
  huge.socket.write(frame("x".repeat(5000)));
  await until("a message over 4 KiB closes its socket", () => huge.closed || huge.closeCode !== undefined);
  check((await b("api/stations")).status === 200, `the console answers after ${fuzzed} fuzzed sockets`);
  const after = await webSocket(portB, whoB.cookie);
  await until("a new live socket still gets the stations", () => after.messages.some((m) => m.type === "stations"));
  for (const ws of [live, after]) ws.socket.destroy();

  // two consoles command one station: each gets its own answer
  const whoA = await login(baseA, "ines", "ines-password");
  check(whoA.status === 429, "console A still makes ines wait (its counter)");
  const c2 = await consoleAt("console-c");
  const whoC = await login(c2[0], "ines", "ines-password");
  const c = client(c2[0], whoC);
  await until("console C sees the station", async () => (await c("api/stations")).data?.some((s) => s.station === "api-1"));
  // a route's next stage started from the console: carl's single_lift is signed off, so deck_discharge
  const command = (body) => b("api/stations/api-1/command", "POST", body);
  for (const [body, status, what] of [
    [{ kind: "start", route: "sts_advanced", trainee: "carl" }, 404, "an unknown route"],
    [{ kind: "start", route: "sts_basic", trainee: "=dora" }, 409, "a trainee not enrolled"],
    [{ kind: "start", route: "sts_basic" }, 400, "no trainee"]]) {
    const r = await command(body);
    check(r.status === status, `a route start with ${what}: ${r.status} (${r.data?.error})`);
  }
  const routed = await command({ kind: "start", route: "sts_basic", trainee: "carl", autopilot: true });
  check(routed.status === 200 && /sts_bay12_deck/.test(routed.data?.message),
    `the route's next stage starts: ${routed.status} ${routed.data?.message}`);
  await until("the station runs carl's deck_discharge", async () => {
    const s = (await c("api/stations")).data?.find((x) => x.station === "api-1");
    return s?.state === "running" && s.exercise === "sts_bay12_deck";
  });
  await command({ kind: "stop" });
  await until("the station is idle again", async () => (await c("api/stations")).data?.find((x) => x.station === "api-1")?.state === "idle");
  const staged = (await b("api/attempts?trainee=carl")).data[0];
  check(staged?.route === "sts_basic" && staged?.stage === "deck_discharge" && staged?.exercise === "sts_bay12_deck",
    `its attempt is stored for the route's stage (${staged?.route}/${staged?.stage}, ${staged?.exercise})`);

  // what the console sends is what schema/wire.json (the browser's types) says: its replies, and every live
  // message of a running station watched with its 3D view
  const watching = await webSocket(portB, whoB.cookie);
  watching.socket.write(frame(JSON.stringify({ type: "subscribe", station: "api-1", view: true })));
  const started = await b("api/stations/api-1/command", "POST", { kind: "start", exercise: "sts_discharge", trainee: "carl", autopilot: true });
  check(started.status === 200, `console B starts the exercise: ${started.data?.message}`);
  await until("it runs", async () => (await c("api/stations")).data?.find((s) => s.station === "api-1")?.state === "running");
  const [holdB, holdC] = await Promise.all([b("api/stations/api-1/command", "POST", { kind: "hold" }),
    c("api/stations/api-1/command", "POST", { kind: "wind:10:200:0.1" })]);
  check(holdB.status === 200 && holdC.status === 200, `both consoles' commands done (${holdB.data?.message}; ${holdC.data?.message})`);
  const again = await c("api/stations/api-1/command", "POST", { kind: "start", exercise: "sts_discharge", trainee: "carl" });
  check(again.status === 409, `a second start while running: 409 (${again.data?.message})`);
  await b("api/stations/api-1/command", "POST", { kind: "resume" });
  await sleep(3000);
  await until("the watched station's state, scene and events have come", () =>
    ["stations", "subscribed", "state", "scene", "event"].every((t) => watching.messages.some((m) => m.type === t)));
  const wrong = [];
  for (const m of watching.messages) wrong.push(...(MESSAGE_OF_TYPE[m.type] ? wireErrors(m, MESSAGE_OF_TYPE[m.type]) : [`a message of type ${m.type}`]));
  for (const [reply, name] of [[await b("api/me"), "Me"], [await b("api/commands"), "CommandTable"], [await b("api/looks"), "Looks"],
    [await b("api/progress?trainee=carl"), "Progress"], [await b("api/evolution?trainee=carl"), "Evolution"]])
    wrong.push(...wireErrors(reply.data, name));
  for (const [path, name] of [["api/stations", "Station"], ["api/exercises", "ExerciseCard"], ["api/attempts", "AttemptItem"],
    ["api/teams", "Team"], ["api/routes", "RouteInfo"]])
    for (const item of (await b(path)).data) wrong.push(...wireErrors(item, name));
  check(wrong.length === 0 && wireErrors({ type: "event", station: "x" }, "EventMessage").length > 0,
    `the console's ${watching.messages.length} live messages and its replies are as the schema says${wrong.length ? `: ${[...new Set(wrong)].slice(0, 8).join("; ")}` : ""}`);
  watching.socket.destroy();

  // the station's process killed mid-exercise: lost at the console, its attempt stored so far
  station.kill("SIGKILL");
  const t0 = Date.now();
  await until("the killed station shows as lost", async () => (await b("api/stations")).data?.find((s) => s.station === "api-1")?.state === "lost", 10);
  console.log(`     lost after ${((Date.now() - t0) / 1000).toFixed(1)} s`);
  const stored = (await b("api/attempts")).data.find((x) => x.trainee === "carl");
  check(stored !== undefined, `its attempt is in the records (status ${stored?.status})`);
  const results = run(["results", "--db", db]);
  check(/interrupted/.test(results), "a later look at the records marks it interrupted");
  const audit = (await b("api/audit")).data;
  check(audit.some((x) => x.action === "command start" && x.target === "api-1" && x.account === "ines"), "the start is audited with who");
  check(audit.filter((x) => x.action === "login_failed").length >= 5, "failed logins are audited");
} catch (e) {
  check(false, `error: ${e.stack ?? e}`);
} finally {
  await h.finish();
}
