// A console on the centre's network serves TLS only: without a certificate a network address is refused,
// bad certificate files are named, and with one a real browser logs in over HTTPS, gets a Secure session
// cookie and the live WebSocket over TLS (wss) shows a station; plain HTTP on the TLS port gets no answer.
// Usage: node console_tls.mjs HARBOURSIM DOMAIN
import { Harness, launchChromium } from "./harness.mjs";
import { execFileSync, spawnSync } from "node:child_process";
import { mkdtempSync, writeFileSync } from "node:fs";
import http from "node:http";
import tls from "node:tls";
import { tmpdir } from "node:os";
import path from "node:path";

const [app, domain] = process.argv.slice(2);
if (!app || !domain) { console.error("usage: console_tls.mjs HARBOURSIM DOMAIN"); process.exit(2); }
const dir = mkdtempSync(path.join(tmpdir(), "harbour-tls-"));
const db = `sqlite3://db=${dir}/records.db`;
const h = new Harness(app);
const check = h.check.bind(h), run = h.run.bind(h), start = h.start.bind(h), until = h.until.bind(h);

// a self-signed certificate for localhost, and a key that is not its
const cert = path.join(dir, "cert.pem"), key = path.join(dir, "key.pem"), otherKey = path.join(dir, "other.pem");
execFileSync("openssl", ["req", "-x509", "-newkey", "ec", "-pkeyopt", "ec_paramgen_curve:prime256v1", "-nodes",
  "-keyout", key, "-out", cert, "-days", "2", "-subj", "/CN=localhost"], { stdio: "ignore" });
execFileSync("openssl", ["genpkey", "-algorithm", "EC", "-pkeyopt", "ec_paramgen_curve:prime256v1", "-out", otherKey],
  { stdio: "ignore" });
writeFileSync(path.join(dir, "garbage.pem"), "-----BEGIN CERTIFICATE-----\nnot one\n");

const refused = (args, says) => {
  const r = spawnSync(app, ["console", "--db", db, "--domain", domain, "--port", "0", "--seconds", "5", ...args],
    { encoding: "utf8" });
  const output = r.stdout + r.stderr;
  check(r.status !== 0 && output.includes(says), `console ${args.join(" ")}: refused, saying '${says}'` +
    (r.status !== 0 && output.includes(says) ? "" : ` (exit ${r.status}: ${output.trim()})`));
};

let browser;
try {
  run(["accounts", "add", "ines", "--role", "instructor", "--db", db], "ines-password\n");
  refused(["--bind", "0.0.0.0"], "serves TLS only");
  refused(["--bind", "0.0.0.0", "--tls-cert", cert], "needs both --tls-cert and --tls-key");
  refused(["--tls-cert", path.join(dir, "missing.pem"), "--tls-key", key], `--tls-cert ${path.join(dir, "missing.pem")}`);
  refused(["--tls-cert", path.join(dir, "garbage.pem"), "--tls-key", key], "not a readable PEM certificate");
  refused(["--tls-cert", cert, "--tls-key", otherKey], "not the key of --tls-cert");

  const c = start(["console", "--db", db, "--domain", domain, "--port", "0", "--bind", "0.0.0.0",
    "--tls-cert", cert, "--tls-key", key]);
  await until("the console listens on https", () => /https:\/\/0\.0\.0\.0:\d+\//.test(c.output));
  const port = c.output.match(/https:\/\/0\.0\.0\.0:(\d+)\//)[1];
  const url = `https://localhost:${port}/`;
  start(["station", "--serve", "--name", "tls-1", "--domain", domain, "--db", db, "--window", "off"]);

  // plain HTTP on the TLS port: no HTTP answer, and the console goes on
  const plain = await new Promise((resolve) => {
    const request = http.get(`http://127.0.0.1:${port}/api/me`, (r) => resolve(`status ${r.statusCode}`));
    request.on("error", (e) => resolve(e.code ?? "error"));
    request.setTimeout(5000, () => { request.destroy(); resolve("timeout"); });
  });
  check(!plain.startsWith("status"), `plain HTTP gets no HTTP answer (${plain})`);

  // over TLS too, no path reaches a file outside the pages
  for (const p of ["//etc/passwd", "/%2e%2e/%2e%2e/etc/passwd", "/../../etc/passwd", `//${dir}/records.db`]) {
    const answer = await new Promise((resolve) => {
      const s = tls.connect({ port: Number(port), host: "127.0.0.1", rejectUnauthorized: false },
        () => s.write(`GET ${p} HTTP/1.1\r\nHost: localhost\r\nConnection: close\r\n\r\n`));
      let got = "";
      s.on("data", (d) => { got += d; });
      s.on("close", () => resolve(got));
      s.on("error", () => resolve(got));
    });
    check(/^HTTP\/1\.1 404/.test(answer) && !answer.includes("root:"), `over TLS GET ${p}: ${answer.split("\r\n")[0]}`);
  }

  browser = await launchChromium();
  const context = await browser.newContext({ ignoreHTTPSErrors: true, viewport: { width: 1280, height: 900 } });
  const page = await context.newPage();
  await page.goto(url);
  await page.fill("#login-name", "ines");
  await page.fill("#login-password", "ines-password");
  await page.click("#login-form button");
  await until("over wss the station shows, idle", async () =>
    (await page.locator("#stations tr[data-station=tls-1] td:nth-child(2)").textContent().catch(() => "")) === "idle", 30);
  const cookie = (await context.cookies()).find((k) => k.name === "hs_session");
  check(cookie && cookie.secure && cookie.httpOnly && cookie.sameSite === "Strict",
    `the session cookie is Secure, HttpOnly, SameSite=Strict (${JSON.stringify(cookie)})`);
  check(page.url().startsWith("https://"), `the page is served over https (${page.url()})`);
  const me = await page.evaluate(async () => (await fetch("/api/me")).json());
  check(me.name === "ines", `the API answers over TLS (${JSON.stringify(me)})`);
} catch (e) {
  check(false, `no exception (${e.stack})`);
} finally {
  if (browser) await browser.close();
  await h.finish();
}
