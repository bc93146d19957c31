// The exercise designer's round trip in a real browser: an instructor starts from a shipped exercise, breaks it
// (refused, the line and field named), fixes it, sees the preview, saves it in the centre's folder; the saved
// exercise runs under the autopilot and its attempt, with the saved version, shows in the trainee's evolution;
// a route of the centre's own, written in the route editor, makes it a stage a station runs for an enrolled trainee.
// Usage: node console_designer.mjs HARBOURSIM OUT_DIR DATA_DIR
import { chromium } from "playwright-core";
import { Harness } from "./harness.mjs";
import { wireErrors } from "./wire.mjs";
import { mkdtempSync, mkdirSync, readdirSync, readFileSync, existsSync, symlinkSync, writeFileSync } from "node:fs";
import { tmpdir } from "node:os";
import path from "node:path";

const [app, out, data] = process.argv.slice(2);
mkdirSync(out, { recursive: true });
const dir = mkdtempSync(path.join(tmpdir(), "harbour-designer-"));
const db = `sqlite3://db=${dir}/records.db`;
const h = new Harness(app);
const check = h.check.bind(h), run = h.run.bind(h), until = h.until.bind(h);
// the centre's folders: its own exercises and routes beside the shipped machines, vessels, ... (linked)
const centre = path.join(dir, "centre");
const exercises = path.join(centre, "exercises"), routes = path.join(centre, "routes");
mkdirSync(exercises, { recursive: true });
mkdirSync(routes, { recursive: true });
for (const entry of readdirSync(data))
  if (entry !== "exercises" && entry !== "routes") symlinkSync(path.join(data, entry), path.join(centre, entry));

