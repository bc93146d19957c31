// Load on the console: N station processes (served, the autopilot at the controls, headless) each running
// an exercise and publishing to one console with B browsers attached (Debian chromium), while a client
// sends instructor commands and times each round trip (HTTP -> console -> DDS -> station -> ack -> HTTP).
// Usage: node web/bench/console_load.mjs HARBOURSIM [STATIONS=16] [BROWSERS=4] [SECONDS=60] [EXERCISE=rtg_rehandle]
import { chromium } from "playwright-core";
import { readFileSync, readdirSync, mkdtempSync } from "node:fs";
import { tmpdir, cpus } from "node:os";
import path from "node:path";
import { Harness, sleep } from "../tests/harness.mjs";
import { execFile, execFileSync } from "node:child_process";

const [app, stations = "16", browsers = "4", seconds = "60", exercise = "rtg_rehandle"] = process.argv.slice(2);
const h = new Harness(app);
const dir = mkdtempSync(path.join(tmpdir(), "harbour-load-"));
const db = `sqlite3://db=${dir}/records.db`;
const domain = "203";
const cpu_s = (pid) => {  // user + system CPU time of a process [s]
  const fields = readFileSync(`/proc/${pid}/stat`, "utf8").split(") ")[1].split(" ");
  return (Number(fields[11]) + Number(fields[12])) / 100;
};
const machine_busy_s = () => {  // CPU time of every process on the machine, and of chromium's [s]
  const fields = readFileSync("/proc/stat", "utf8").split("\n")[0].split(/ +/).slice(1).map(Number);
  const hz = 100;
  return (fields.reduce((a, b) => a + b, 0) - fields[3] - fields[4]) / hz;
};
const chromium_s = () => readdirSync("/proc").filter((p) => /^\d+$/.test(p)).reduce((sum, p) => {
  try {
    if (!readFileSync(`/proc/${p}/cmdline`, "utf8").startsWith("/usr/lib/chromium/chromium")) return sum;
    return sum + cpu_s(p);
  } catch { return sum; }
}, 0);
const percentile = (sorted, p) => sorted[Math.min(sorted.length - 1, Math.floor(p * sorted.length))];
let browser;
try {
  h.run(["trainees", "add", "load", "Load Test", "--db", db]);
  h.run(["accounts", "add", "ines", "--role", "instructor", "--db", db], "ines-password\n");
  // the console and each station in a session of its own, as the services of a centre run
  const [base] = await h.console(db, domain, "load-console", { service: !process.env.ONE_GROUP });
  const consolePid = h.children[0].pid;
  const names = Array.from({ length: Number(stations) }, (_, n) => `load-${n + 1}`);
  // NICE=10: the stations yield to the console and the browsers, as if on their own PCs (a centre's layout)
  const stationPids = names.map((name) => h.start(["station", "--serve", "--autopilot", "--window", "off", "--name", name, "--domain", domain, "--db", db], { service: !process.env.ONE_GROUP }).pid);
  if (process.env.NICE) for (const pid of stationPids) execFileSync("renice", ["-n", process.env.NICE, "-p", String(pid)]);
  const login = await fetch(base + "api/login", { method: "POST", headers: { "Content-Type": "application/json" }, body: JSON.stringify({ name: "ines", password: "ines-password" }) });
  const cookie = login.headers.get("set-cookie").split(";")[0];
  const { csrf } = await login.json();
  const call = async (p, body) => {
    const r = await fetch(base + p, { method: body ? "POST" : "GET", headers: { Cookie: cookie, "Content-Type": "application/json", "X-CSRF-Token": csrf }, body: body && JSON.stringify(body) });
    return { status: r.status, data: await r.json() };
  };
  await h.until("every station is seen", async () => (await call("api/stations")).data.length === names.length, 60);
  for (const name of names) {
    const r = await call(`api/stations/${name}/command`, { kind: "start", exercise, trainee: "load", autopilot: true });
    h.check(r.status === 200, `${name} starts: ${r.data.message ?? r.data.error}`);
  }
  await h.until("every station runs", async () => (await call("api/stations")).data.every((s) => s.state === "running"), 60);

  browser = await chromium.launch({ executablePath: "/usr/bin/chromium", args: ["--headless", "--no-sandbox",
    "--disable-gpu", "--enable-unsafe-swiftshader", "--disable-quic", "--no-first-run", "--disable-background-networking", "--disable-component-update", "--disable-sync"] });
  for (let n = 0; n < Number(browsers); ++n) {
    const page = await browser.newPage();
    await page.goto(base, { timeout: 90000 });
    await page.fill("#login-name", "ines");
    await page.fill("#login-password", "ines-password");
    await page.click("#login-form button");
    await page.click(`#stations tr[data-station=${names[n % names.length]}]`, { timeout: 90000 });
    // VIEW=full: the 3D view with every pixel drawn even in software (it starts light there)
    if (process.env.VIEW === "full")
      await page.$eval("#view-light", (e) => { e.checked = false; e.dispatchEvent(new Event("change")); });
  }
  await sleep(3000);

  const before = (await call("api/stations")).data;
  const cpuBefore = cpu_s(consolePid), stationCpuBefore = stationPids.map(cpu_s), t0 = Date.now();
  const machineBefore = machine_busy_s(), chromiumBefore = chromium_s();
  // a command's round trip and a read the console answers alone (GET /api/stations), timed by a client of
  // its own (command_client.mjs): the browsers' automation here never delays reading a reply
  const client = JSON.parse(await new Promise((resolve, reject) => execFile(process.execPath,
    [new URL("command_client.mjs", import.meta.url).pathname, base, cookie, csrf, seconds, ...names],
    { maxBuffer: 1 << 26 }, (error, stdout) => (error ? reject(error) : resolve(stdout)))));
  const { rtt, reads, refused, firstRefusal } = client;
  const wall = (Date.now() - t0) / 1000, cpu = cpu_s(consolePid) - cpuBefore;
  const machine = machine_busy_s() - machineBefore, chromiumCpu = chromium_s() - chromiumBefore;
  const stationCpu = stationPids.map((pid, n) => cpu_s(pid) - stationCpuBefore[n]);
  const after = (await call("api/stations")).data;
  rtt.sort((a, b) => a - b);
  reads.sort((a, b) => a - b);
  const rates = after.map((s) => (s.states_received - before.find((b) => b.station === s.station).states_received) / wall);
  const rtf = after.map((s) => s.real_time_factor), late = after.map((s) => s.late_ticks), skipped = after.map((s) => s.skipped_ticks);
  console.log(`${exercise}: stations ${names.length}, browsers ${browsers}, ${wall.toFixed(1)} s, ${rtt.length} commands (${refused} not done${refused ? `, the first: ${firstRefusal}` : ""})`);
  console.log(`command round trip: median ${percentile(rtt, 0.5).toFixed(1)} ms, p99 ${percentile(rtt, 0.99).toFixed(1)} ms, max ${rtt[rtt.length - 1].toFixed(1)} ms`);
  console.log(`the console alone (GET /api/stations): median ${percentile(reads, 0.5).toFixed(1)} ms, p99 ${percentile(reads, 0.99).toFixed(1)} ms`);
  console.log(`state rate per station at the console: min ${Math.min(...rates).toFixed(1)} Hz, mean ${(rates.reduce((a, b) => a + b, 0) / rates.length).toFixed(1)} Hz`);
  console.log(`console CPU: ${(100 * cpu / wall).toFixed(1)} % of a core, ${(100 * cpu / wall / names.length).toFixed(2)} % per station`);
  console.log(`station CPU: mean ${(100 * stationCpu.reduce((a, b) => a + b, 0) / stationCpu.length / wall).toFixed(1)} % of a core`);
  console.log(`chromium CPU: ${(100 * chromiumCpu / wall).toFixed(1)} % of a core; the machine: ${(100 * machine / wall).toFixed(0)} % of ${cpus().length} cores busy`);
  console.log(`stations: real-time factor min ${Math.min(...rtf).toFixed(3)}, late ticks max ${Math.max(...late)}, given up max ${Math.max(...skipped)}`);
  h.check(refused === 0, "every command is done");
  h.check(percentile(rtt, 0.99) < 100, "command round trip p99 under 100 ms");
} catch (e) {
  h.check(false, `error: ${e.stack ?? e}`);
} finally {
  await browser?.close();
  await h.finish();
}
