// An instructor's day in a real browser (Debian chromium driven by playwright-core), asserting what the page
// says: two stations run exercises for two trainees; a fault is injected and cleared; an attempt is ended by
// the instructor and the panel says so; its replay is taken over on a free station; the designer makes a
// centre copy of an exercise and saves it under a title of its own; a trainee is enrolled in a route; the
// results are filtered and sorted, an attempt's debrief read, the reports opened. Each panel is audited with
// axe-core (no serious or critical violation) and photographed at 1280x720 and at a tablet's width, in the
// light and the dark theme; the trainee's own page shows no raw key.
// Usage: node console_day.mjs HARBOURSIM OUT_DIR DOMAIN
import { Harness, launchChromium } from "./harness.mjs";
import { existsSync, mkdtempSync, mkdirSync, readdirSync, readFileSync, symlinkSync } from "node:fs";
import { createRequire } from "node:module";
import { tmpdir } from "node:os";
import path from "node:path";
import { fileURLToPath } from "node:url";

const [app, out, domain] = process.argv.slice(2);
if (!app || !out || !domain) { console.error("usage: console_day.mjs HARBOURSIM OUT_DIR DOMAIN"); process.exit(2); }
mkdirSync(out, { recursive: true });
const dir = mkdtempSync(path.join(tmpdir(), "harbour-day-"));
const db = `sqlite3://db=${dir}/records.db`;
const h = new Harness(app);
const check = h.check.bind(h), run = h.run.bind(h), start = h.start.bind(h), until = h.until.bind(h);
const axeSource = readFileSync(createRequire(import.meta.url).resolve("axe-core/axe.min.js"), "utf8");

// axe-core over the page as it is: the serious and critical violations, each with the elements it found
async function audit(page, what) {
  // evaluated through the browser's debugging protocol: the page's content security policy allows no inline script
  if (!(await page.evaluate(() => typeof window.axe === "object"))) await page.evaluate(axeSource);
  const result = await page.evaluate(async () => (await window.axe.run(document, { resultTypes: ["violations"] })).violations
    .filter((v) => v.impact === "serious" || v.impact === "critical")
    .map((v) => `${v.id} (${v.impact}): ${v.nodes.slice(0, 3).map((n) => n.target.join(" ")).join("; ")}`));
  check(result.length === 0, `axe-core finds no serious violation ${what}${result.length ? `:\n     ${result.join("\n     ")}` : ""}`);
}
// the text a person sees on the page (hidden sections left out)
const visibleText = (page) => page.evaluate(() => document.body.innerText);
// raw keys: snake_case words as the records store them (file names and paths left out)
const rawKeys = (text) => [...new Set(text.split(/\s+/).filter((w) => /^[a-z]+_[a-z0-9_]+$/.test(w.replace(/[(),.:;]/g, ""))))];

