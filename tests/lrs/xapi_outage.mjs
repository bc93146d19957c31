// xAPI statements survive an LRS outage and arrive once: attempts queue their statements in the records while
// the Learning Record Store (Learning Locker's xapi-statements, which validates every statement against xAPI
// 1.0.3) is down; `harboursim xapi send --watch` retries until it is up; statements sent again (their
// acknowledgement lost) are stored once; an invalid one is rejected with the LRS's reason, the rest flow on.
// Usage: node xapi_outage.mjs HARBOURSIM PORT
import { spawn, execFileSync } from "node:child_process";
import { mkdtempSync } from "node:fs";
import http from "node:http";
import { tmpdir } from "node:os";
import path from "node:path";
import { fileURLToPath } from "node:url";

const [app, port] = process.argv.slice(2);
const here = path.dirname(fileURLToPath(import.meta.url));
const dir = mkdtempSync(path.join(tmpdir(), "harbour-xapi-"));
const file = path.join(dir, "records.db");
const db = `sqlite3://db=${file}`;
const endpoint = `http://127.0.0.1:${port}/xAPI/`;
let failures = 0;
const children = [];
const check = (ok, what) => { console.log(`${ok ? "ok  " : "FAIL"} ${what}`); if (!ok) failures++; };
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));
const run = (args) => execFileSync(app, args, { encoding: "utf8" });
const sql = (text) => execFileSync("sqlite3", [file, text], { encoding: "utf8" }).trim();
function start(command, args, env = {}) {
  const child = spawn(command, args, { stdio: ["ignore", "pipe", "pipe"], env: { ...process.env, ...env } });
  child.output = "";
  child.stdout.on("data", (d) => { child.output += d; });
  child.stderr.on("data", (d) => { child.output += d; });
  children.push(child);
  return child;
}
async function until(what, test, seconds = 30) {
  for (let t = 0; t < seconds * 10; ++t) { if (await test()) return true; await sleep(100); }
  check(false, `${what} (waited ${seconds} s)`);
  return false;
}
// A fresh connection per request (agent: false): the test blocks its event loop in execFileSync, so a pooled
// keep-alive socket the LRS closed meanwhile would be reused before its close is seen ("fetch failed").
const lrsStatements = () => new Promise((resolve, reject) => {
  const request = http.get(`${endpoint}statements?limit=500`, { agent: false, headers: {
    "X-Experience-API-Version": "1.0.3", Authorization: "Basic " + Buffer.from("centre:secret").toString("base64") } },
  (response) => {
    let body = "";
    response.setEncoding("utf8");
    response.on("data", (d) => { body += d; });
    response.on("end", () => { try { resolve(JSON.parse(body).statements); } catch (e) { reject(e); } });
  });
  request.on("error", reject);
});
const lrsUp = async () => { try { await lrsStatements(); return true; } catch { return false; } };

