// The console tried as a centre's IT person and a curious trainee would: files outside the pages, the
// records file itself, other trainees' results and live stations, a hostile design, a flood of idle
// connections, name probing by login time, foreign origins, hidden characters and duplicate keys, and a
// centre's design named like a shipped exercise. Usage: node console_security.mjs HARBOURSIM DOMAIN
import { Harness, sleep, webSocket } from "./harness.mjs";
import { spawn } from "node:child_process";
import { mkdtempSync, mkdirSync, readdirSync, readFileSync, symlinkSync, statSync } from "node:fs";
import http from "node:http";
import net from "node:net";
import { tmpdir } from "node:os";
import path from "node:path";
import { fileURLToPath } from "node:url";

const [app, domain] = process.argv.slice(2);
if (!app || !domain) { console.error("usage: console_security.mjs HARBOURSIM DOMAIN"); process.exit(2); }
const data = path.resolve(path.dirname(fileURLToPath(import.meta.url)), "../../data");
const dir = mkdtempSync(path.join(tmpdir(), "harbour-security-"));
const dbFile = path.join(dir, "records.db");
const db = `sqlite3://db=${dbFile}`;
const h = new Harness(app);
const check = h.check.bind(h), run = h.run.bind(h), start = h.start.bind(h), until = h.until.bind(h);

// a centre's own exercise folder beside the shipped machines, vessels, ... (linked), as the designer's
const centre = path.join(dir, "centre"), exercises = path.join(centre, "exercises");
mkdirSync(exercises, { recursive: true });
for (const entry of readdirSync(data))
  if (entry !== "exercises" && entry !== "routes") symlinkSync(path.join(data, entry), path.join(centre, entry));

// exactly these bytes on a fresh connection (fetch would tidy the path first); the whole answer
function raw(port, text, { localAddress } = {}) {
  return new Promise((resolve) => {
    const s = net.connect({ port: Number(port), host: "127.0.0.1", localAddress }, () => s.write(text));
    let got = "";
    s.on("data", (d) => { got += d; if (/\r\n\r\n/.test(got) && !/Connection: keep-alive/i.test(got)) s.end(); });
    s.on("close", () => resolve(got));
    s.on("error", () => resolve(got));
    s.setTimeout(10000, () => { s.destroy(); resolve(got); });
  });
}
const get = (target) => `GET ${target} HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n`;
// a JSON request from a given local address (each address has its own failed-login count)
function request(base, p, { method = "GET", body, cookie, csrf, origin, localAddress } = {}) {
  return new Promise((resolve) => {
    const headers = { Connection: "close" };
    if (cookie) headers.Cookie = cookie;
    if (body !== undefined) { headers["Content-Type"] = "application/json"; headers["X-CSRF-Token"] = csrf ?? ""; }
    if (origin) headers.Origin = origin;
    const started = performance.now();
    const r = http.request(base + p, { method, headers, localAddress, agent: false }, (res) => {
      let text = "";
      res.on("data", (d) => { text += d; });
      res.on("end", () => {
        let json = null;
        try { json = JSON.parse(text); } catch { /* not JSON */ }
        resolve({ status: res.statusCode, data: json, text, ms: performance.now() - started,
          cookie: (res.headers["set-cookie"]?.[0] ?? "").split(";")[0] });
      });
    });
    r.on("error", (e) => resolve({ status: 0, error: e.message, ms: performance.now() - started }));
    if (body !== undefined) r.write(typeof body === "string" ? body : JSON.stringify(body));
    r.end();
  });
}
async function login(base, name, password, localAddress) {
  const r = await request(base, "api/login", { method: "POST", body: { name, password }, localAddress });
  return { status: r.status, cookie: r.cookie, csrf: r.data?.csrf, ms: r.ms };
}
const median = (xs) => [...xs].sort((a, b) => a - b)[Math.floor(xs.length / 2)];

