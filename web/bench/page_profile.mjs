// Where a console page's CPU goes while it watches one station: Chrome's Performance metrics over 10 s.
// Usage: node web/bench/page_profile.mjs HARBOURSIM
import { chromium } from "playwright-core";
import { mkdtempSync, readFileSync, readdirSync } from "node:fs";
import { tmpdir } from "node:os";
import path from "node:path";
import { Harness, sleep } from "../tests/harness.mjs";

const [app] = process.argv.slice(2);
const h = new Harness(app);
const dir = mkdtempSync(path.join(tmpdir(), "harbour-page-"));
const db = `sqlite3://db=${dir}/records.db`;
let browser;
try {
  h.run(["trainees", "add", "load", "Load Test", "--db", db]);
  h.run(["accounts", "add", "ines", "--role", "instructor", "--db", db], "ines-password\n");
  const [base] = await h.console(db, "204", "page-console");
  h.start(["station", "--serve", "--autopilot", "--window", "off", "--name", "page-1", "--domain", "204", "--db", db]);
  browser = await chromium.launch({ executablePath: "/usr/bin/chromium", args: ["--headless", "--no-sandbox",
    ...(process.env.ARGS ?? "--disable-gpu --enable-unsafe-swiftshader").split(" "), "--no-first-run", "--disable-background-networking", "--disable-component-update", "--disable-sync"] });
  const page = await browser.newPage();
  await page.goto(base);
  await page.fill("#login-name", "ines");
  await page.fill("#login-password", "ines-password");
  await page.click("#login-form button");
  await page.click("#stations tr[data-station=page-1]", { timeout: 30000 });
  await page.selectOption("#exercise", process.argv[3] ?? "sts_discharge");
  await page.check("#autopilot");
  if (process.env.VIEW === "off") await page.uncheck("#view-on");
  await page.click("button[data-kind=start]");
  await sleep(5000);
  const cdp = await page.context().newCDPSession(page);
  await cdp.send("Performance.enable");
  const metrics = async () => Object.fromEntries((await cdp.send("Performance.getMetrics")).metrics.map((m) => [m.name, m.value]));
  const chromium_s = () => readdirSync("/proc").filter((p) => /^\d+$/.test(p)).reduce((sum, p) => {
    try {
      if (!readFileSync(`/proc/${p}/cmdline`, "utf8").startsWith("/usr/lib/chromium/chromium")) return sum;
      const f = readFileSync(`/proc/${p}/stat`, "utf8").split(") ")[1].split(" ");
      return sum + (Number(f[11]) + Number(f[12])) / 100;
    } catch { return sum; }
  }, 0);
  await page.evaluate(() => {  // count the 3D view's frames
    const view = window.harbourView;
    if (!view) return;
    window.framesDrawn = 0;
    const render = view.renderer.render.bind(view.renderer);
    view.renderer.render = (...args) => { ++window.framesDrawn; return render(...args); };
  });
  const c0 = chromium_s();
  const a = await metrics();
  let bytes = 0, messages = 0;
  page.on("websocket", () => {});
  await sleep(10000);
  const b = await metrics();
  console.log(`chromium, every process: ${(100 * (chromium_s() - c0) / 10).toFixed(1)} % of a core`);
  for (const k of ["TaskDuration", "ScriptDuration", "LayoutDuration", "RecalcStyleDuration", "LayoutCount", "RecalcStyleCount", "JSHeapUsedSize", "Nodes"])
    console.log(`${k}: ${k.endsWith("Duration") ? `${(100 * (b[k] - a[k]) / 10).toFixed(1)} % of a core` : k.endsWith("Count") ? `${((b[k] - a[k]) / 10).toFixed(1)} per s` : b[k]}`);
  const drawn = await page.evaluate(() => {  // the 3D view's last frame, as three.js counted it
    const view = window.harbourView;
    return view ? view.renderer.info.render : null;
  });
  const frames = await page.evaluate(() => window.framesDrawn ?? 0);
  const canvas = await page.evaluate(() => { const c = document.getElementById("view3d"); return c ? `${c.width}x${c.height}` : "none"; });
  if (drawn) console.log(`3D view: ${(frames / 10).toFixed(1)} frames a second on a ${canvas} canvas`);
  if (drawn) console.log(`3D view: ${drawn.calls} draw calls, ${drawn.triangles} triangles, ${drawn.lines} line segments a frame`);
  await page.screenshot({ path: `${dir}/page.png` });
  console.log(`screenshot ${dir}/page.png`);
} catch (e) {
  h.check(false, `error: ${e.stack ?? e}`);
} finally {
  await browser?.close();
  await h.finish();
}