try {
  check(!(await lrsUp()), `nothing listens on port ${port} before the test`);
  run(["trainees", "add", "ana", "Ana Lopez", "--db", db]);
  run(["run", "--exercise", "sts_discharge", "--autopilot", "--trainee", "ana", "--db", db]);
  check(/4 queued, 0 sent/.test(run(["xapi", "status", "--db", db])), "a finished attempt queues 4 statements");

  // the LRS is down: the sender retries, the statements wait in the records, a second attempt adds its own
  const auth = path.join(dir, "lrs.auth");
  execFileSync("sh", ["-c", `printf 'centre:secret\\n' > '${auth}'`]);
  const centre = "https://port-academy.example/harboursim";
  const sender = start(app, ["xapi", "send", "--watch", "--db", db, "--lrs", endpoint, "--lrs-auth-file", auth,
    "--centre-iri", centre]);
  await until("the sender meets the outage", () => /Connection refused/.test(run(["xapi", "status", "--db", db])));
  run(["run", "--exercise", "sts_discharge", "--autopilot", "--trainee", "ana", "--db", db]);
  check(/8 queued, 0 sent/.test(run(["xapi", "status", "--db", db])), "during the outage 8 statements wait, none lost");

  // the LRS comes up: everything arrives, in order, once
  const lrs = start("node", [path.join(here, "node_modules/@learninglocker/xapi-statements/dist/server.js")], {
    EXPRESS_PORT: port, AUTH_REPO: "test", EVENTS_REPO: "test", MODELS_REPO: "memory", STORAGE_REPO: "local",
    FS_LOCAL_STORAGE_DIR: path.join(dir, "lrs"), EXPRESS_MORGAN_DIRECTORY: path.join(dir, "lrs"),
    WINSTON_CONSOLE_LEVEL: "error" });
  await until("the LRS is up", lrsUp);
  await until("the sender delivers all 8 after the outage", () => /0 queued, 8 sent/.test(run(["xapi", "status", "--db", db])), 40);
  let stored = await lrsStatements();
  const ids = sql("SELECT statement_id FROM xapi_outbox ORDER BY id").split("\n");
  check(stored.length === 8 && ids.every((id) => stored.some((s) => s.id === id)),
    `the LRS holds the 8 statements under their ids (${stored.length})`);
  const verbs = sql("SELECT verb FROM xapi_outbox ORDER BY id").split("\n").join(",");
  check(verbs === "launched,attempted,passed,completed,launched,attempted,passed,completed", `verbs in order: ${verbs}`);
  const passed = stored.find((s) => s.verb.id === "http://adlnet.gov/expapi/verbs/passed");
  const extensions = Object.keys(passed?.result?.extensions ?? {});
  check(passed?.actor?.account?.name === "ana" && passed.actor.name === "Ana Lopez" &&
    passed.result.score.scaled >= 0 && passed.result.score.scaled <= 1 && passed.result.success === true &&
    /^PT\d+(\.\d+)?S$/.test(passed.result.duration) &&
    extensions.includes("https://harboursim.org/xapi/metrics/collisions") &&
    passed.object.id === `${centre}/exercises/sts_discharge` && passed.actor.account.homePage === `${centre}/trainees` &&
    passed.object.definition.name["en-US"] === "First discharge onto a truck" &&
    /truck under the crane/.test(passed.object.definition.description?.["en-US"] ?? ""),
    `a passed statement: actor, score, success, duration, ${extensions.length} metric extensions, the exercise ` +
    `by the centre's IRI with its title (${passed?.object?.id}, '${passed?.object?.definition?.name?.["en-US"]}')`);
  // one registration per attempt (cmi5, LMSs): every statement of an attempt carries its attempt's
  const byAttempt = new Map();
  for (const s of stored) {
    const attempt = s.context?.extensions?.["https://harboursim.org/xapi/extensions/attempt"];
    byAttempt.set(attempt, [...(byAttempt.get(attempt) ?? []), s.context?.registration]);
  }
  const registrations = [...byAttempt.values()].map((r) => [...new Set(r)]);
  check(byAttempt.size === 2 && registrations.every((r) => r.length === 1 && /^[0-9a-f-]{36}$/.test(r[0])) &&
    registrations[0][0] !== registrations[1][0],
    `each attempt's statements share one registration, the attempts' differ (${registrations.map((r) => r.join("/")).join(", ")})`);
  const queuedAt = new Map(sql("SELECT statement_id || ' ' || queued_at FROM xapi_outbox").split("\n").map((l) => l.split(" ")));
  check(stored.every((s) => Date.parse(s.timestamp) === Date.parse(queuedAt.get(s.id))),
    "each statement's timestamp is when the attempt did it (not when the LRS got it)");

  // acknowledgements lost: the same statements sent again are stored once
  sql("UPDATE xapi_outbox SET state = 'queued', next_try_at = queued_at");
  await until("they are sent again", () => /0 queued, 8 sent/.test(run(["xapi", "status", "--db", db])));
  stored = await lrsStatements();
  check(stored.length === 8, `sent twice, stored once (${stored.length})`);

  // an invalid statement (as a damaged database might hold) is rejected with the LRS's reason
  sql(`INSERT INTO xapi_outbox VALUES (100, '6fbd600f-d17c-4c74-801a-2ec2e53231a9', 1, 'launched',
       '{"actor":{"objectType":"Agent"},"verb":{"id":"nope"},"object":{"id":"x"}}', '2000-01-01T00:00:00.000Z',
       'queued', 0, '2000-01-01T00:00:00.000Z', '', '')`);
  await until("the invalid one is rejected", () => /1 rejected/.test(run(["xapi", "status", "--db", db])));
  const status = run(["xapi", "status", "--db", db]);
  check(/rejected launched .*not retried.*LRS answered 400/.test(status), `the reason is kept: ${status.split("\n")[1]}`);
  run(["run", "--exercise", "sts_discharge", "--autopilot", "--trainee", "ana", "--db", db]);
  await until("statements after it flow on", () => /0 queued, 12 sent, 1 rejected/.test(run(["xapi", "status", "--db", db])));
  check((await lrsStatements()).length === 12, "the LRS holds the 12 valid ones");
  sender.kill("SIGTERM");
  await until("the sender stops on SIGTERM", () => sender.exitCode !== null, 5);

  // the console sends them too (harboursim console --lrs): a fourth attempt's statements arrive through it
  const consoleSender = start(app, ["console", "--db", db, "--port", "0", "--domain", "206", "--lrs", endpoint,
    "--lrs-auth-file", auth]);
  await until("the console is up", () => /http:\/\/127\.0\.0\.1:\d+\//.test(consoleSender.output));
  run(["run", "--exercise", "sts_discharge", "--autopilot", "--trainee", "ana", "--db", db]);
  await until("the console's sender delivers them", () => /0 queued, 16 sent, 1 rejected/.test(run(["xapi", "status", "--db", db])));
  check((await lrsStatements()).length === 16, "the LRS holds 16");
  consoleSender.kill("SIGTERM");
  await until("the console stops with its sender", () => consoleSender.exitCode !== null, 10);

  // the Host header carries the LRS's port (RFC 9112: uri-host [":" port]), as a virtual host behind it needs
  const hosts = [];
  const other = Number(port) + 1;
  const fake = http.createServer((req, res) => {
    hosts.push(req.headers.host);
    req.resume();
    req.on("end", () => { res.writeHead(204); res.end(); });
  });
  await new Promise((resolve) => fake.listen(other, "127.0.0.1", resolve));
  run(["run", "--exercise", "sts_discharge", "--autopilot", "--trainee", "ana", "--db", db]);
  const once = start(app, ["xapi", "send", "--db", db, "--lrs", `http://127.0.0.1:${other}/xAPI/`, "--lrs-auth-file", auth]);
  await until("the one-shot sender ends", () => once.exitCode !== null);
  fake.close();
  check(hosts.length > 0 && hosts.every((h) => h === `127.0.0.1:${other}`),
    `the Host header names the LRS's port: ${[...new Set(hosts)].join(", ")} (${hosts.length} requests)`);

  // refusals
  for (const [args, what] of [[["xapi", "send", "--db", db, "--lrs", "ftp://x/"], "an ftp URL"],
    [["xapi", "send", "--db", db, "--lrs", endpoint, "--lrs-auth-file", path.join(dir, "none")], "a missing credentials file"],
    [["console", "--db", db, "--port", "0", "--lrs", "lrs.centre:8080", "--seconds", "1"], "a console with an LRS that is no URL"]]) {
    let error = "";
    try { execFileSync(app, args, { encoding: "utf8", stdio: "pipe" }); } catch (e) { error = String(e.stderr); }
    check(error.length > 0 && !/Assertion|terminate/.test(error), `${what} is refused: ${error.trim()}`);
  }
} catch (e) {
  check(false, `error: ${e.stack ?? e}${e.cause ? `\ncause: ${e.cause.stack ?? e.cause}` : ""}`);
} finally {
  for (const c of children) if (c.exitCode === null) c.kill("SIGTERM");
  if (failures) for (const c of children) console.log(`--- ${c.spawnargs.slice(0, 3).join(" ")}\n${c.output.slice(-2000)}`);
  process.exit(failures ? 1 : 0);
}