try {
  for (const [id, name] of [["tom", "Tom Berg"], ["una", "Una Lind"]]) run(["trainees", "add", id, name, "--db", db]);
  run(["run", "--exercise", "sts_discharge", "--autopilot", "--trainee", "una", "--db", db]);
  run(["accounts", "add", "ines", "--role", "instructor", "--db", db], "ines-password\n");
  run(["accounts", "add", "ivan", "--role", "instructor", "--db", db], "ivan-password\n");
  run(["accounts", "add", "tom", "--role", "trainee", "--trainee", "tom", "--db", db], "tom-password\n");
  const c = start(["console", "--db", db, "--domain", domain, "--port", "0", "--exercises", exercises]);
  await until("the console listens", () => /http:\/\/127\.0\.0\.1:\d+\//.test(c.output));
  const port = c.output.match(/http:\/\/127\.0\.0\.1:(\d+)\//)[1];
  const base = `http://127.0.0.1:${port}/`;

  // files: only the pages' own, whatever the path says; the records file is never opened from outside
  const probes = ["//etc/passwd", "/%2e%2e/%2e%2e/etc/passwd", "/..%2f..%2f..%2fetc%2fpasswd", "/../../../etc/passwd",
    "/%2F%2Fetc%2Fpasswd", "//proc/self/environ", "/index.html/../../../../etc/passwd", `/${dbFile}`, `//${dbFile}`,
    "/..\\..\\..\\etc\\passwd", "/.%00./etc/passwd", "/%c0%ae%c0%ae/etc/passwd", "/./index.html", "//index.html"];
  for (const p of probes) {
    const answer = await raw(port, get(p));
    const status = answer.split("\r\n")[0];
    check(/^HTTP\/1\.1 40\d/.test(status) && !answer.includes("root:") && !answer.includes("SQLite format"),
      `GET ${p}: ${status}`);
  }
  check(/^HTTP\/1\.1 200/.test(await raw(port, get("/"))) && /^HTTP\/1\.1 200/.test(await raw(port, get("/app.js"))),
    "the pages themselves are served");

  // logins from a few loopback addresses, each with its own count of failures
  const ines = await login(base, "ines", "ines-password", "127.0.0.2");
  const ivan = await login(base, "ivan", "ivan-password", "127.0.0.2");
  const tom = await login(base, "tom", "tom-password", "127.0.0.2");
  check(ines.status === 200 && ivan.status === 200 && tom.status === 200, "an instructor, another and a trainee log in");
  // the records stay whole while the files above are asked for: trainees added meanwhile are all there
  for (let n = 0; n < 5; ++n) {
    await raw(port, get(`//${dbFile}`));
    const added = await request(base, "api/trainees", { method: "POST", body: { id: `t${n}`, name: `T ${n}` }, ...ines });
    check(added.status === 201, `trainee t${n} added (${added.status})`);
  }
  const listed = (await request(base, "api/trainees", ines)).data ?? [];
  check([0, 1, 2, 3, 4].every((n) => listed.some((t) => t.id === `t${n}`)), `all five are in the records (${listed.length})`);

  // a trainee sees only their own records, and no live station at all
  const una = (await request(base, "api/attempts", ines)).data.find((a) => a.trainee === "una");
  for (const [p, want] of [["api/stations", 403], ["api/attempts?trainee=una", 403], [`api/attempts/${una.id}`, 404],
    ["api/evolution?trainee=una", 403], ["api/progress?trainee=una", 403], ["api/reports/trainee?trainee=una", 403],
    ["api/attempts.csv?trainee=una", 403], ["api/class", 403], ["api/audit", 403], ["api/designer/source?exercise=sts_discharge", 403]]) {
    const r = await request(base, p, tom);
    check(r.status === want, `a trainee's GET ${p}: ${r.status}`);
  }
  const own = await request(base, "api/attempts", tom);
  check(own.status === 200 && own.data.every((a) => a.trainee === "tom"), `a trainee's own attempts only (${own.data?.length})`);
  const replay = await request(base, "api/replays", { method: "POST", body: { attempt: una.id }, ...tom });
  check(replay.status === 403, `a trainee may not open a replay (${replay.status})`);
  const tomSocket = await webSocket(port, tom.cookie);
  await sleep(300);
  check(tomSocket.status === 403 && tomSocket.messages.length === 0,
    `a trainee's live socket is refused (${tomSocket.status}) and gets nothing (${tomSocket.messages.length} messages)`);
  tomSocket.socket.destroy();
  const inesSocket = await webSocket(port, ines.cookie);
  await until("an instructor's live socket gets the stations", async () => inesSocket.messages.some((m) => m.type === "stations"), 5);
  check(inesSocket.status === 101, `an instructor's live socket opens (${inesSocket.status})`);
  inesSocket.socket.destroy();

  // pages of another origin (another site, another port of this host) may neither change nor watch anything
  const foreign = await request(base, "api/trainees", { method: "POST", body: { id: "evil", name: "Evil" }, ...ines,
    origin: "http://127.0.0.1:9" });
  check(foreign.status === 403, `a change from another origin's page: ${foreign.status} (${foreign.data?.error})`);
  const same = await request(base, "api/trainees", { method: "POST", body: { id: "good", name: "Good" }, ...ines,
    origin: `http://127.0.0.1:${port}` });
  check(same.status === 201, `the console's own origin: ${same.status}`);
  const foreignSocket = await new Promise((resolve) => {
    const s = net.connect(Number(port), "127.0.0.1", () => s.write(`GET /api/live HTTP/1.1\r\nHost: 127.0.0.1:${port}\r\n` +
      `Origin: http://localhost:1234\r\nUpgrade: websocket\r\nConnection: Upgrade\r\nSec-WebSocket-Key: ` +
      `dGhlIHNhbXBsZSBub25jZQ==\r\nSec-WebSocket-Version: 13\r\nCookie: ${ines.cookie}\r\n\r\n`));
    let got = "";
    s.on("data", (d) => { got += d; s.end(); });
    s.on("close", () => resolve(got.split("\r\n")[0]));
  });
  check(/ 403 /.test(foreignSocket), `a live socket from another origin's page: ${foreignSocket}`);

  // names that hide characters, and keys given twice, are refused
  for (const [what, body] of [["a right-to-left override", `{"id":"rlo","name":"anna\u202Egnp.exe"}`],
    ["a zero-width direction mark", `{"id":"lrm\u200E","name":"x"}`], ["a key given twice", `{"id":"dup","name":"a","name":"b"}`]]) {
    const r = await request(base, "api/trainees", { method: "POST", body, ...ines });
    check(r.status === 400, `${what}: ${r.status} (${r.data?.error})`);
  }

  // a hostile design (nested aliases) is refused while another user's requests are answered at once
  let bomb = "exercise:\n  name: bomb\n  a0: &a0 [lol, lol, lol, lol, lol, lol, lol, lol, lol]\n";
  for (let n = 1; n <= 9; ++n) bomb += `  a${n}: &a${n} [${Array(9).fill(`*a${n - 1}`).join(", ")}]\n`;
  const checking = request(base, "api/designer/check", { method: "POST", body: { text: bomb }, ...ines });
  const latencies = [];
  for (let n = 0; n < 10; ++n) latencies.push((await request(base, "api/me", ivan)).ms);
  const verdict = await checking;
  check(verdict.status === 422 && /aliases/.test(verdict.data?.error ?? ""), `the alias bomb: ${verdict.status} (${verdict.data?.error})`);
  check(Math.max(...latencies) < 100, `meanwhile another instructor's requests took at most ${Math.max(...latencies).toFixed(1)} ms`);

  // a centre's design may not take a shipped exercise's name
  const shipped = readFileSync(path.join(data, "exercises", "sts_discharge.yaml"), "utf8");
  const shadow = await request(base, "api/designer/save", { method: "POST", body: { text: shipped }, ...ines });
  check(shadow.status === 409 && /shipped/.test(shadow.data?.error ?? ""), `a design named sts_discharge: ${shadow.status} (${shadow.data?.error})`);
  check(readdirSync(exercises).every((f) => f !== "sts_discharge.yaml"), "and nothing is written");

  // login time does not tell which names have accounts (a password check either way)
  const known = [], unknown = [];
  for (let n = 0; n < 2; ++n) {
    known.push((await login(base, "ines", "wrong-password", "127.0.0.3")).ms);
    unknown.push((await login(base, `nobody${n}`, "wrong-password", "127.0.0.3")).ms);
  }
  check(median(unknown) > 0.3 * median(known), `a wrong password for a known name ${median(known).toFixed(0)} ms, ` +
    `for an unknown name ${median(unknown).toFixed(0)} ms`);

  // idle connections past the process's file limit: the console makes room, and a login is still answered
  const total = 25000, perChild = 8400;
  const children = [];
  for (let n = 0; n * perChild < total; ++n) {
    const count = Math.min(perChild, total - n * perChild);
    const script = `const net=require("net");let open=0,done=0;for(let i=0;i<${count};++i){const s=net.connect({port:${port},host:"127.0.0.1",localAddress:"127.0.1.${n + 1}"});` +
      `s.on("connect",()=>{++open;if(++done===${count})console.log("open "+open)});s.on("error",()=>{if(++done===${count})console.log("open "+open)});s.on("close",()=>{})}setInterval(()=>{},1000)`;
    const child = spawn("sh", ["-c", `ulimit -n $(ulimit -Hn); exec node -e '${script}'`], { stdio: ["ignore", "pipe", "pipe"] });
    child.output = "";
    child.stdout.on("data", (d) => { child.output += d; });
    child.stderr.on("data", (d) => { child.output += d; });
    children.push(child);
  }
  await until("25,000 connections are made", async () => children.every((k) => /open \d+/.test(k.output)), 120);
  const opened = children.reduce((sum, k) => sum + Number(k.output.match(/open (\d+)/)?.[1] ?? 0), 0);
  const after = await login(base, "ivan", "ivan-password", "127.0.0.4");
  check(after.status === 200 && after.ms < 5000, `with ${opened} connections made, a login is answered: ${after.status} in ${after.ms.toFixed(0)} ms`);
  const me = await request(base, "api/me", ivan);
  check(me.status === 200, `and an API request: ${me.status}`);
  for (const k of children) k.kill("SIGKILL");
  check(c.exitCode === null, "the console is still running");
} catch (e) {
  check(false, `no exception (${e.stack})`);
} finally {
  await h.finish();
}
