// What the console's browser and API tests share: checks that count failures, the harboursim processes they
// start (killed at the end, their output shown when something failed) and waiting for a condition.
import { spawn, execFileSync } from "node:child_process";
import { chromium } from "playwright-core";

export class Harness {
  constructor(app) { this.app = app; this.children = []; this.failures = 0; }
  check(ok, what) { console.log(`${ok ? "ok  " : "FAIL"} ${what}`); if (!ok) this.failures++; }
  run(args, input) { return execFileSync(this.app, args, { input, encoding: "utf8" }); }
  // `service`: in a session of its own, as a service manager starts a station or a console (the kernel then
  // schedules it as a group of its own, not with whatever else this script started)
  start(args, { service = false, env } = {}) {
    const child = spawn(this.app, args, { stdio: ["ignore", "pipe", "pipe"], detached: service,
      env: env ? { ...process.env, ...env } : process.env });
    this.children.push(child);
    child.output = "";
    child.stdout.on("data", (d) => { child.output += d; });
    child.stderr.on("data", (d) => { child.output += d; });
    return child;
  }
  async until(what, test, seconds = 20) {
    for (let t = 0; t < seconds * 10; ++t) { if (await test()) return true; await sleep(100); }
    this.check(false, `${what} (waited ${seconds} s)`);
    return false;
  }
  // a console on a free port of this machine: its base URL and port
  async console(db, domain, name, options = {}) {
    const c = this.start(["console", "--db", db, "--domain", domain, "--port", "0", ...(name ? ["--name", name] : [])], options);
    await this.until(`console ${name ?? ""} listens`, () => /http:\/\/127\.0\.0\.1:\d+\//.test(c.output));
    return c.output.match(/http:\/\/127\.0\.0\.1:(\d+)\//);
  }
  async finish() {
    for (const c of this.children) c.kill("SIGTERM");
    // let them end (their last words are in their output); one that has not in 10 s is killed, and said
    await Promise.all(this.children.map((c) => c.exitCode !== null || c.signalCode !== null ? null
      : new Promise((r) => { c.on("exit", r); setTimeout(r, 10000); })));
    for (const c of this.children)
      if (c.exitCode === null && c.signalCode === null) {
        this.check(false, `${c.spawnargs.slice(1, 3).join(" ")} (pid ${c.pid}) ended within 10 s of SIGTERM`);
        c.kill("SIGKILL");
      }
    if (this.failures)
      for (const c of this.children) console.log(`--- ${c.spawnargs.slice(1, 3).join(" ")}\n${c.output.slice(-2000)}`);
    process.exit(this.failures ? 1 : 0);
  }
}

export const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

// A WebSocket client on a plain TCP socket (Node 20 has none built in), so that tests can also send what no
// browser would: frames of random bytes, truncated frames, garbage.
import net from "node:net";
import { randomBytes } from "node:crypto";

export function frame(payload, { opcode = 1, fin = true, masked = true } = {}) {
  const data = Buffer.from(payload);
  const length = data.length < 126 ? [data.length] : data.length < 65536 ? [126, data.length >> 8, data.length & 255]
    : [127, 0, 0, 0, 0, (data.length >>> 24) & 255, (data.length >> 16) & 255, (data.length >> 8) & 255, data.length & 255];
  const head = Buffer.from([(fin ? 0x80 : 0) | opcode, (masked ? 0x80 : 0) | length[0], ...length.slice(1)]);
  if (!masked) return Buffer.concat([head, data]);
  const mask = randomBytes(4);
  return Buffer.concat([head, mask, Buffer.from(data.map((b, i) => b ^ mask[i % 4]))]);
}

export function webSocket(port, cookie) {
  return new Promise((resolve) => {
    const socket = net.connect(Number(port), "127.0.0.1");
    const ws = { socket, status: 0, messages: [], closed: false, buffer: Buffer.alloc(0) };
    socket.on("connect", () => socket.write(`GET /api/live HTTP/1.1\r\nHost: 127.0.0.1\r\nUpgrade: websocket\r\n` +
      `Connection: Upgrade\r\nSec-WebSocket-Key: ${randomBytes(16).toString("base64")}\r\n` +
      `Sec-WebSocket-Version: 13\r\nCookie: ${cookie}\r\n\r\n`));
    socket.on("data", (d) => {
      ws.buffer = Buffer.concat([ws.buffer, d]);
      if (!ws.status) {
        const end = ws.buffer.indexOf("\r\n\r\n");
        if (end < 0) return;
        ws.status = Number(ws.buffer.subarray(9, 12).toString());
        ws.buffer = ws.buffer.subarray(end + 4);
        resolve(ws);
      }
      // server frames: unmasked
      for (;;) {
        if (ws.buffer.length < 2) break;
        let length = ws.buffer[1] & 127, at = 2;
        if (length === 126) { if (ws.buffer.length < 4) break; length = ws.buffer.readUInt16BE(2); at = 4; }
        else if (length === 127) { if (ws.buffer.length < 10) break; length = Number(ws.buffer.readBigUInt64BE(2)); at = 10; }
        if (ws.buffer.length < at + length) break;
        const opcode = ws.buffer[0] & 15, fin = (ws.buffer[0] & 128) !== 0;
        const payload = ws.buffer.subarray(at, at + length);
        ws.buffer = ws.buffer.subarray(at + length);
        // a text message may come in fragments (a first frame, continuations, the last with FIN)
        if (opcode === 1 || (opcode === 0 && ws.fragments)) ws.fragments = [...(opcode === 1 ? [] : ws.fragments), payload];
        if ((opcode === 1 || opcode === 0) && fin && ws.fragments) {
          ws.messages.push(JSON.parse(Buffer.concat(ws.fragments).toString()));
          ws.fragments = null;
        }
        if (opcode === 8) ws.closeCode = payload.length >= 2 ? payload.readUInt16BE(0) : 0;
      }
    });
    socket.on("close", () => { ws.closed = true; resolve(ws); });
    socket.on("error", () => { ws.closed = true; resolve(ws); });
  });
}

// Debian's chromium, headless, as root, on a closed network (no background connections, no QUIC)
export function launchChromium() {
  return chromium.launch({ executablePath: "/usr/bin/chromium", args: ["--headless", "--no-sandbox",
    "--disable-gpu", "--enable-unsafe-swiftshader", "--disable-quic", "--no-first-run", "--disable-background-networking",
    "--disable-component-update", "--disable-sync"] });
}
