// A signaller at work in a real browser: beside the instructor, a signaller logs in, sees the stations and
// nothing of the records or the instructor's controls, picks the crane, looks at it from the ground, and
// gives hand signals from buttons that draw each signal; the station shows the signal in the trainee's cab
// picture and calls it on the radio, refuses one the crane cannot follow, and the attempt's records time the
// operator's answers. Usage: node console_signaller.mjs HARBOURSIM OUT_DIR DOMAIN
import { Harness, launchChromium } from "./harness.mjs";
import fs, { mkdtempSync, mkdirSync } from "node:fs";
import { tmpdir } from "node:os";
import path from "node:path";

const [app, out, domain] = process.argv.slice(2);
mkdirSync(out, { recursive: true });
const dir = mkdtempSync(path.join(tmpdir(), "harbour-signaller-"));
const db = `sqlite3://db=${dir}/records.db`;
const h = new Harness(app);
const check = h.check.bind(h), run = h.run.bind(h), start = h.start.bind(h), until = h.until.bind(h);

// the pixels of the signal's panel in a 640x360 cab picture (its top right, under the HUD's lines) that are
// the signaller's high-visibility yellow
const yellowInPanel = (page) => page.$eval("#cab-picture", (img) => {
  const c = document.createElement("canvas");
  c.width = img.naturalWidth; c.height = img.naturalHeight;
  const g = c.getContext("2d");
  g.drawImage(img, 0, 0);
  const d = g.getImageData(500, 55, 140, 140).data;
  let n = 0;
  for (let k = 0; k < d.length; k += 4) if (d[k] > 180 && d[k + 1] > 140 && d[k + 2] < 110) n++;
  return n;
});

