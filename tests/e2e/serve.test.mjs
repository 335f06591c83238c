// The end-to-end suite is served by `cargo xtask serve` itself (issue 25
// §8): what every other test loads comes with that server's media types,
// cache headers, Content-Security-Policy header and compression, so one
// table of them is tested, not a copy kept for the tests.

import { after, before, test } from "node:test";
import assert from "node:assert/strict";
import { readdirSync } from "node:fs";
import { join } from "node:path";
import { DIST, isContentHashed, startServer } from "./helpers.mjs";

const servers = {};
before(async () => {
  servers.compressed = await startServer();
  servers.plain = await startServer({ compress: false });
});
after(async () => {
  await servers.compressed?.close();
  await servers.plain?.close();
});

/** A hashed wasm module of dist/pkg/, relative to dist/. */
const hashedWasm = () => {
  const name = readdirSync(join(DIST, "pkg")).find((f) => f.endsWith(".wasm") && isContentHashed(f));
  assert.ok(name, "dist/pkg/ has a content-hashed wasm module");
  return `pkg/${name}`;
};

test("the suite's server is `cargo xtask serve`: its Content-Security-Policy and nosniff headers, media types and cache rules", async () => {
  const { base, hits } = servers.compressed;
  const page = await fetch(`${base}index.html`);
  assert.equal(page.status, 200);
  assert.equal(page.headers.get("content-type"), "text/html; charset=utf-8");
  assert.equal(page.headers.get("cache-control"), "no-cache");
  assert.equal(page.headers.get("x-content-type-options"), "nosniff", "xtask serve sends nosniff");
  assert.match(page.headers.get("content-security-policy") ?? "", /script-src 'self' 'wasm-unsafe-eval'/);
  // The same policy as the page's own <meta>.
  const html = await page.text();
  const meta = html.match(/<meta http-equiv="Content-Security-Policy" content="([^"]+)"/)?.[1];
  assert.equal(page.headers.get("content-security-policy"), meta?.replaceAll("&#39;", "'").replaceAll("&apos;", "'"));

  const wasm = await fetch(`${base}${hashedWasm()}`, { headers: { "accept-encoding": "br, gzip" } });
  assert.equal(wasm.status, 200);
  assert.equal(wasm.headers.get("content-type"), "application/wasm");
  assert.equal(wasm.headers.get("cache-control"), "public, max-age=31536000, immutable");
  assert.equal(wasm.headers.get("vary"), "Accept-Encoding");
  assert.ok(hits.some((p) => p.endsWith(".wasm")), `the request is in the server's log: ${hits}`);
  // Without its slash, the sub-path redirects to the folder.
  const bare = await fetch(base.slice(0, -1), { redirect: "manual" });
  assert.equal(bare.status, 301);
  assert.equal(new URL(bare.headers.get("location"), base).href, base);
});

test("the suite's server compresses as `cargo xtask serve` does, and `compress: false` sends files as they are", async () => {
  // Node's fetch decodes the body and drops nothing of the headers.
  const wasm = hashedWasm();
  const packed = await fetch(`${servers.compressed.base}${wasm}`, { headers: { "accept-encoding": "br" } });
  assert.equal(packed.headers.get("content-encoding"), "br");
  const plain = await fetch(`${servers.plain.base}${wasm}`, { headers: { "accept-encoding": "br, gzip" } });
  assert.equal(plain.headers.get("content-encoding"), null);
  assert.deepEqual(
    Buffer.from(await packed.arrayBuffer()),
    Buffer.from(await plain.arrayBuffer()),
    "the same module either way",
  );
});
