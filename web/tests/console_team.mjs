// A team session run from the console in a real browser: two served stations, each started as a role of
// sts_and_tractor (the crane, the tractor) by the instructor; the table says who is which member, each station
// announces the other, the crane's 3D view holds the tractor; both stopped.
// Usage: node console_team.mjs HARBOURSIM OUT_DIR DOMAIN
import { Harness, launchChromium } from "./harness.mjs";
import { wireErrors } from "./wire.mjs";
import { mkdtempSync, mkdirSync } from "node:fs";
import { tmpdir } from "node:os";
import path from "node:path";

const [app, out, domain] = process.argv.slice(2);
mkdirSync(out, { recursive: true });
const dir = mkdtempSync(path.join(tmpdir(), "harbour-team-"));
const db = `sqlite3://db=${dir}/records.db`;
const h = new Harness(app);
const check = h.check.bind(h), run = h.run.bind(h), start = h.start.bind(h), until = h.until.bind(h);

let browser;
try {
  run(["accounts", "add", "ines", "--role", "instructor", "--db", db], "ines-password\n");
  const [url] = await h.console(db, domain);
  for (const name of ["crane-cab", "tractor-cab"])
    start(["station", "--serve", "--name", name, "--domain", domain, "--db", db, "--window", "off"]);
  browser = await launchChromium();
  const page = await browser.newPage({ viewport: { width: 1280, height: 1100 } });
  await page.goto(url);
  await page.fill("#login-name", "ines");
  await page.fill("#login-password", "ines-password");
  await page.click("#login-form button");
  const cell = (station, n) => page.locator(`#stations tr[data-station=${station}] td:nth-child(${n})`).textContent().catch(() => "");
  for (const name of ["crane-cab", "tractor-cab"])
    await until(`${name} shows, idle`, async () => (await cell(name, 2)) === "idle", 40);

  // each station started as its role: the team's roles offered once a team is chosen
  for (const [station, role] of [["crane-cab", "crane"], ["tractor-cab", "tractor"]]) {
    await page.click(`#stations tr[data-station=${station}]`);
    await page.selectOption("#start-team", "sts_and_tractor");
    const roles = await page.locator("#start-role option").allTextContents();
    check(roles.join(", ") === "crane: First discharge onto a truck, tractor: Park a mafi in its lane", `the team's roles offered: ${roles.join(", ")}`);
    await page.selectOption("#start-role", role);
    await page.check("#autopilot");
    await page.click("button[data-kind=start]");
    await until(`${station} acknowledges`, async () =>
      (await page.textContent("#command-result")) === `start: starting ${role} of team sts_and_tractor`, 20);
  }
  await until("both run, each named as its role of the team", async () =>
    (await cell("crane-cab", 2)) === "running" && (await cell("tractor-cab", 2)) === "running" &&
    (await cell("crane-cab", 4)) === "First discharge onto a truck (crane of team sts and tractor)" &&
    (await cell("tractor-cab", 4)) === "Park a mafi in its lane (tractor of team sts and tractor)", 90);

  // the tractor's station (selected, started last) announces the crane; the crane's 3D view holds the tractor
  await until("the tractor's station says the crane joined", async () =>
    (await page.locator("#events li").allTextContents()).some((t) => t.includes("team: crane: joined (crane-cab)")), 30);
  await page.click("#stations tr[data-station=crane-cab]");
  await until("the crane's 3D view holds the tractor and its trailer", async () => page.evaluate(() => {
    const names = window.harbourView?.names ?? [];
    return names.includes("tractor: tractor") && names.includes("tractor: trailer");
  }), 30);
  const drawnAt = () => page.evaluate(() => {
    const v = window.harbourView, at = v.entities[v.names.indexOf("tractor: tractor")].position;
    return [at.x, at.y, at.z];
  });
  await until("the crane's view draws the tractor on the quay, on its wheels", async () => {
    const [x, y, z] = await drawnAt();
    return Math.abs(x) < 10 && y > -45 && y < 40 && z > 0.5 && z < 3;
  }, 20);
  await page.uncheck("#view-light");
  const tractorAt = await page.evaluate(() => {  // looking at the tractor from behind it, the crane beyond
    const v = window.harbourView;
    const at = v.entities[v.names.indexOf("tractor: tractor")].position;
    v.camera.position.set(at.x - 22, at.y - 30, at.z + 18);
    v.controls.target.set(at.x + 4, at.y + 12, at.z);
    v.controls.update();
    return [at.x, at.y, at.z];
  });
  check(tractorAt[2] > 0.5, `the crane's view draws the tractor at (${tractorAt.map((c) => c.toFixed(1)).join(", ")}) m`);
  await page.waitForTimeout(4000);
  await page.locator("#view3d").screenshot({ path: path.join(out, "console_team.png") });

  // the instructor holds the whole team, resumes it and ends it, from one member's panel
  const teamCommand = async (kind, state) => {
    await page.click(`button[data-team-kind=${kind}]`);
    await until(`team ${kind} answered`, async () =>
      /^team sts and tractor \w+: (crane-cab|tractor-cab) done, (crane-cab|tractor-cab) done$/.test(await page.textContent("#command-result")), 20);
    check(true, `team ${kind}: ${await page.textContent("#command-result")}`);
    if (state) await until(`both ${state}`, async () => (await cell("crane-cab", 2)) === state && (await cell("tractor-cab", 2)) === state, 20);
  };
  check(await page.isVisible("#team-actions"), "the team's buttons show for a member");
  await page.locator("#stations").screenshot({ path: path.join(out, "console_team_stations.png") });
  await page.locator("#control-panel").screenshot({ path: path.join(out, "console_team_panel.png") });
  // fog over both (recorded in each member's run: the session's replay lists it for each)
  const fogged = await page.evaluate(async () => {
    const me = await (await fetch("/api/me")).json();
    const answers = [];
    for (const station of ["crane-cab", "tractor-cab"])
      answers.push((await fetch(`/api/stations/${station}/command`, { method: "POST", headers: {
        "Content-Type": "application/json", "X-CSRF-Token": me.csrf }, body: JSON.stringify({ kind: "visibility:800" }) })).status);
    return answers;
  });
  check(fogged.every((status) => status === 200), `fog commanded on both members: ${fogged.join(", ")}`);
  await teamCommand("hold", "held");
  await teamCommand("resume", "running");
  await teamCommand("stop", null);
  await until("both idle again", async () => (await cell("crane-cab", 2)) === "idle" && (await cell("tractor-cab", 2)) === "idle", 40);
  const last = await cell("tractor-cab", 10);
  check(/tractor of team sts_and_tractor/.test(last), `the tractor's last attempt said: ${last}`);
  // both attempts stored as the team's members, linked by one session
  const attempts = await page.evaluate(async () => (await fetch("/api/attempts")).json());
  const members = attempts.filter((a) => a.team === "sts_and_tractor");
  const sessions = new Set(members.map((a) => a.team_session));
  check(members.length === 2 && members.map((a) => a.team_role).sort().join(",") === "crane,tractor" &&
    sessions.size === 1 && /^sts_and_tractor@\d{4}-\d\d-\d\dT\d\d:\d\d:\d\dZ$/.test([...sessions][0]),
    `the members' attempts: ${JSON.stringify(members.map((a) => [a.id, a.team_role, a.team_session]))}`);
  const session = [...sessions][0];
  await until("the records table names both members and their session", async () => {
    const rows = await page.locator("#attempts tbody tr td:nth-child(3)").allTextContents();
    return rows.includes(`First discharge onto a truck (crane of ${session})`) &&
      rows.includes(`Park a mafi in its lane (tractor of ${session})`);
  }, 20);
  await page.locator("#attempts").screenshot({ path: path.join(out, "console_team_records.png") });

  // the session replayed as a whole: both members' machines in one scene on the session's clock
  const opened = await page.evaluate(async (name) => {
    const me = await (await fetch("/api/me")).json();
    const open = async (body) => {
      const r = await fetch("/api/replays", { method: "POST", headers: { "Content-Type": "application/json",
        "X-CSRF-Token": me.csrf }, body: JSON.stringify(body) });
      return { status: r.status, body: await r.json() };
    };
    const whole = await open({ session: name }), none = await open({ session: "no_such_team@2026" });
    if (whole.status === 201) await fetch(`/api/replays/${whole.body.replay}`, { method: "POST",
      headers: { "Content-Type": "application/json", "X-CSRF-Token": me.csrf }, body: JSON.stringify({ action: "close" }) });
    return { whole, none };
  }, session);
  check(opened.whole.status === 201 && opened.whole.body.session === session &&
    (opened.whole.body.members ?? []).map((m) => m.role).join(",") === "crane,tractor",
  `the session opens as one replay, the crane first: ${opened.whole.status} ${JSON.stringify(opened.whole.body.members ?? opened.whole.body.error)}`);
  const said = (opened.whole.body.events ?? []).map((e) => e.text);
  check(said.filter((t) => /^(crane|tractor): instructor: visibility$/.test(t)).length === 2 &&
    said.every((t) => /^(crane|tractor): [^_]+$/.test(t)),
    `the session's timeline says each event in words with its member's role: ${said.slice(0, 4).join("; ")}`);
  check(wireErrors(opened.whole.body, "ReplayInfo").length === 0,
    `the session's replay is as schema/wire.json says: ${wireErrors(opened.whole.body, "ReplayInfo").join("; ")}`);
  check(opened.none.status === 404 && /no team session 'no_such_team@2026'/.test(opened.none.body.error),
    `a session nobody ran: ${opened.none.status} (${opened.none.body.error})`);
  await page.locator("#attempts tbody tr", { hasText: `tractor of ${session}` }).click();
  await until("a member's attempt offers its session's replay", async () => page.isVisible("#open-session-replay"), 10);
  await page.click("#open-session-replay");
  await until("the session's replay opens, naming its members", async () =>
    /^team session \S+: crane \(attempt \d+, \w+(, from \d+\.\d s)?\), tractor \(attempt \d+, \w+/.test(await page.textContent("#replay-title")), 20);
  const middle = opened.whole.body.duration_s / 2;
  await page.$eval("#replay-scrub", (e, at) => { e.value = String(at); e.dispatchEvent(new Event("change")); }, middle);
  await until("the replay shows its middle", async () => Math.abs(parseFloat(await page.textContent("#replay-time")) - middle) < 0.1, 30);
  await until("the replay's 3D view draws the crane and the tractor, the tractor on the quay", async () => page.evaluate(() => {
    const v = window.harbourView;
    if (!v?.drawnStation().startsWith("replay-")) return false;
    const shown = (name) => v.entities.find((e, k) => v.names[k] === name && e.visible);
    const tractor = shown("tractor");
    return shown("gantry") !== undefined && tractor !== undefined && tractor.position.z > 0.5 && tractor.position.z < 3;
  }), 20);
  check(!(await page.isVisible("#take-over")), "a session's replay offers no take-over (a member's own replay does)");
  await page.locator("#view3d").screenshot({ path: path.join(out, "console_team_replay.png") });
  await page.locator("#replay-panel").screenshot({ path: path.join(out, "console_team_replay_panel.png") });
  await page.click("#replay-close");
  await page.click("#stations tr[data-station=crane-cab]");

  // the whole team started again as one: a free station and a trainee for each role, one button (the roles
  // swapped between the stations this time)
  await page.selectOption("#start-team", "sts_and_tractor");
  const about = await page.textContent("#exercise-about");
  check(about === "Team sts and tractor: crane, First discharge onto a truck; tractor, Park a mafi in its lane.",
    `with the team chosen, the line under the start says what each role runs: ${about}`);
  await until("the team's start row offers both idle stations for each role", async () =>
    (await page.locator("#team-start-station-crane option").count()) === 2 &&
    (await page.locator("#team-start-station-tractor option").count()) === 2);
  await page.selectOption("#team-start-station-crane", "tractor-cab");
  await page.selectOption("#team-start-station-tractor", "crane-cab");
  await page.check("#autopilot");
  await page.locator("#control-panel").screenshot({ path: path.join(out, "console_team_start.png") });
  await page.click("#team-start-go");
  await until("the team starts as one", async () => /^team sts and tractor started: (crane-cab|tractor-cab) done, (crane-cab|tractor-cab) done$/
    .test(await page.textContent("#command-result")), 30);
  await until("each station runs the role chosen for it", async () =>
    (await cell("tractor-cab", 4)) === "First discharge onto a truck (crane of team sts and tractor)" &&
    (await cell("crane-cab", 4)) === "Park a mafi in its lane (tractor of team sts and tractor)", 60);
  // started again while it runs: refused whole, naming the busy station, nothing sent
  const again = await page.evaluate(async () => {
    const me = await (await fetch("/api/me")).json();
    const r = await fetch("/api/teams/sts_and_tractor/start", { method: "POST", headers: { "Content-Type": "application/json",
      "X-CSRF-Token": me.csrf }, body: JSON.stringify({ members: [{ role: "crane", station: "crane-cab" }, { role: "tractor", station: "tractor-cab" }] }) });
    return { status: r.status, body: await r.json() };
  });
  check(again.status === 409 && /is not idle on the network \(running\)/.test(again.body.error), `a second team start while it runs: ${again.status} (${again.body.error})`);
  await page.click("#stations tr[data-station=crane-cab]");
  await teamCommand("stop", null);
  await until("both idle once more", async () => (await cell("crane-cab", 2)) === "idle" && (await cell("tractor-cab", 2)) === "idle", 40);
  const figures = await page.evaluate(async (id) => (await fetch(`/api/attempts/${id}`)).json(), members[0]?.id);
  check(figures.metrics?.team_near_misses === 0 && figures.metrics?.team_closest_m > 1,
    `a member's team figures: near misses ${figures.metrics?.team_near_misses}, closest ${figures.metrics?.team_closest_m?.toFixed(1)} m`);
} catch (e) {
  check(false, `error: ${e.stack ?? e}`);
} finally {
  await browser?.close();
  await h.finish();
}
