// Page weight, counted the way a browser downloads it: every response of a
// first visit with an empty cache, summed raw (as a host that does not
// compress sends it) and gzip -9 (as `cargo xtask dist`'s .gz siblings are).
// Bytes, not milliseconds: the figures are the same on a busy machine.
// The table is also written to target/page-weights.json (docs/development.md
// names it).

import { after, test } from "node:test";
import assert from "node:assert/strict";
import { mkdirSync, readdirSync, readFileSync, writeFileSync } from "node:fs";
import { join } from "node:path";
import { gzipSync } from "node:zlib";
import { BASE_PATH, DIST, experimentIds, open, useLab } from "./helpers.mjs";

/** Budgets of issue 16, in bytes, with 1 KB = 1,024 bytes as `cargo xtask
 * size` counts (the table prints both units). */
const KB = 1024;
const EXPERIMENT_RAW = 700 * KB;
const EXPERIMENT_GZIP = 250 * KB;
const HOME_GZIP = 150 * KB;

const lab = useLab();
const table = [];

after(() => {
  const dir = join(process.cwd(), "target");
  mkdirSync(dir, { recursive: true });
  writeFileSync(join(dir, "page-weights.json"), JSON.stringify(table, null, 2));
  const kib = (n) => `${(n / 1024).toFixed(1)} KiB (${n.toLocaleString("en")} B)`;
  console.log("\npage              files   raw                          gzip -9");
  for (const r of table) {
    console.log(`${r.page.padEnd(18)}${String(r.files).padEnd(8)}${kib(r.raw).padEnd(29)}${kib(r.gzip)}`);
  }
});

/**
 * Opens `hash` in a fresh context (an empty cache) and sums every file the
 * server sent with its bytes. Counted at the server, not from the browser's
 * responses: `withPage`'s request routing turns the HTTP cache off, so a
 * file the page uses twice (the icon: the tab's and the header's) would be
 * counted twice, where a browser revalidates it and the host answers 304
 * with no body (nginx and Apache send entity tags; `xtask serve` does too).
 * A request to another origin is a problem here, as in `withPage`.
 */
async function weigh(hash) {
  const context = await lab.browser.newContext({ serviceWorkers: "block" });
  const problems = [];
  context.on("request", (req) => {
    const url = new URL(req.url());
    if (!["data:", "blob:"].includes(url.protocol) && url.origin !== lab.server.origin) {
      problems.push(`request to another origin: ${req.url()}`);
    }
  });
  context.on("page", (p) => {
    p.on("pageerror", (e) => problems.push(`uncaught exception: ${e.message}`));
    p.on("console", (m) => m.type() === "error" && problems.push(`console error: ${m.text()}`));
  });
  const { hits, notModified } = lab.server;
  const [hitsFrom, unchangedFrom] = [hits.length, notModified.length];
  try {
    const page = await context.newPage();
    await open(lab, page, hash);
    if (hash !== "#/") {
      await page.waitForSelector("article.exp:not([hidden]) canvas.sim-canvas");
    }
    await page.waitForLoadState("networkidle");
  } finally {
    await context.close();
  }
  assert.deepEqual(problems, [], `${hash}: the page reported problems`);
  const sent = hits.slice(hitsFrom);
  for (const path of notModified.slice(unchangedFrom)) {
    assert.ok(sent.includes(path), `${path} was answered 304 but never asked for`);
    sent.splice(sent.indexOf(path), 1);
  }
  const files = sent.map((path) => {
    const name = path.slice(BASE_PATH.length) || "index.html";
    return [name, readFileSync(join(DIST, name))];
  });
  return {
    files: files.length,
    names: files.map(([name]) => name.split("/").pop()),
    revalidated: notModified.slice(unchangedFrom).map((path) => path.split("/").pop()),
    raw: files.reduce((n, [, b]) => n + b.length, 0),
    gzip: files.reduce((n, [, b]) => n + gzipSync(b, { level: 9 }).length, 0),
  };
}

test("page budget: the home page downloads at most 150 KB gzip", async () => {
  const w = await weigh("#/");
  table.push({ page: "home", ...w });
  assert.ok(!w.names.some((n) => n.endsWith(".wasm")), "the home page downloads no wasm");
  assert.ok(w.gzip <= HOME_GZIP, `home: ${w.gzip} bytes gzip > ${HOME_GZIP} (${w.names.join(", ")})`);
});

test("page budget: every experiment's first visit downloads at most 700 KB raw and 250 KB gzip", async (t) => {
  for (const id of await experimentIds(lab)) {
    await t.test(id, async () => {
      const w = await weigh(`#/${id}/simulation`);
      table.push({ page: id, ...w });
      const wasm = w.names.filter((n) => n.endsWith(".wasm"));
      assert.equal(wasm.length, 1, `${id} downloads one wasm module: ${wasm}`);
      assert.ok(w.raw <= EXPERIMENT_RAW, `${id}: ${w.raw} bytes raw > ${EXPERIMENT_RAW} (${w.names.join(", ")})`);
      assert.ok(w.gzip <= EXPERIMENT_GZIP, `${id}: ${w.gzip} bytes gzip > ${EXPERIMENT_GZIP}`);
    });
  }
});

test("a module already downloaded is not downloaded again for another experiment it holds", async () => {
  // Not withPage: its request routing (which refuses other origins) turns
  // the HTTP cache off, and the cache is the point here. Requests are
  // counted at the server instead.
  const context = await lab.browser.newContext({ serviceWorkers: "block" });
  const errors = [];
  context.on("page", (p) => {
    p.on("pageerror", (e) => errors.push(e.message));
    p.on("console", (m) => m.type() === "error" && errors.push(m.text()));
  });
  try {
    const page = await context.newPage();
    // fk and ik share the "arms" module (crates/xtask/src/modules.rs).
    await open(lab, page, "#/fk/simulation");
    const wasmHits = () => lab.server.hits.filter((p) => p.endsWith(".wasm"));
    const before = wasmHits().length;
    // Within the page: the other experiment of the module mounts from the running module.
    await page.evaluate(() => { location.hash = "#/ik/simulation"; });
    await page.waitForSelector("article.exp[data-experiment=ik]:not([hidden]) canvas.sim-canvas");
    assert.equal(wasmHits().length, before, "no wasm request for an experiment of the same module");
    // A new page of the same browser: the module comes from the HTTP cache
    // (content-hashed name, cached for good).
    const second = await context.newPage();
    await open(lab, second, "#/ik/aim");
    await second.waitForLoadState("networkidle");
    assert.equal(wasmHits().length, before, "the cached module is not fetched again");
    // An experiment of another module downloads that module, once.
    await open(lab, second, "#/astar/simulation");
    assert.equal(wasmHits().length, before + 1, "the astar module is fetched once");
    assert.deepEqual(errors, []);
  } finally {
    await context.close();
  }
});

// Issue 25 step 9: the content files are read at build time (labcore's
// build.rs writes them as Rust data), so a module carries the quiz's words
// but no JSON text of them to parse in the browser.
test("content is parsed at build time: no wasm module carries a content file's JSON", () => {
  const modules = readdirSync(join(DIST, "pkg")).filter((name) => name.endsWith(".wasm"));
  assert.ok(modules.length > 0, "dist/pkg holds the wasm modules");
  for (const name of modules) {
    const bytes = readFileSync(join(DIST, "pkg", name)).toString("latin1");
    for (const key of ['"explanation":', '"kind":"choice"', '"prompt":']) {
      assert.ok(!bytes.includes(key), `${name} holds content JSON (${key})`);
    }
  }
});
