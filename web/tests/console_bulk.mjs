// A bulk exercise watched live in a real browser: an MHC station digs coal under the autopilot, its bulk
// surfaces reach the console over DDS (harbour/station_bulk) and the 3D view meshes them; as the grab bites, the
// hold's surface the browser has changes. Usage: node console_bulk.mjs HARBOURSIM OUT_DIR DOMAIN
import { Harness, launchChromium } from "./harness.mjs";
import { mkdtempSync, mkdirSync } from "node:fs";
import { tmpdir } from "node:os";
import path from "node:path";

const [app, out, domain] = process.argv.slice(2);
mkdirSync(out, { recursive: true });
const dir = mkdtempSync(path.join(tmpdir(), "harbour-bulk-"));
const db = `sqlite3://db=${dir}/records.db`;
const h = new Harness(app);
const check = h.check.bind(h), run = h.run.bind(h), start = h.start.bind(h), until = h.until.bind(h);

let browser;
try {
  run(["accounts", "add", "ines", "--role", "instructor", "--db", db], "ines-password\n");
  const [url] = await h.console(db, domain);
  start(["station", "--serve", "--name", "mhc-1", "--domain", domain, "--db", db, "--window", "off"]);
  browser = await launchChromium();
  const page = await browser.newPage({ viewport: { width: 1280, height: 1000 } });
  // every bulk message the page gets: the hold's (the first grid's) heights summed
  await page.addInitScript(() => {
    window.bulkSums = [];
    const Native = window.WebSocket;
    window.WebSocket = class extends Native {
      constructor(...args) {
        super(...args);
        this.addEventListener("message", (e) => {
          const m = JSON.parse(e.data);
          if (m.type === "bulk" && m.grids.length) window.bulkSums.push(m.grids[0].heights.reduce((a, b) => a + b, 0));
        });
      }
    };
  });
  await page.goto(url);
  await page.fill("#login-name", "ines");
  await page.fill("#login-password", "ines-password");
  await page.click("#login-form button");
  await until("the station shows, idle", async () =>
    (await page.locator("#stations tr[data-station=mhc-1] td:nth-child(2)").textContent().catch(() => "")) === "idle");
  await page.click("#stations tr[data-station=mhc-1]");
  await page.selectOption("#exercise", "mhc_coal_discharge");
  await page.check("#autopilot");
  await page.click("button[data-kind=start]");
  await until("the exercise runs", async () =>
    (await page.locator("#stations tr[data-station=mhc-1] td:nth-child(2)").textContent()) === "running", 40);
  await until("the 3D view meshes the coal", async () => Number(await page.getAttribute("#view3d", "data-bulk")) > 500, 30);
  await until("the grab's bites change the hold the browser has", async () => {
    const sums = await page.evaluate(() => window.bulkSums);
    return sums.length > 2 && Math.abs(sums[sums.length - 1] - sums[0]) > 1.0;
  }, 90);
  const sums = await page.evaluate(() => window.bulkSums);
  check(sums.length > 2, `${sums.length} bulk messages, the hold's heights summed ${sums[0]?.toFixed(1)} -> ${sums[sums.length - 1]?.toFixed(1)}`);
  // looking down into the hold the grab digs (the view's camera moved as a drag would), every pixel drawn
  await page.uncheck("#view-light");
  await page.evaluate(() => {
    const v = window.harbourView;
    v.camera.position.set(22, -16, 30);
    v.controls.target.set(34.5, 0, -2);
    v.controls.update();
  });
  await page.waitForTimeout(1500);
  await page.locator("#view3d").screenshot({ path: path.join(out, "console_bulk.png") });
} catch (e) {
  check(false, `error: ${e.stack ?? e}`);
} finally {
  await browser?.close();
  await h.finish();
}
