// The load bench's instructor: sends a wind command to the stations in turn every 50 ms and times each round
// trip (HTTP -> console -> DDS -> station -> ack -> HTTP 200), then a GET /api/stations the console answers
// alone. A process of its own, so that the browsers' automation in the bench's process never delays a reply
// being read. Usage: node command_client.mjs BASE COOKIE CSRF SECONDS NAME... ; prints its figures as JSON.
const [base, cookie, csrf, seconds, ...names] = process.argv.slice(2);
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));
const call = async (p, body) => {
  const r = await fetch(base + p, { method: body ? "POST" : "GET", headers: { Cookie: cookie, "Content-Type": "application/json", "X-CSRF-Token": csrf }, body: body && JSON.stringify(body) });
  return { status: r.status, data: await r.json() };
};
const rtt = [], reads = [];
let refused = 0, firstRefusal = "";
const t0 = Date.now();
while (Date.now() - t0 < Number(seconds) * 1000) {
  const name = names[rtt.length % names.length];
  const start = performance.now();
  const r = await call(`api/stations/${name}/command`, { kind: `wind:${(5 + (rtt.length % 10)).toFixed(1)}:270:0.1` });
  rtt.push(performance.now() - start);
  const read = performance.now();
  await call("api/stations");
  reads.push(performance.now() - read);
  if (r.status !== 200 && refused++ === 0) firstRefusal = `${name}: ${r.status} ${JSON.stringify(r.data)}`;
  await sleep(50);
}
console.log(JSON.stringify({ wall_s: (Date.now() - t0) / 1000, rtt, reads, refused, firstRefusal }));