let browser;
try {
  for (const [id, name] of [["anna", "Anna Berg"], ["ben", "Ben Olsen"], ["carl", "Carl Dahl"]])
    run(["trainees", "add", id, name, "--db", db]);
  // yesterday's work: finished attempts for the results, the evolution and the reports
  for (const who of ["anna", "ben"]) run(["run", "--exercise", "sts_discharge", "--autopilot", "--trainee", who, "--db", db]);
  run(["run", "--exercise", "tractor_mafi_park", "--autopilot", "--trainee", "carl", "--db", db]);
  run(["accounts", "add", "ines", "--role", "instructor", "--db", db], "ines-password\n");
  run(["accounts", "add", "anna", "--role", "trainee", "--trainee", "anna", "--db", db], "anna-password\n");
  // the centre's own exercise folder, where the designer saves (never among the shipped ones), beside the
  // shipped machines, vessels, ... (linked) that its exercises name
  const data = path.join(path.dirname(fileURLToPath(import.meta.url)), "..", "..", "data");
  const exercises = path.join(dir, "centre", "exercises");
  mkdirSync(exercises, { recursive: true });
  for (const entry of readdirSync(data))
    if (entry !== "exercises" && entry !== "routes") symlinkSync(path.join(data, entry), path.join(dir, "centre", entry));
  const c = start(["console", "--db", db, "--domain", domain, "--port", "0", "--exercises", exercises]);
  await until("the console listens", () => /http:\/\/127\.0\.0\.1:\d+\//.test(c.output));
  const url = c.output.match(/http:\/\/127\.0\.0\.1:\d+\//)[0];
  for (const name of ["day-1", "day-2"])
    start(["station", "--serve", "--name", name, "--domain", domain, "--db", db, "--window", "off", "--sound", "off"]);

  browser = await launchChromium();
  const context = await browser.newContext({ viewport: { width: 1280, height: 720 } });
  const page = await context.newPage();
  const pageErrors = [];
  page.on("pageerror", (e) => pageErrors.push(e.message));
  await page.goto(url);
  await audit(page, "on the login page");
  await page.fill("#login-name", "ines");
  await page.fill("#login-password", "ines-password");
  await page.click("#login-form button");
  const stateOf = (station) => page.locator(`#stations tr[data-station=${station}] td:nth-child(2)`).textContent().catch(() => "");
  await until("both stations show, idle", async () => (await stateOf("day-1")) === "idle" && (await stateOf("day-2")) === "idle");

  // morning: ben on the STS, carl on the tractor, each exercise picked by its title, what it asks shown
  await page.click("#stations tr[data-station=day-1]");
  const titles = await page.locator("#exercise optgroup").evaluateAll((groups) =>
    groups.map((g) => `${g.label}: ${[...g.querySelectorAll("option")].length}`));
  check(titles.some((t) => t.startsWith("ship-to-shore gantry crane:")) && titles.some((t) => t.startsWith("ro-ro terminal tractor:")),
    `the exercises are grouped by machine (${titles.join(", ")})`);
  await page.selectOption("#exercise", "sts_discharge");
  await until("the exercise says what it asks", async () =>
    /truck under the crane\. Beginner, about 3 min\./.test(await page.textContent("#exercise-about")));
  await page.selectOption("#trainee", "ben");
  await page.check("#autopilot");
  await page.click("button[data-kind=start]");
  await until("day-1 runs", async () => (await stateOf("day-1")) === "running", 40);
  await page.click("#stations tr[data-station=day-2]");
  await page.selectOption("#exercise", "tractor_mafi_park");
  await page.selectOption("#trainee", "carl");
  await page.check("#autopilot");
  await page.click("button[data-kind=start]");
  await until("day-2 runs", async () => (await stateOf("day-2")) === "running", 40);
  // the tractor has no hoist brake, twistlocks or limiter: none of their faults is offered, its stops are
  const shown = async (kind) => page.isVisible(`button[data-kind="${kind}"]`);
  await until("the tractor's panel offers no fault of a part it lacks", async () =>
    !(await shown("hoist-brake-fault")) && !(await shown("landed-sensor-fault")) && !(await shown("limiter-fault")) &&
    !(await shown("clear-faults")) && await shown("emergency-stop") && await shown("power-failure"));
  // its live line is its cab's HUD: its own lines first, its speed once (its line replaces the harbour's)
  await until("the tractor's live line reads as its cab's HUD", async () => {
    const live = await page.textContent("#live");
    return /speed -?\d+ km\/h\s+selector [RND]\s+gear \d/.test(live) && live.split("speed").length === 2;
  });
  const row1 = await page.locator("#stations tr[data-station=day-1] td").allTextContents();
  check(row1[2] === "ship-to-shore gantry crane" && row1[3] === "First discharge onto a truck" && row1[4] === "ben",
    `the stations table names the machine and the exercise in words (${row1.slice(0, 5).join(" | ")})`);
  await page.screenshot({ path: path.join(out, "day_stations_1280.png") });
  await audit(page, "with two stations running");

  // a fault on the STS: its lamp in the live line, cleared again
  await page.click("#stations tr[data-station=day-1]");
  await until("day-1's live line", async () => /load -?\d+\.\d t/.test(await page.textContent("#live")));
  await until("the STS's panel offers its hoist brake's and twistlocks' faults, not a limiter's", async () =>
    await shown("hoist-brake-fault") && await shown("landed-sensor-fault") && await page.isVisible("#command-landed-sensor-fault-0") && !(await shown("limiter-fault")) &&
    await shown("clear-faults"));
  await page.click("button[data-kind=hoist-brake-fault]");
  await until("the fault is in force", async () => (await page.textContent("#live-faults")).includes("BRAKE FAULT"));
  await page.click("button[data-kind=clear-faults]");
  await until("and cleared", async () => await page.isHidden("#live-faults"));
  // ended by the instructor: the panel says how, in words
  await page.waitForTimeout(2000);
  await page.click("button[data-kind=stop]");
  await until("day-1 is idle again", async () => (await stateOf("day-1")) === "idle", 40);
  await until("the panel says how ben's attempt ended", async () =>
    /^Last: attempt \d+ ended by the instructor, score [\d.]+ \(First discharge onto a truck\)$/.test(
      (await page.textContent("#attempt-outcome")) ?? ""), 40);
  await page.screenshot({ path: path.join(out, "day_ended_1280.png") });

  // the results: filtered to ben, newest first; sorted by score; the stopped attempt's debrief in words
  await page.selectOption("#filter-trainee", "ben");
  await until("only ben's attempts are listed", async () =>
    (await page.locator("#attempts tbody tr").count()) === 2 &&
    (await page.locator("#attempts tbody tr td:nth-child(2)").allTextContents()).every((t) => t === "ben"));
  check(/^2 of \d+ attempts$/.test(await page.textContent("#attempts-shown")), `the count of what is shown (${await page.textContent("#attempts-shown")})`);
  const ids = async () => (await page.locator("#attempts tbody tr td:nth-child(1)").allTextContents()).map(Number);
  const newest = await ids();
  check(newest[0] > newest[1], `newest first (${newest.join(", ")})`);
  await page.click("#attempts thead th:nth-child(5) button");
  await until("sorted by score, best first", async () => {
    const scores = (await page.locator("#attempts tbody tr td:nth-child(5)").allTextContents()).map(Number);
    return scores.length === 2 && scores[0] >= scores[1];
  });
  check((await page.getAttribute("#attempts thead th:nth-child(5)", "aria-sort")) === "descending", "the sorted column says so");
  await page.selectOption("#filter-outcome", "ended by the instructor");
  await until("only the stopped attempt", async () => (await page.locator("#attempts tbody tr").count()) === 1);
  const stopped = Number(await page.locator("#attempts tbody tr td:nth-child(1)").textContent());
  // by keyboard: the row takes the focus and Enter opens it
  await page.focus("#attempts tbody tr");
  await page.keyboard.press("Enter");
  await until("its debrief opens", async () =>
    (await page.textContent("#attempt-detail")).includes(`Attempt ${stopped}: ben on First discharge onto a truck, ended by the instructor`));
  const debrief = (await page.textContent("#attempt-detail")).split("recording:")[0];
  check(rawKeys(debrief).length === 0 && /time\s*[\d.]+ s/.test(debrief) && /hoist energy\s*[\d.]+ MJ/.test(debrief),
    `the debrief is words (raw keys: ${rawKeys(debrief).join(", ") || "none"})`);
  await page.locator("#records-panel").scrollIntoViewIfNeeded().catch(() => {});
  await page.screenshot({ path: path.join(out, "day_results_1280.png") });
  await audit(page, "on the results and a debrief");

  // its replay taken over on the free station at 2 s, for anna
  await page.click("#open-replay");
  await until("the replay opens", async () => (await page.textContent("#replay-time")).startsWith("0.0 /"));
  check(/instructor: hoist brake fault/.test(await page.textContent("#replay-events")), "the replay's events are words");
  await page.$eval("#replay-scrub", (e) => { e.value = "2"; e.dispatchEvent(new Event("change")); });
  await until("the replay shows 2 s", async () => Math.abs(parseFloat(await page.textContent("#replay-time")) - 2) < 0.05);
  await page.click("#replay-pause");
  await until("day-1 is offered for the take-over", async () => (await page.inputValue("#takeover-station")) === "day-1", 40);
  await page.locator("#replay-panel").screenshot({ path: path.join(out, "day_replay_1280.png") });
  await page.selectOption("#takeover-trainee", "anna");
  await page.check("#takeover-autopilot");
  await page.click("#take-over");
  await until("the take-over runs on day-1", async () => (await stateOf("day-1")) === "running", 40);
  const branch = (await page.evaluate(async () => (await fetch("/api/attempts")).json())).find((a) => a.parent === stopped);
  check(branch?.trainee === "anna", `the branch is anna's, its parent attempt ${stopped}`);
  await page.click("#stations tr[data-station=day-1]");
  await page.click("button[data-kind=stop]");
  await page.click("#stations tr[data-station=day-2]");
  await page.click("button[data-kind=stop]");
  await until("both stations idle at the end of the session", async () =>
    (await stateOf("day-1")) === "idle" && (await stateOf("day-2")) === "idle", 40);

  // the designer: a centre copy of the first discharge with a longer time limit, saved under its own title
  await page.selectOption("#design-base", "sts_discharge");
  await page.click("#design-load");
  await until("the shipped exercise is loaded and checked", async () => (await page.textContent("#design-result")).includes("sts_discharge: valid"));
  check((await page.inputValue("#design-about-title")) === "First discharge onto a truck (centre copy)",
    "the copy's title is its own");
  const deductions = await page.locator("#design-rubric [id^=design-rule-]").evaluateAll((e) => e.map((x) => x.id));
  check(deductions.includes("design-rule-twistlock_misuse") && !deductions.includes("design-rule-jackknife") &&
    !deductions.includes("design-rule-pad_lift_off"), "the rubric offers only what an STS operator can incur");
  await page.fill("#design-name", "sts_discharge_long");
  await page.press("#design-name", "Enter");
  await page.fill("#design-about-title", "First discharge, four minutes");
  await page.press("#design-about-title", "Enter");
  await page.fill("#design-rule-time_limit_s", "240");
  await page.press("#design-rule-time_limit_s", "Enter");
  await until("the edit is checked", async () => (await page.textContent("#design-result")).includes("sts_discharge_long: valid"));
  await page.locator("#designer-panel").scrollIntoViewIfNeeded();
  await page.screenshot({ path: path.join(out, "day_designer_1280.png") });
  await audit(page, "on the designer");
  await page.click("#design-save");
  await until("it is saved", async () => (await page.textContent("#design-result")).startsWith("saved"));
  check(existsSync(path.join(exercises, "sts_discharge_long.yaml")), "saved in the centre's folder");
  await until("the start list offers it by its title", async () =>
    (await page.locator('#exercise option[value=sts_discharge_long]').textContent().catch(() => "")).startsWith("First discharge, four minutes"));

  // a route: anna enrolled in the STS route; her progress in words
  await page.selectOption("#progress-trainee", "anna");
  await page.selectOption("#route", "sts_basic");
  await page.click("#enrol-form button[type=submit]");
  await until("anna is enrolled", async () => (await page.textContent("#enrol-result")) === "enrolled");
  await until("her progress names the stages' exercises by title", async () =>
    (await page.locator("#progress table[data-route=sts_basic] tr[data-stage=single_lift] td:nth-child(3)").textContent()
      .catch(() => "")) === "First discharge onto a truck");
  await page.locator("#routes-panel").scrollIntoViewIfNeeded();
  await page.screenshot({ path: path.join(out, "day_routes_1280.png") });
  await audit(page, "on the routes and the evolution");

  // the reports: ben's, as an instructor reads it, and the class's
  const report = await page.evaluate(async () => (await fetch("/api/reports/trainee?trainee=ben")).text());
  const standings = report.slice(report.indexOf("Standing in the cohort"));
  check(/<td>hoist energy<\/td>/.test(standings) && /[\d.]+ MJ/.test(standings) && !/hoist_energy_j|>time_s</.test(standings),
    "ben's report names each figure in words with its unit");
  const classReport = await page.evaluate(async () => (await fetch("/api/reports/class")).text());
  check(/Class report/.test(classReport) && /Ben Olsen/.test(classReport) && /Carl Dahl/.test(classReport),
    "the class report lists the trainees by name");

  await page.locator("#class-panel").screenshot({ path: path.join(out, "day_class_1280.png") });

  // the whole page again at a tablet's width, and in the dark theme
  await page.setViewportSize({ width: 820, height: 1180 });
  await page.evaluate(() => window.scrollTo(0, 0));
  await page.screenshot({ path: path.join(out, "day_stations_tablet.png") });
  const overflow = await page.evaluate(() => document.documentElement.scrollWidth - window.innerWidth);
  check(overflow <= 0, `at 820 px nothing runs off the side of the page (${overflow} px)`);
  await page.locator("#records-panel").scrollIntoViewIfNeeded().catch(() => {});
  await page.screenshot({ path: path.join(out, "day_results_tablet.png") });
  await page.click("#theme");
  const dark = await page.evaluate(() => ({ theme: document.documentElement.dataset.theme,
    background: getComputedStyle(document.body).backgroundColor, remembered: localStorage.getItem("theme") }));
  check(dark.theme === "dark" && dark.background === "rgb(21, 24, 30)" && dark.remembered === "dark",
    `the dark theme, remembered (${JSON.stringify(dark)})`);
  await audit(page, "in the dark theme");
  await page.setViewportSize({ width: 1280, height: 720 });
  await page.evaluate(() => window.scrollTo(0, 0));
  await page.screenshot({ path: path.join(out, "day_stations_dark_1280.png") });
  await page.locator("#designer-panel").scrollIntoViewIfNeeded();
  await page.screenshot({ path: path.join(out, "day_designer_dark_1280.png") });
  // what an instructor reads, the designer's and the route editor's file names and YAML aside
  const instructorReads = await page.evaluate(() => [...document.querySelectorAll("section:not([hidden])")]
    .filter((s) => s.id !== "designer-panel" && s.id !== "route-editor-panel").map((s) => s.innerText).join("\n"));
  const instructorKeys = rawKeys(instructorReads);
  check(instructorKeys.length === 0, `the instructor's panels show no raw key (${instructorKeys.map((k) => {
    const at = instructorReads.indexOf(k);
    return `'${instructorReads.slice(Math.max(0, at - 60), at + k.length + 10).replace(/\s+/g, " ")}'`;
  }).join(", ") || "none"})`);
  check(pageErrors.length === 0, `the instructor's page threw nothing (${pageErrors.join("; ") || "none"})`);

  // anna's own page: her results and progress, no raw key anywhere she can see
  const trainee = await (await browser.newContext({ viewport: { width: 1280, height: 720 } })).newPage();
  await trainee.goto(url);
  await trainee.fill("#login-name", "anna");
  await trainee.fill("#login-password", "anna-password");
  await trainee.click("#login-form button");
  await until("anna sees her attempts", async () => (await trainee.locator("#attempts tbody tr").count()) >= 2);
  await trainee.locator("#attempts tbody tr").first().click();
  await until("and a debrief", async () => (await trainee.textContent("#attempt-detail")).startsWith("Attempt"));
  await trainee.waitForTimeout(1500);
  const seen = await visibleText(trainee);
  check(rawKeys(seen).length === 0 && !/[{}]/.test(seen), `anna's page shows no raw key or JSON (${rawKeys(seen).join(", ") || "none"})`);
  await trainee.screenshot({ path: path.join(out, "day_trainee_1280.png"), fullPage: true });
  await audit(trainee, "on the trainee's page");
} catch (e) {
  check(false, `error: ${e.stack ?? e}`);
} finally {
  await browser?.close();
  await h.finish();
}
