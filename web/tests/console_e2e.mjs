// End to end in a real browser (Debian chromium driven by playwright-core): an instructor logs in, starts an
// exercise on a station process, changes the wind and sees it in the telemetry, injects a hoist brake fault
// and sees its lamp and the event, repairs it, holds and resumes; a trainee is refused instructor actions and
// sees only their own results. Usage: node console_e2e.mjs HARBOURSIM OUT_DIR DOMAIN
import { Harness, sleep, launchChromium } from "./harness.mjs";
import fs, { mkdtempSync, mkdirSync } from "node:fs";
import { tmpdir } from "node:os";
import path from "node:path";

const [app, out, domain] = process.argv.slice(2);
if (!app || !out || !domain) { console.error("usage: console_e2e.mjs HARBOURSIM OUT_DIR DOMAIN"); process.exit(2); }
mkdirSync(out, { recursive: true });
const dir = mkdtempSync(path.join(tmpdir(), "harbour-e2e-"));
const db = `sqlite3://db=${dir}/records.db`;
const h = new Harness(app);
const check = h.check.bind(h), run = h.run.bind(h), start = h.start.bind(h), until = h.until.bind(h);

let browser;
try {
  run(["trainees", "add", "anna", "Anna Berg", "--db", db]);
  run(["trainees", "add", "ben", "Ben Olsen", "--db", db]);
  // a finished attempt each, for the evolution, the comparison and the class overview
  for (const who of ["anna", "ben"]) run(["run", "--exercise", "sts_discharge", "--autopilot", "--trainee", who, "--db", db]);
  run(["accounts", "add", "ines", "--role", "instructor", "--db", db], "ines-password\n");
  run(["accounts", "add", "anna", "--role", "trainee", "--trainee", "anna", "--db", db], "anna-password\n");
  const [url] = await h.console(db, domain);
  // its sound on: OpenAL Soft's wave-writer backend plays it into a file (no sound card needed)
  const played = path.join(dir, "station-sound.wav");
  fs.writeFileSync(path.join(dir, "alsoft.conf"), `[general]\ndrivers=wave\n[wave]\nfile=${played}\n`);
  const station = start(["station", "--serve", "--name", "e2e-1", "--domain", domain, "--db", db, "--window", "off",
    "--sound", "on"], { env: { ALSOFT_CONF: path.join(dir, "alsoft.conf") } });

  browser = await launchChromium();
  const page = await browser.newPage({ viewport: { width: 1280, height: 1000 } });
  await page.goto(url);
  await page.fill("#login-name", "ines");
  await page.fill("#login-password", "wrong-password");
  await page.click("#login-form button");
  await until("a wrong password is refused", async () => (await page.textContent("#login-error")).includes("wrong"));
  await page.fill("#login-password", "ines-password");
  await page.click("#login-form button");
  await until("the station shows, idle", async () =>
    (await page.locator("#stations tr[data-station=e2e-1] td:nth-child(2)").textContent().catch(() => "")) === "idle");
  await page.click("#stations tr[data-station=e2e-1]");
  await page.selectOption("#exercise", "sts_discharge");
  await page.selectOption("#trainee", "ben");
  await page.check("#autopilot");
  await page.click("button[data-kind=start]");
  await until("the exercise runs", async () =>
    (await page.locator("#stations tr[data-station=e2e-1] td:nth-child(2)").textContent()) === "running", 40);
  await until("telemetry arrives", async () => ((await page.getAttribute("#live", "data-wind")) ?? "") !== "");
  // the live line reads as the trainee's HUD does (the looks' hud lines for this machine), not raw keys
  await until("the live line shows the STS's HUD: its payload and spreader", async () => {
    const live = await page.textContent("#live");
    return /load -?\d+\.\d t/.test(live) && /spreader (20|40|45) ft/.test(live) && !/flipper|_/.test(live);
  });
  // the instructor sees what the trainee sees: the station's cab view as pictures, 640x360, new ones coming
  const picture = () => page.$eval("#cab-picture", (img) =>
    ({ frames: Number(img.dataset.frames ?? 0), time: Number(img.dataset.time ?? 0), width: img.naturalWidth, height: img.naturalHeight }));
  await until("the trainee's cab view arrives", async () => (await picture()).frames >= 2, 40);
  const first = await picture();
  await page.waitForTimeout(3000);
  const later = await picture();
  const rate = (later.frames - first.frames) / 3;
  check(first.width === 640 && first.height === 360 && later.frames > first.frames && later.time > first.time,
    `the trainee's cab view in the console: ${first.width}x${first.height}, ${rate.toFixed(1)} pictures a second, ` +
    `t ${first.time.toFixed(1)} -> ${later.time.toFixed(1)} s`);
  await page.locator("#cab-figure").screenshot({ path: path.join(out, "console_cab_view.png") });
  // the 3D view and the plan draw the station's entities with their looks; a drag orbits the view
  const view = (what) => page.evaluate((w) => window.harbourView?.[w]() ?? null, what);
  await until("the 3D view draws the station's entities", async () => (await view("visibleEntities")) > 10);
  const pixels = (id) => page.$eval(id, (canvas) => {
    const copy = document.createElement("canvas");
    copy.width = canvas.width; copy.height = canvas.height;
    const c = copy.getContext("2d"); c.drawImage(canvas, 0, 0);
    const data = c.getImageData(0, 0, copy.width, copy.height).data;
    const colours = new Set();
    let orange = 0;  // the STS's own paint (data/visuals/harbour.yaml, linear 0.80 0.25 0.10), lit
    for (let k = 0; k < data.length; k += 4) {
      colours.add((data[k] << 16) | (data[k + 1] << 8) | data[k + 2]);
      if (data[k] > 120 && data[k] > 1.4 * data[k + 1] && data[k + 1] > 1.2 * data[k + 2]) ++orange;
    }
    return { colours: colours.size, orange: orange / (data.length / 4) };
  });
  // the plan is redrawn with the states that follow: wait for its first picture
  let plan = await pixels("#plan");
  await until("the plan has drawn", async () => (plan = await pixels("#plan")).colours > 10, 10);
  const drawn = await pixels("#view3d");
  check(drawn.colours > 40 && drawn.orange > 0.005, `the 3D view shows the crane (${drawn.colours} colours, ${(100 * drawn.orange).toFixed(1)} % crane paint)`);
  check(plan.colours > 10 && plan.orange > 0.005, `the plan shows the crane from above (${plan.colours} colours, ${(100 * plan.orange).toFixed(1)} % crane paint)`);
  const eye = await view("cameraPosition");
  const box = await page.locator("#view3d").boundingBox();
  await page.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
  await page.mouse.down();
  await page.mouse.move(box.x + box.width / 2 + 200, box.y + box.height / 2 + 40, { steps: 10 });
  await page.mouse.up();
  const moved = Math.hypot(...(await view("cameraPosition")).map((v, k) => v - eye[k]));
  check(moved > 10, `a drag orbits the 3D view (the eye moved ${moved.toFixed(1)} m)`);
  // chromium draws WebGL here in software: the view starts light (a quarter of the pixels, shown at full size);
  // unticked, it draws every pixel (as on a PC with a GPU: the docs' picture)
  const buffer = () => page.$eval("#view3d", (c) => [c.width, c.height, c.clientWidth, c.clientHeight]);
  const light = await buffer();
  check(await page.isChecked("#view-light") && light[0] * 2 === light[2] && light[1] * 2 === light[3],
    `drawn in software the view is light (${light[0]}x${light[1]} shown at ${light[2]}x${light[3]})`);
  await page.uncheck("#view-light");
  const full = await buffer();
  check(full[0] === full[2] && full[1] === full[3], `unticked, every pixel is drawn (${full[0]}x${full[1]})`);
  await page.waitForTimeout(500);
  const sharp = await pixels("#view3d");
  check(sharp.colours > 40 && sharp.orange > 0.005, `the full view shows the crane (${sharp.colours} colours)`);
  await page.locator("#watch").screenshot({ path: path.join(out, "console_3d_view.png"), timeout: 60000 });
  // the view shows the station's weather: 300 m of fog greys its sky and hides the far quay; clear again after
  const sky = async () => ((await page.getAttribute("#view3d", "data-sky")) ?? "").split(" ").map(Number);
  const clear = await sky();
  await page.fill("#command-visibility-0", "300");
  await page.click("button[data-kind=visibility]");
  await until("the fog greys the view's sky", async () => {
    const [r, g, b] = await sky();
    return Math.abs(r - g) < 0.02 && Math.abs(b - g) < 0.04;
  });
  check(clear[2] > clear[0] + 0.1, `the clear sky was blue (${clear.join(", ")})`);
  await page.waitForTimeout(500);
  await page.locator("#watch").screenshot({ path: path.join(out, "console_3d_fog.png"), timeout: 60000 });
  await page.fill("#command-visibility-0", "20000");
  await page.click("button[data-kind=visibility]");
  await until("the sky clears", async () => (await sky())[2] > (await sky())[0] + 0.1);
  // an overcast (8 oktas, no rain) greys it too, a broken sky (4 oktas) leaves it blue between the clouds
  await page.fill("#command-cloud-0", "8");
  await page.click("button[data-kind=cloud]");
  await until("the overcast greys the view's sky", async () => {
    const [r, g, b] = await sky();
    return Math.abs(r - g) < 0.02 && Math.abs(b - g) < 0.04;
  });
  await page.fill("#command-cloud-0", "4");
  await page.click("button[data-kind=cloud]");
  await until("the sky is blue again between broken cloud", async () => (await sky())[2] > (await sky())[0] + 0.1);
  const calm = Number(await page.getAttribute("#live", "data-wind"));
  await page.fill("#command-wind-0", "18");
  await page.click("button[data-kind=wind]");
  await until("the wind command is done", async () => (await page.textContent("#command-result")).includes("done"));
  await until("the wind shows in the telemetry", async () => Number(await page.getAttribute("#live", "data-wind")) > 12);
  check(calm < 12, `the wind before: ${calm} m/s`);
  // the telemetry plots, chosen by the figures' names: the STS's load and rope tension, its spreader's swing
  // with the wind, its three motions' speeds
  const plotted = await page.$$eval("#plot .telemetry-plot", (boxes) => boxes.map((b) => `${b.dataset.plot}: ${b.dataset.series}`));
  check(plotted.join("; ") === "load: load_t,rope_tension_kn; sway: swing_m,wind; speeds: gantry_speed_mps,hoist_speed_mps,trolley_speed_mps",
    `the telemetry plots load, ropes, swing, wind and speeds (${plotted.join("; ")})`);
  await page.waitForTimeout(600);  // a draw of the plots after the gust
  await page.locator("#plot").screenshot({ path: path.join(out, "console_telemetry.png") });
  await page.click("button[data-kind=hoist-brake-fault]");
  await until("the fault's event is logged", async () => (await page.textContent("#events")).includes("instructor: hoist brake fault by ines"));
  await until("the cab's fault lamp shows in the live line", async () =>
    (await page.textContent("#live-faults")).includes("BRAKE FAULT"));
  await page.click("button[data-kind=clear-faults]");  // repaired before the autopilot takes the crane out of service
  await until("the repair is logged and the lamp goes out", async () =>
    (await page.textContent("#events")).includes("instructor: clear faults by ines") && await page.isHidden("#live-faults"));
  await page.click("button[data-kind=emergency-stop]");
  await until("the emergency stop is logged", async () => (await page.textContent("#events")).includes("instructor: emergency stop by ines"));
  await page.click("button[data-kind=release-emergency-stop]");
  await until("its release is logged", async () => (await page.textContent("#events")).includes("instructor: release emergency stop by ines"));
  // a power failure and the supply back: both logged (the autopilot's hands come off the levers meanwhile)
  await page.click("button[data-kind=power-failure]");
  await until("the power failure is logged", async () => (await page.textContent("#events")).includes("instructor: power failure by ines"));
  await page.click("button[data-kind=power-restored]");
  await until("the supply back is logged", async () => (await page.textContent("#events")).includes("instructor: power restored by ines"));
  // the station's sound: the instructor's radio call, the volume, mute and back
  const said = async (what) => (await page.textContent("#command-result")).includes(what);
  await page.fill("#command-radio-0", "hoist up slowly");
  await page.click("button[data-kind=radio]");
  await until("the radio call is made", () => said('done: on the radio, "hoist up slowly"'));
  await page.fill("#command-volume-0", "50");
  await page.click("button[data-kind=volume]");
  await until("the volume is set", () => said("done: volume 50 %"));
  await page.click("button[data-kind=mute]");
  await until("the station is muted", () => said("done: sound muted"));
  await page.click("button[data-kind=unmute]");
  await until("and heard again", () => said("done: sound on"));
  await page.fill("#command-volume-0", "500");
  await page.click("button[data-kind=volume]");
  // refused by the console's command table before it reaches the station, saying the range the form shows
  await until("a volume past 200 % is refused", () => said("refused (400)") && said("volume [%], 0-200"));
  check(await page.getAttribute("#command-volume-0", "max") === "200", "the volume's field has the table's range");
  check(station.output.includes("sound: OpenAL Soft, 2 channels, HRTF"), "the station plays its sound on the desktop's headphones");
  check(fs.existsSync(played) && fs.statSync(played).size > 48000 * 8, "the station's sound was played (the wave writer's file)");
  await page.click("button[data-kind=hold]");
  await until("the station is held", async () =>
    (await page.locator("#stations tr[data-station=e2e-1] td:nth-child(2)").textContent()) === "held");
  const heldAt = await page.textContent("#stations tr[data-station=e2e-1] td:nth-child(6)");
  await sleep(1000);
  check(heldAt === await page.textContent("#stations tr[data-station=e2e-1] td:nth-child(6)"), `held time stays at ${heldAt}`);
  await page.click("button[data-kind=resume]");
  await until("it runs again", async () =>
    (await page.locator("#stations tr[data-station=e2e-1] td:nth-child(2)").textContent()) === "running");
  const stationTime = async () => parseFloat(await page.textContent("#stations tr[data-station=e2e-1] td:nth-child(6)"));
  await until("12 s of the exercise have run (a keyframe at 10 s)", async () => (await stationTime()) >= 12.5, 40);
  await page.screenshot({ path: path.join(out, "console_instructor.png"), fullPage: true });
  // stopped with a fault in force: once the station is idle the live line no longer shows the fault. Held
  // first: running, the autopilot answers the fault by setting the spreader down and taking the crane out of
  // service, which can end the attempt before the lamp's state reaches the page
  await page.click("button[data-kind=hold]");
  await until("it is held again", async () =>
    (await page.locator("#stations tr[data-station=e2e-1] td:nth-child(2)").textContent()) === "held");
  await page.click("button[data-kind=hoist-brake-fault]");
  if (!await until("the fault is in force again", async () => (await page.textContent("#live-faults")).includes("BRAKE FAULT"), 40))
    console.log(`  the page then: live "${await page.textContent("#live")}" (${await page.getAttribute("#live", "data-state")}),` +
      ` command "${await page.textContent("#command-result")}", station "${await page.textContent("#stations tr[data-station=e2e-1]")}"`);
  await page.click("button[data-kind=stop]");
  await until("the idle station's live line says so and shows no fault", async () =>
    (await page.textContent("#live")).startsWith("idle") && await page.isHidden("#live-faults"));
  await until("the panel says how the attempt ended", async () =>
    /^Last: attempt \d+ ended by the instructor, score \d+\.\d \(First discharge onto a truck\)$/.test(await page.textContent("#attempt-outcome")) &&
    await page.isVisible("#attempt-outcome"));
  await page.locator("#control-panel").screenshot({ path: path.join(out, "console_outcome.png") });
  let original;
  await until("the stopped attempt is stored", async () => {
    const r = await page.evaluate(async () => (await fetch("/api/attempts")).json());
    original = r.find((a) => a.trainee === "ben" && a.status === "ended_by_instructor");
    return original !== undefined;
  });
  check(original?.outcome === "ended by the instructor" && !original.passed,
    `stopped with its move left, it is ended by the instructor, not passed (${original?.outcome})`);
  await until("the records table says so in words", async () =>
    (await page.textContent(`#attempts tbody tr:has(td:text-is("${original.id}"))`).catch(() => "")).includes("ended by the instructor"));

  // the records keep its recording: moved away from where the station wrote it (as if the station were
  // another PC), it still replays and is taken over
  const detail = await page.evaluate(async (id) => (await fetch(`/api/attempts/${id}`)).json(), original.id);
  check(typeof detail.recording === "string" && fs.existsSync(detail.recording) &&
    path.dirname(detail.recording) === path.join(dir, "recordings"),
    `the attempt names its recording, beside the station's records (${detail.recording})`);
  fs.renameSync(detail.recording, `${detail.recording}.elsewhere`);

  // replay it: scrub to 11 s (from the keyframe), play at 8x, then take over there on the station
  await page.click(`#attempts tbody tr:has(td:text-is("${original.id}"))`);
  await until("the attempt's debrief says what it was, in words", async () =>
    (await page.textContent("#attempt-detail")).includes(`Attempt ${original.id}: ben on First discharge onto a truck, ended by the instructor`));
  const debrief = await page.textContent("#attempt-detail");
  const words = debrief.split("recording:")[0];  // the recording's path is a file name
  check(!/[{}"_]/.test(words) && /hoist energy\s*[\d.]+ MJ/.test(words) && /safety\s*\d/.test(words) &&
    /time\s*[\d.]+ s/.test(words),
    `the debrief shows figures with words and units, no raw keys (${debrief.slice(0, 160)}...)`);
  await page.click("#open-replay");
  await until("the replay opens at 0 s", async () => (await page.textContent("#replay-time")).startsWith("0.0 /"));
  await page.$eval("#replay-scrub", (e) => { e.value = "11"; e.dispatchEvent(new Event("change")); });
  const replayTime = async () => parseFloat(await page.textContent("#replay-time"));
  if (!(await until("the replay shows 11 s", async () => Math.abs((await replayTime()) - 11) < 0.05)))
    console.log(`     the replay says: ${await page.textContent("#replay-time")}`);
  await until("the 3D view draws the replay", async () =>
    (await view("drawnStation")).startsWith("replay-") && (await view("visibleEntities")) > 10);
  await page.selectOption("#replay-speed", "2");
  await until("it plays on at 2x", async () => (await replayTime()) > 11.5);
  await page.click("#replay-pause");
  await page.waitForTimeout(300);
  const takenAt = await replayTime();
  await page.screenshot({ path: path.join(out, "console_replay.png"), fullPage: true });
  await until("the stopped station is idle again", async () =>
    (await page.locator("#stations tr[data-station=e2e-1] td:nth-child(2)").textContent()) === "idle");
  // the only free station is already chosen: pressing Take over needs no pick first
  await until("the take-over offers the free station without a pick", async () =>
    (await page.inputValue("#takeover-station")) === "e2e-1");
  await page.selectOption("#takeover-trainee", "anna");
  await page.check("#takeover-autopilot");
  await page.click("#take-over");
  await until("the take-over is accepted", async () => (await page.textContent("#takeover-result")).includes("taking over"));
  await until("the station runs the branch", async () =>
    (await page.locator("#stations tr[data-station=e2e-1] td:nth-child(2)").textContent()) === "running");
  const branchStart = await stationTime();
  check(branchStart >= takenAt - 0.01, `the branch starts at the replay's moment (${branchStart} s, taken at ${takenAt} s)`);
  const branch = (await page.evaluate(async () => (await fetch("/api/attempts")).json())).find((a) => a.parent === original.id);
  check(branch?.trainee === "anna", `the branch is a new attempt of anna's with attempt ${original.id} as its parent`);
  await page.click("button[data-kind=stop]");
  // the results table says when each attempt ran, for how long, who drove and where a take-over came from
  const rowText = async (id) => (await page.locator(`#attempts tbody tr:has(td:nth-child(1):text-is("${id}"))`)
    .allTextContents().catch(() => []))[0] ?? "";
  await until("the branch's row names its parent and its driver", async () =>
    (await rowText(branch?.id)).includes(`attempt ${original.id}`) && (await rowText(branch?.id)).includes("autopilot"));
  const originalRow = await page.locator(`#attempts tbody tr:has(td:nth-child(1):text-is("${original.id}")) td`).allTextContents();
  check(originalRow[6] !== "" && /^\d+ (s|min \d+ s)$/.test(originalRow[7]) && originalRow[8] !== "" &&
    originalRow[10] === original.exercise_version.slice(0, 8),
    `the stopped attempt's row: started ${originalRow[6]}, took ${originalRow[7]}, driven by ${originalRow[8]}, version ${originalRow[10]}`);

  // training routes: anna enrolled in the STS route from the panel; her progress shows the first stage open
  await page.selectOption("#progress-trainee", "anna");
  await page.selectOption("#route", "sts_basic");
  await page.click("#enrol-form button[type=submit]");
  await until("anna is enrolled", async () => (await page.textContent("#enrol-result")) === "enrolled");
  const stageState = (p, stage) => p.locator(`#progress table[data-route=sts_basic] tr[data-stage=${stage}] td:nth-child(4)`)
    .textContent().catch(() => "");
  await until("her progress shows single_lift open, deck_discharge locked", async () =>
    (await stageState(page, "single_lift")) === "open" && (await stageState(page, "deck_discharge")) === "locked");
  await page.locator("#routes-panel").screenshot({ path: path.join(out, "console_routes.png") });

  // evolution on one figure against another trainee, and the class overview
  await until("anna's figures are offered", async () =>
    (await page.locator("#evolution-figure option[value=time_s]").count()) === 1);
  await page.selectOption("#evolution-figure", "time_s");
  await page.selectOption("#compare-with", "ben");
  await until("the plot shows time_s for anna and ben", async () =>
    (await page.getAttribute("#evolution", "data-figure")) === "time_s" &&
    (await page.locator("#evolution .u-legend .u-series").count()) === 3);
  await until("the comparison table shows time_s", async () => (await page.isVisible("#comparison")) &&
    (await page.locator("#comparison tbody tr").count()) >= 1 &&
    (await page.locator("#comparison tbody tr td:nth-child(3)").first().textContent()) === "time");
  check((await page.locator("#cohort tbody tr td:nth-child(3)").first().textContent()) === "time" &&
    /^[\d.]+ s$/.test(await page.locator("#cohort tbody tr td:nth-child(4)").first().textContent()),
    "anna's standing is shown on the time, in seconds");
  const place = await page.locator("#cohort tbody tr td:nth-child(7)").first().textContent();
  check(/^\d+(st|nd|rd|th) of \d+( \(tied\))?$/.test(place), `her place among the trainees in words (${place})`);
  await page.locator("#routes-panel").screenshot({ path: path.join(out, "console_compare.png") });
  await until("the class overview lists anna and ben", async () =>
    (await page.locator("#class tbody tr").count()) === 2 &&
    Number(await page.locator("#class tr[data-trainee=anna] td:nth-child(3)").textContent()) >= 2);
  const classReport = await page.evaluate(async () => {
    const r = await fetch("/api/reports/class");
    return { status: r.status, text: await r.text() };
  });
  check(classReport.status === 200 && classReport.text.includes("Class report") && classReport.text.includes("anna"),
    `the class report page (${classReport.status})`);
  await page.locator("#class-panel").screenshot({ path: path.join(out, "console_class.png") });

  // a trainee: own results only, no instructor actions
  const trainee = await browser.newPage();
  await trainee.goto(url);
  await trainee.fill("#login-name", "anna");
  await trainee.fill("#login-password", "anna-password");
  await trainee.click("#login-form button");
  await until("the trainee is in", async () => (await trainee.textContent("#who")).includes("anna (trainee)"));
  const refused = await trainee.evaluate(async () => {
    const me = await (await fetch("/api/me")).json();
    const post = (p, b) => fetch(p, { method: "POST", headers: { "Content-Type": "application/json", "X-CSRF-Token": me.csrf }, body: JSON.stringify(b) });
    return {
      stations: (await fetch("/api/stations")).status,
      command: (await post("/api/stations/e2e-1/command", { kind: "hold" })).status,
      trainee: (await post("/api/trainees", { id: "x", name: "X" })).status,
      rename: (await fetch("/api/trainees", { method: "PATCH", headers: { "Content-Type": "application/json", "X-CSRF-Token": me.csrf }, body: JSON.stringify({ id: "anna", name: "Queen Anna" }) })).status,
      others: (await fetch("/api/attempts?trainee=ben")).status,
      othersProgress: (await fetch("/api/progress?trainee=ben")).status,
      enrol: (await post("/api/enrolments", { trainee: "anna", route: "mhc_bulk" })).status,
      own: await (await fetch("/api/attempts")).json(),
    };
  });
  check(refused.stations === 403, `a trainee may not list stations (${refused.stations})`);
  check(refused.command === 403, `a trainee may not command a station (${refused.command})`);
  check(refused.trainee === 403, `a trainee may not add trainees (${refused.trainee})`);
  check(refused.rename === 403, `a trainee may not rename trainees, not even themselves (${refused.rename})`);
  check(refused.others === 403, `a trainee may not read another's results (${refused.others})`);
  check(refused.own.every((a) => a.trainee === "anna"), `a trainee sees only their own attempts (${refused.own.length})`);
  check(refused.othersProgress === 403 && refused.enrol === 403,
    `a trainee may not read another's progress (${refused.othersProgress}) nor enrol (${refused.enrol})`);
  await until("a trainee sees their own progress", async () => (await stageState(trainee, "single_lift")) === "open");
  check(!(await trainee.isVisible("#stations-panel")), "a trainee's page has no station panel");
  for (const form of ["#trainee-form", "#rename-form", "#enrol-form", "#decision-form", "#attempt-actions", "#class-panel",
    "#compare-with"])
    check(!(await trainee.isVisible(form)), `a trainee's page shows no ${form}`);
  await trainee.screenshot({ path: path.join(out, "console_trainee.png"), fullPage: true });
} catch (e) {
  check(false, `error: ${e.stack ?? e}`);
} finally {
  await browser?.close();
  await h.finish();
}