let browser;
try {
  run(["accounts", "add", "ines", "--role", "instructor", "--db", db], "ines-password\n");
  run(["accounts", "add", "sam", "--role", "signaller", "--db", db], "sam-password\n");
  const [url] = await h.console(db, domain);
  const played = path.join(dir, "station-sound.wav");
  fs.writeFileSync(path.join(dir, "alsoft.conf"), `[general]\ndrivers=wave\n[wave]\nfile=${played}\n`);
  start(["station", "--serve", "--name", "crane-1", "--domain", domain, "--db", db, "--window", "off",
    "--sound", "on"], { env: { ALSOFT_CONF: path.join(dir, "alsoft.conf") } });
  browser = await launchChromium();
  const login = async (name) => {
    const page = await (await browser.newContext()).newPage({ viewport: { width: 1280, height: 1000 } });
    await page.goto(url);
    await page.fill("#login-name", name);
    await page.fill("#login-password", `${name}-password`);
    await page.click("#login-form button");
    await until(`${name} is in`, async () => (await page.textContent("#who")).includes(name));
    await until(`${name} sees the station`, async () =>
      (await page.locator("#stations tr[data-station=crane-1] td:nth-child(2)").textContent().catch(() => "")) !== "");
    return page;
  };
  // the instructor starts the crane under its autopilot
  const ines = await login("ines");
  await page_start(ines);
  // the signaller: the stations, and in the station's panel the signals and the radio call only
  const sam = await login("sam");
  const shown = async (selector) => sam.locator(selector).first().isVisible();
  check(!(await shown("#records-panel")) && !(await shown("#designer-panel")) && !(await shown("#class-panel")),
    "the signaller's page has no records, designer or class");
  await sam.click("#stations tr[data-station=crane-1]");
  await until("the signal buttons show", async () => (await sam.locator("button.signal").count()) > 0);
  const signals = await sam.locator("button.signal").count();
  check(signals === 14 && await shown("button.signal[data-signal=hoist-slowly] svg polyline") &&
    await shown("#commands-sound button[data-kind=radio]") && !(await shown("button[data-kind=start]")) &&
    !(await shown("#commands-weather button")) && !(await shown("button[data-kind=mute]")),
    `${signals} signal buttons, each drawing the signaller; the radio call; no start, weather or sound buttons`);
  // from the ground: the 3D view's eye 1.7 m over the quay
  await until("the 3D view draws the crane", async () => (await sam.evaluate(() => window.harbourView?.visibleEntities() ?? 0)) > 10);
  await sam.click("#view-ground");
  const eye = await sam.evaluate(() => window.harbourView.cameraPosition());
  check(Math.abs(eye[2] - 1.7) < 0.5, `the view from the ground: eye at ${eye.map((v) => v.toFixed(1)).join(", ")} m`);
  await sam.locator("#view3d").screenshot({ path: path.join(out, "console_signaller_ground.png") });
  await until("the trainee's cab picture arrives", async () =>
    Number(await sam.getAttribute("#cab-picture", "data-frames") ?? 0) >= 2, 40);
  const before = await yellowInPanel(sam);
  // a hand signal: the station shows it in the cab and calls it on the radio
  await sam.click("button.signal[data-signal=stop]");
  await until("the station answers the signal", async () => /signal:stop: done/.test(await sam.textContent("#command-result")));
  const answer = await sam.textContent("#command-result");
  check(/sees "stop" and hears it on the radio/.test(answer), `the answer: ${answer}`);
  await until("the cab picture shows the signaller", async () => (await yellowInPanel(sam)) > 150, 20);
  const after = await yellowInPanel(sam);
  check(before < 40 && after > 150, `yellow pixels where the cab draws the signal: ${before} before, ${after} after`);
  await sam.locator("#cab-figure").screenshot({ path: path.join(out, "console_signaller_cab.png") });
  await sam.locator("#control-panel").screenshot({ path: path.join(out, "console_signaller_panel.png") });
  // one the STS cannot follow (it does not slew) is refused by the station, saying why
  await sam.click("button.signal[data-signal=slew-left]");
  await until("the slew signal is answered", async () => /slew left refused|signal:slew-left refused/.test(await sam.textContent("#command-result")));
  check(/slew/.test(await sam.textContent("#command-result")), `refused: ${await sam.textContent("#command-result")}`);
  await sam.click("button.signal[data-signal=lower]");
  await until("the lower signal is done", async () => /signal:lower: done/.test(await sam.textContent("#command-result")));
  // a signaller's limits, at the API
  const refused = await sam.evaluate(async () => {
    const me = await (await fetch("/api/me")).json();
    const post = (p, b) => fetch(p, { method: "POST", headers: { "Content-Type": "application/json", "X-CSRF-Token": me.csrf }, body: JSON.stringify(b) });
    const hold = await post("/api/stations/crane-1/command", { kind: "hold" });
    return { hold: hold.status, why: (await hold.json()).error, attempts: (await fetch("/api/attempts")).status,
      trainees: (await fetch("/api/trainees")).status, radio: (await post("/api/stations/crane-1/command", { kind: "radio:all clear" })).status };
  });
  check(refused.hold === 403 && /signals and radio calls only/.test(refused.why) && refused.attempts === 403 &&
    refused.trainees === 403 && refused.radio === 200, `a signaller's limits: ${JSON.stringify(refused)}`);
  // the instructor stops the attempt once "lower" has had its time: its records count the signals and time the
  // operator's answer (the autopilot does not watch the signaller: "lower" is either followed as it happens to
  // lower, or late)
  await sam.waitForTimeout(3000);
  await ines.click("button[data-kind=stop]");
  await until("the attempt is stored", async () =>
    (await ines.locator("#stations tr[data-station=crane-1] td:nth-child(2)").textContent()) === "idle", 40);
  const metrics = await ines.evaluate(async () => {
    const list = await (await fetch("/api/attempts")).json();
    const last = list.reduce((a, b) => (a.id > b.id ? a : b));
    return (await (await fetch(`/api/attempts/${last.id}`)).json()).metrics;
  });
  check(metrics.signals === 2 && (metrics.late_signals >= 1 || metrics.worst_signal_delay_s >= 0),
    `the attempt's signal figures: ${metrics.signals} signals, ${metrics.late_signals} late, slowest answer ${metrics.worst_signal_delay_s?.toFixed(2) ?? "none"} s`);
} catch (e) {
  check(false, `error: ${e.stack ?? e}`);
} finally {
  await browser?.close();
  await h.finish();
}

async function page_start(page) {
  await page.click("#stations tr[data-station=crane-1]");
  await page.selectOption("#exercise", "sts_discharge");
  await page.check("#autopilot");
  await page.click("button[data-kind=start]");
  await until("the exercise runs", async () =>
    (await page.locator("#stations tr[data-station=crane-1] td:nth-child(2)").textContent()) === "running", 40);
}