let browser;
try {
  run(["trainees", "add", "eva", "Eva Lind", "--db", db]);
  run(["accounts", "add", "ines", "--role", "instructor", "--db", db], "ines-password\n");
  const c = h.start(["console", "--db", db, "--domain", "205", "--port", "0", "--exercises", exercises,
    "--routes", routes]);
  await until("the console listens", () => /http:\/\/127\.0\.0\.1:\d+\//.test(c.output));
  const url = c.output.match(/http:\/\/127\.0\.0\.1:\d+\//)[0];
  browser = await chromium.launch({ executablePath: "/usr/bin/chromium", args: ["--headless", "--no-sandbox",
    "--disable-gpu", "--enable-unsafe-swiftshader", "--no-first-run", "--disable-background-networking"] });
  const page = await browser.newPage({ viewport: { width: 1400, height: 1000 } });
  await page.goto(url);
  await page.fill("#login-name", "ines");
  await page.fill("#login-password", "ines-password");
  await page.click("#login-form button");
  await until("the designer offers the shipped exercises", async () =>
    (await page.locator("#design-base option[value=sts_discharge]").count()) === 1);
  await page.selectOption("#design-base", "sts_discharge");
  await page.click("#design-load");
  await until("the shipped exercise is loaded", async () => (await page.inputValue("#design-text")).includes("name: sts_discharge"));
  const shipped = await page.inputValue("#design-text");

  // broken: a time limit that is no number is refused with its line and field
  const broken = shipped.replace("name: sts_discharge", "name: sts_long_discharge").replace("time_limit_s: 180", "time_limit_s: soon");
  const brokenLine = broken.split("\n").findIndex((l) => l.includes("time_limit_s: soon")) + 1;
  const drawnAtNaN = [];  // the timeline once drew ~90 SVG attributes at NaN for such a limit
  page.on("console", (m) => { if (m.type() === "error" && /NaN/.test(m.text())) drawnAtNaN.push(m.text()); });
  await page.fill("#design-text", broken);
  await page.click("#design-check");
  await until("the broken design is refused", async () => (await page.textContent("#design-result")).includes("refused"));
  check(drawnAtNaN.length === 0, `the forms draw nothing at NaN while the limit is no number (${drawnAtNaN.length}: ${drawnAtNaN[0] ?? ""})`);
  const refusal = await page.textContent("#design-result");
  check(/422/.test(refusal) && refusal.includes("time_limit_s") && refusal.includes(`:${brokenLine}`) && refusal.includes("the design"),
    `refused with the line (${brokenLine}) and field named: ${refusal}`);
  await page.click("#design-save");
  await until("and not saved", async () => (await page.textContent("#design-result")).includes("save refused"));
  check(!existsSync(path.join(exercises, "sts_long_discharge.yaml")), "a refused design writes no file");

  // fixed: valid, previewed, saved
  await page.fill("#design-text", broken.replace("time_limit_s: soon", "time_limit_s: 240").replace("name: sts_long_discharge", "name: sts_draft"));
  await page.click("#design-check");
  await until("the design is valid", async () => (await page.textContent("#design-result")).includes("valid"));
  check((await page.textContent("#design-summary")).includes("time limit 240 s"), "the summary shows the new time limit");
  await until("the preview draws its world", async () => Number(await page.getAttribute("#design-view", "data-entities")) > 10);

  // the forms edit the same YAML: stowage by clicking slots, events on the timeline, weather, the rubric
  const yaml = () => page.inputValue("#design-text");
  const entities = async () => Number(await page.getAttribute("#design-view", "data-entities"));
  await until("the stowage grid shows bay 12", async () =>
    (await page.getAttribute('#design-stowage td[data-slot="12,1,82"]', "class"))?.includes("moved"));
  const before = await entities();
  await page.click('#design-stowage td[data-slot="12,5,82"]');
  await until("a box is stowed in the clicked slot", async () => (await yaml()).includes("slot: [12, 5, 82]"));
  check((await yaml()).startsWith("# First STS exercise"), "the file's comments are kept");
  await until("the preview shows it", async () => (await entities()) === before + 1);
  // a slot with nothing under it to stand on is not offered: clicking it stows nothing
  check((await page.getAttribute('#design-stowage td[data-slot="12,7,84"]', "class")) === "floating" &&
    (await page.getAttribute('#design-stowage td[data-slot="12,5,84"]', "class")) === null,
    "the grid offers a slot above a box and not one above nothing");
  await page.click('#design-stowage td[data-slot="12,7,84"]');
  check(!(await yaml()).includes("[12, 7, 84]"), "a click on a floating slot stows nothing");
  // typed, and at once a box clicked: the click edits the typed text
  await page.fill("#design-text", (await yaml()).replace("pass_score: 70", "pass_score: 75"));
  await page.click('#design-stowage td[data-slot="12,6,82"]');
  check((await yaml()).includes("pass_score: 75") && (await yaml()).includes("[12, 6, 82]"), "a form edit right after typing keeps what was typed");
  await page.click("#design-box-remove");
  // a box on nothing typed into the text: the loader's refusal names the box's slot field
  await page.fill("#design-text", (await yaml()).replace("  containers:\n",
    "  containers:\n    - {id: HSIM0000009, type: 40ft, gross_mass_kg: 20000, slot: [12, 7, 84]}\n"));
  await until("a box on nothing is refused", async () => (await page.textContent("#design-result")).includes("nothing stowed under it"));
  check((await page.textContent("#design-result")).includes("exercise.containers[0].slot"), "the refusal names the box's slot");
  await page.fill("#design-text", (await yaml()).replace(/    - \{id: HSIM0000009.*\n/, ""));
  await until("removed, the design is valid again", async () => (await page.textContent("#design-result")).includes("valid") &&
    !(await yaml()).includes("[12, 7, 84]"));
  await page.fill("#design-name", "sts_long_discharge");
  await page.press("#design-name", "Enter");
  // a number the field cannot take is said as typed and written nowhere
  await page.fill("#design-rule-time_limit_s", "-5");
  await page.press("#design-rule-time_limit_s", "Enter");
  await until("a negative time limit is said at once", async () =>
    /time limit \[s\]: at least 0/.test(await page.textContent("#design-rubric")));
  check(!(await yaml()).includes("time_limit_s: -5"), "and not written");
  await page.fill("#design-rule-time_limit_s", "250");
  await page.press("#design-rule-time_limit_s", "Enter");
  check(await page.getAttribute("#design-rule-hard_landing_mps", "placeholder") === "0.3", "a threshold the design leaves shows its default");
  await page.fill("#design-rule-collision", "25");
  await page.press("#design-rule-collision", "Enter");
  await page.fill("#design-wind", "6");
  await page.press("#design-wind", "Enter");
  // where the crane starts, in the ranges its machine file gives: the trolley moved, a gantry off its rails refused
  check(await page.getAttribute("#design-pose-trolley_x_m", "max") === "62", "the trolley's start offers the machine's range (to 62 m)");
  await page.fill("#design-pose-gantry_y_m", "500");
  await page.press("#design-pose-gantry_y_m", "Enter");
  await until("a gantry off its rails is said as typed", async () =>
    /gantry y m: at most \d+/.test(await page.textContent("#design-start-pose")));
  check(!/gantry_y_m: 500/.test(await yaml()), "and not written");
  await page.fill("#design-pose-gantry_y_m", "0");
  await page.press("#design-pose-gantry_y_m", "Enter");
  await page.fill("#design-pose-trolley_x_m", "40");
  await page.press("#design-pose-trolley_x_m", "Enter");
  await until("the trolley's start is written and valid", async () => /trolley_x_m: 40/.test(await yaml()) &&
    (await page.textContent("#design-result")).includes(": valid"));
  // two gusts put on the timeline, the second moved before the first: kept in time order
  for (const [x, at] of [[400, 60], [500, 20]]) {
    await page.click("#design-timeline", { position: { x, y: 30 } });
    await until("an event is added", async () => (await page.locator("#design-event-at").count()) === 1);
    await page.fill("#design-event-at", String(at));
    await page.press("#design-event-at", "Enter");
    await until(`it is at ${at} s`, async () => (await yaml()).includes(`at_s: ${at}`));
  }
  // the kinds of event offered read as the console's command table words them (the STS: a gust and its faults)
  const kindWords = await page.$$eval("#design-event-kind option", (os) => os.map((o) => `${o.value}=${o.textContent}`));
  check(kindWords.includes("gust=gust") && kindWords.includes("hoist_brake_fault=hoist brake fault") &&
    kindWords.includes("landed_sensor_fault=landed sensor fault"), `the event kinds in words: ${kindWords.join(", ")}`);
  const text = await yaml();
  check(text.indexOf("at_s: 20") < text.indexOf("at_s: 60") && /collision: 25/.test(text) && /wind_mean_mps: 6/.test(text) &&
    /time_limit_s: 250/.test(text) && /name: sts_long_discharge/.test(text), `the forms wrote the YAML:\n${text}`);
  await until("the edited design is valid", async () => (await page.textContent("#design-result")).includes("sts_long_discharge: valid"));
  check((await page.textContent("#design-summary")).includes("2 scripted events"), "the check counts the scripted events");
  await page.click('#design-stowage td[data-slot="12,5,82"]');
  await until("the new box is selected", async () => (await page.locator("#design-box").count()) === 1);
  await page.locator("#designer-panel").screenshot({ path: path.join(out, "console_designer.png") });
  check((await yaml()).includes('title: "First discharge onto a truck (centre copy)"'),
    "the copy of a shipped exercise has a title of its own");
  await page.click("#design-save");
  await until("it is saved", async () => (await page.textContent("#design-result")).startsWith("saved"));
  const version = (await page.textContent("#design-result")).match(/version ([0-9a-f]{16})/)?.[1];
  const file = path.join(exercises, "sts_long_discharge.yaml");
  check(existsSync(file) && readFileSync(file, "utf8").includes("time_limit_s: 250") &&
    readFileSync(file, "utf8").includes("slot: [12, 5, 82]") && readFileSync(file, "utf8").includes("collision: 25") &&
    existsSync(path.join(exercises, "versions", `sts_long_discharge-${version}.yaml`)),
    `saved in the centre's folder with its version kept (${version})`);
  await until("the exercise lists offer it", async () => (await page.locator("#exercise option[value=sts_long_discharge]").count()) === 1);

  // the saved exercise runs; its attempt records the saved version and shows in eva's evolution
  run(["run", "--exercise", file, "--autopilot", "--trainee", "eva", "--db", db, "--record", path.join(dir, "eva.hsrec")]);
  const evolution = await page.evaluate(async () => (await fetch("/api/evolution?trainee=eva")).json());
  check(evolution.attempts.length === 1 && evolution.attempts[0].exercise_version === version,
    `eva's attempt ran version ${evolution.attempts[0]?.exercise_version} (${evolution.attempts[0]?.exercise})`);
  check(wireErrors(evolution, "Evolution").length === 0, `eva's evolution is as schema/wire.json says: ${wireErrors(evolution, "Evolution").join("; ")}`);
  await page.selectOption("#progress-trainee", "eva");
  await page.click("#show-progress");
  await until("her evolution plots the attempt", async () => (await page.getAttribute("#evolution", "data-attempts")) === "1");

  // a second version: the first is kept for the attempts that ran it
  await page.fill("#design-text", broken.replace("time_limit_s: soon", "time_limit_s: 300"));
  await page.click("#design-save");
  await until("the second version is saved", async () => {
    const t = await page.textContent("#design-result");
    return t.startsWith("saved") && !t.includes(version);
  });
  check(readdirSync(path.join(exercises, "versions")).length === 2, "both versions are kept");
  // eva's attempt replays on the version it ran, which the designer kept, not on the one saved since
  const replay = await page.evaluate(async (attempt) => {
    const me = await (await fetch("/api/me")).json();
    const r = await fetch("/api/replays", { method: "POST", headers: { "Content-Type": "application/json",
      "X-CSRF-Token": me.csrf }, body: JSON.stringify({ attempt }) });
    return { status: r.status, body: await r.json() };
  }, evolution.attempts[0].id);
  check(replay.status === 201 && replay.body.exercise_version === version,
    `the replay of eva's attempt opens on version ${replay.body.exercise_version ?? replay.body.error} (${version} ran)`);
  check(wireErrors(replay.body, "ReplayInfo").length === 0, `the opened replay is as schema/wire.json says: ${wireErrors(replay.body, "ReplayInfo").join("; ")}`);
  // the command line replays it bit for bit on the kept version's file (it stands in versions/, beside the
  // centre's folder)
  const kept = path.join(exercises, "versions", `sts_long_discharge-${version}.yaml`);
  let replayed = "";
  try { replayed = run(["replay", path.join(dir, "eva.hsrec"), "--exercise", kept]); } catch (e) { replayed = `${e.stdout}${e.stderr}`; }
  check(/bit for bit|identical|matches/i.test(replayed) && !/diverge/i.test(replayed), `harboursim replay on the kept version: ${replayed.split("\n")[0]}`);
  // and taken over at a station of the centre, it goes on in that version too
  const api = (url, body) => page.evaluate(async ([url, body]) => {
    const me = await (await fetch("/api/me")).json();
    const r = await fetch(url, body === undefined ? {} : { method: "POST", headers: { "Content-Type": "application/json",
      "X-CSRF-Token": me.csrf }, body: JSON.stringify(body) });
    return { status: r.status, body: await r.json() };
  }, [url, body]);
  h.start(["station", "--serve", "--name", "designer-1", "--domain", "205", "--db", db, "--window", "off", "--exercises", exercises,
    "--routes", routes, "--record", path.join(dir, "branch.hsrec")]);
  await until("the centre's station is idle", async () =>
    (await api("/api/stations")).body.some((s) => s.station === "designer-1" && s.state === "idle"), 40);
  const takeOver = await api(`/api/replays/${replay.body.replay}`, { action: "take-over", station: "designer-1", trainee: "eva",
    autopilot: true });
  check(takeOver.status === 200, `the take-over is accepted: ${takeOver.status} ${takeOver.body.message ?? takeOver.body.error}`);
  let branch;
  await until("the branch is an attempt of eva's", async () => {
    branch = (await api("/api/attempts?trainee=eva")).body.find((a) => a.parent === evolution.attempts[0].id);
    return branch !== undefined;
  }, 40);
  check(branch?.exercise_version === version, `the take-over runs version ${branch?.exercise_version} (${version} ran, the file is newer)`);
  await api("/api/stations/designer-1/command", { kind: "stop", exercise: "", trainee: "", route: "" });
  const idle = () => until("the centre's station is idle again", async () =>
    (await api("/api/stations")).body.some((s) => s.station === "designer-1" && s.state === "idle"), 40);
  await idle();

  // the route editor: a route of the centre's own naming the designed exercise; a stage naming no exercise is
  // refused with its line and field, the stage added by the form is valid and saved in the centre's route folder
  const routeResult = () => page.textContent("#route-result");
  await page.selectOption("#route-base", "sts_basic");
  await page.click("#route-load");
  await until("the shipped route is loaded and checked", async () => (await routeResult()).includes("sts_basic_centre: valid, 5 stages"));
  check((await page.inputValue("#route-text")).includes("name: STS basic (centre copy)"),
    "the copy of a shipped route gets a title of its own");
  check((await page.locator("#route-stages tr[data-stage=hoist_brake_fault]").count()) === 1, "the loader's stages are listed");
  // a route begun from nothing trains on its first stage's machine, as the machine's type calls it
  await page.fill("#route-text", "");
  await page.selectOption("#route-add-exercise", "rtg_rehandle");
  await page.click("#route-add-stage");
  await until("a new route is begun", async () => (await page.inputValue("#route-text")).startsWith("name: New route"));
  check(/\nmachine: "?rubber-tyred gantry crane"?\n/.test(await page.inputValue("#route-text")),
    `the new route's machine is its stage's: ${await page.inputValue("#route-text")}`);
  await page.fill("#route-id", "centre_long");
  await page.fill("#route-text", "# the centre's own\nname: Long discharges\nmachine: STS\ngoals:\n  - goal: Endurance\n    stages:\n" +
    "      - {id: warm_up, exercise: sts_nowhere}\n");
  await page.click("#route-check");
  await until("a stage naming no exercise is refused", async () => (await routeResult()).includes("refused"));
  check(/centre_long\.yaml:7: goals\[0\]\.stages\[0\]\.exercise: no exercise 'sts_nowhere'/.test(await routeResult()) &&
    (await routeResult()).includes("sts_long_discharge"), `refused with the line and field, listing the centre's exercises: ${await routeResult()}`);
  await page.fill("#route-text", (await page.inputValue("#route-text")).replace("sts_nowhere", "sts_discharge"));
  await page.selectOption("#route-add-exercise", "sts_long_discharge");
  await page.fill("#route-add-id", "long");
  await page.fill("#route-add-goal", "Endurance");
  await page.fill("#route-add-score", "60");
  await page.click("#route-add-stage");
  await until("the stage is written and the route valid", async () =>
    (await page.inputValue("#route-text")).includes("{id: long, exercise: sts_long_discharge, pass: {score: 60}}") &&
    (await routeResult()).includes("centre_long: valid, 2 stages"));
  check((await page.inputValue("#route-text")).startsWith("# the centre's own"), "the route's comment is kept");
  await page.locator("#route-editor-panel").screenshot({ path: path.join(out, "console_route_editor.png") });
  await page.click("#route-save");
  await until("the route is saved", async () => (await routeResult()).startsWith("saved centre_long"));
  check(readFileSync(path.join(routes, "centre_long.yaml"), "utf8").includes("exercise: sts_long_discharge"),
    "saved in the centre's route folder");
  const shippedRoute = readFileSync(path.join(data, "routes", "sts_basic.yaml"), "utf8");
  check((await api("/api/routes/save", { id: "sts_basic", text: shippedRoute })).status === 409 &&
    readFileSync(path.join(data, "routes", "sts_basic.yaml"), "utf8") === shippedRoute, "a shipped route's name is refused (409)");
  const twin = await api("/api/routes/check", { id: "centre_twin", text: shippedRoute });
  check(twin.status === 422 && /route\.name: 'STS basic' is also the name of route 'sts_basic'/.test(twin.body.error ?? ""),
    `a shipped route's title is refused under another file name: ${twin.status} ${twin.body.error}`);
  // eva enrolled; the station runs the route's next stage (warm-up passed by the autopilot, then the long one)
  await until("the enrol form offers it", async () => (await page.locator("#route option[value=centre_long]").count()) === 1);
  await page.selectOption("#progress-trainee", "eva");
  await page.selectOption("#route", "centre_long");
  await page.click("#enrol-form button[type=submit]");
  await until("eva is enrolled", async () => (await page.textContent("#enrol-result")) === "enrolled");
  const started = await api("/api/stations/designer-1/command", { kind: "start", exercise: "", trainee: "eva", route: "centre_long",
    autopilot: true });
  check(started.status === 200 && /sts_discharge/.test(started.body.message), `the route's first stage starts: ${started.status} ${started.body.message ?? started.body.error}`);
  let staged;
  await until("its attempt is stored for the centre's route", async () => {
    staged = (await api("/api/attempts?trainee=eva")).body.find((a) => a.route === "centre_long");
    return staged !== undefined;
  }, 40);
  check(staged.stage === "warm_up" && staged.exercise === "sts_discharge", `for its stage (${staged.stage}, ${staged.exercise})`);
  await api("/api/stations/designer-1/command", { kind: "stop", exercise: "", trainee: "", route: "" });
  await idle();
  const progress = (await api("/api/progress?trainee=eva")).body.routes.find((r) => r.route === "centre_long");
  const stopped = (await api("/api/attempts?trainee=eva")).body.find((a) => a.id === staged.id);
  // stopped by the instructor with its move left: the instructor's end, not one of eva's attempts at the stage
  check(stopped?.status === "ended_by_instructor" && progress?.stages[0].attempts === 0 && progress?.stages[1].state === "locked",
    `eva's progress on it: ${stopped?.outcome}, warm_up ${progress?.stages[0].attempts} attempts counted, long ${progress?.stages[1].state}`);

  // a yard block: a box's goal set by clicking the slot it is to go to
  const load = async (name) => {
    await page.selectOption("#design-base", name);
    await page.click("#design-load");
    await until(`${name} is loaded and checked`, async () => (await page.textContent("#design-result")).includes(`${name}: valid`));
  };
  await load("rtg_rehandle");
  await until("the block grid shows bay 06", async () => (await page.locator("#design-block td.box").count()) > 0);
  check((await page.getAttribute('#design-block td[data-slot="6,2,1"]', "class")) === "target",
    "a move's target slot is marked in the grid");
  await page.click('#design-block td[data-slot="6,1,2"]');
  await page.selectOption("#design-box-goal", "slot");
  await page.click('#design-block td[data-slot="6,5,2"]');
  await until("the move to the clicked slot is written", async () =>
    /\{container: MSKU7100012, block_slot: \[6, 5, 2\]/.test(await yaml()));
  await until("and the design stays valid", async () => (await page.textContent("#design-result")).includes("rtg_rehandle: valid") &&
    (await page.textContent("#design-summary")).includes("4 moves"));
  await page.locator("#design-block-set").screenshot({ path: path.join(out, "console_designer_block.png") });
  // a component of where the RTG stands
  await page.fill("#design-pose-position_m-1", "3.5");
  await page.press("#design-pose-position_m-1", "Enter");
  await until("the RTG's start position is written and valid", async () => /position_m: \[-55(\.0)?, 3\.5, 0(\.0)?\]/.test(await yaml()) &&
    (await page.textContent("#design-result")).includes("rtg_rehandle: valid"));
  // bulk: a heap added on the stockpile
  await load("mhc_pile_trim");
  await page.click("#design-add-heap");
  await until("a second heap is written", async () => ((await yaml()).match(/\{grid: stockpile, x_m/g) ?? []).length === 2);
  await until("and checked", async () => (await page.textContent("#design-result")).includes("mhc_pile_trim: valid"));
  await page.locator("#design-bulk").screenshot({ path: path.join(out, "console_designer_bulk.png") });
  // the preview draws the material: both heaps on the stockpile (coarsened as a station sends it)
  await until("the preview draws the piles", async () => Number(await page.getAttribute("#design-view", "data-bulk")) > 100);
  await page.locator("#design-preview").screenshot({ path: path.join(out, "console_designer_bulk_preview.png") });
  // the reach stacker's two lift jacks in the preview: each barrel from its eye on the chassis towards the
  // boom, the rod back from the boom's eye, in line and overlapping, the eyes between the rod's length and
  // both lengths apart (2.45 m boom down to 4.79 m at 60 degrees in its data)
  await load("reach_stacker_stack");
  await until("the reach stacker is checked", async () => (await page.textContent("#design-result")).includes("reach_stacker_stack: valid"));
  const jacks = JSON.parse((await page.getAttribute("#design-view", "data-jacks")) ?? "[]");
  check(jacks.length === 4, `two jacks drawn, a barrel and a rod each (${jacks.length} pieces)`);
  for (let k = 0; k + 1 < jacks.length; k += 2) {
    const [barrel, rod] = [jacks[k], jacks[k + 1]];
    const eyes = Math.hypot(rod[3] - barrel[0], rod[4] - barrel[1], rod[5] - barrel[2]);
    const direction = (s) => [s[3] - s[0], s[4] - s[1], s[5] - s[2]].map((v, _, a) => v / Math.hypot(...a));
    const inLine = direction(barrel).reduce((sum, v, i) => sum + v * direction(rod)[i], 0);
    check(eyes > 2.4 && eyes < 4.8 && inLine > 0.999,
      `jack ${k / 2 + 1}: eyes ${eyes.toFixed(2)} m apart, barrel and rod in line (cos ${inLine.toFixed(4)})`);
  }
  // general cargo on the MHC's hook: a second piece beside the first, going beside its target, given a mass
  await load("mhc_hook_lift");
  await page.click("#design-add-cargo");
  await until("a second piece and its move are written", async () =>
    /\{id: PIECE-2, size_m: \[5, 3, 3\.5\], mass_kg: 10000, position_m: \[-1, -10, 1\.75\]/.test(await yaml()) &&
    /\{cargo: PIECE-2, target_m: \[-9, 13, 1\.75\], tolerance_m: 0\.5\}/.test(await yaml()));
  await page.fill("#design-cargo-mass-1", "12000");
  await page.press("#design-cargo-mass-1", "Enter");
  await until("its mass is written and the design checked", async () => /mass_kg: 12000/.test(await yaml()) &&
    (await page.textContent("#design-result")).includes("mhc_hook_lift: valid") &&
    (await page.textContent("#design-summary")).includes("2 moves"));
  await page.locator("#design-cargo").screenshot({ path: path.join(out, "console_designer_cargo.png") });

  // every shipped exercise loads into the forms and checks valid, the page throwing nothing
  const pageErrors = [];
  page.on("pageerror", (e) => pageErrors.push(e.message));
  const shippedNames = readdirSync(path.join(data, "exercises")).filter((f) => f.endsWith(".yaml")).map((f) => f.slice(0, -5));
  for (const name of shippedNames) await load(name);
  check(pageErrors.length === 0 && (await page.locator("#design-forms fieldset").count()) >= 3,
    `all ${shippedNames.length} shipped exercises load into the forms (page errors: ${pageErrors.join("; ") || "none"})`);
  // a fault timed from the first lift: a hollow marker below the line; ticking it back to the exercise clock
  // rewrites the key
  await load("sts_hoist_brake_fault");
  await until("the lift-timed fault is drawn hollow", async () =>
    (await page.locator('#design-timeline circle[fill="#fff"]').count()) === 1);
  await page.locator("#design-timeline .event-marker").first().click();
  await page.uncheck("#design-event-from-lift");
  await until("it is written at_s", async () => /\{at_s: 8, kind: hoist_brake_fault/.test(await yaml()));
  await until("and checked", async () => (await page.textContent("#design-result")).includes("sts_hoist_brake_fault: valid"));

  // the sea as a sum of harmonics: a second roll harmonic added and given its own period
  await load("sts_discharge_gusty");
  await page.click("#design-sea-roll-add");
  await until("a second roll harmonic is written", async () => /roll: \[\{amplitude_deg: 0\.15[^\]]*\}, \{amplitude_deg: 0\.15, period_s: 12\.5\}\]/.test(await yaml()));
  await page.fill('input[data-path="vessel.sea_state.roll.1.period_s"]', "4.5");
  await page.press('input[data-path="vessel.sea_state.roll.1.period_s"]', "Enter");
  await until("its period is set and the design checked", async () => /period_s: 4\.5\}\]/.test(await yaml()) &&
    (await page.textContent("#design-result")).includes("sts_discharge_gusty: valid"));
  await page.locator("#design-weather").screenshot({ path: path.join(out, "console_designer_sea.png") });

  // what the designer may not overwrite, and who may not design
  const handmade = shipped.replace("name: sts_discharge", "name: handmade").replace(/^(\s+title:).*$/m,
    "$1 Handmade discharge");
  writeFileSync(path.join(exercises, "handmade.yaml"), handmade);
  const conflict = await page.evaluate(async (text) => {
    const me = await (await fetch("/api/me")).json();
    const r = await fetch("/api/designer/save", { method: "POST", headers: { "Content-Type": "application/json",
      "X-CSRF-Token": me.csrf }, body: JSON.stringify({ text }) });
    return { status: r.status, error: (await r.json()).error };
  }, handmade);
  check(conflict.status === 409 && !readFileSync(path.join(exercises, "handmade.yaml"), "utf8").includes("designed in"),
    `an exercise not made by the designer is not overwritten: ${conflict.status} ${conflict.error}`);
} catch (e) {
  check(false, `error: ${e.stack ?? e}`);
} finally {
  await browser?.close();
  await h.finish();
}
