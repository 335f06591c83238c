// The end-to-end suite waits for conditions, not for time (issue 25 §8): a
// test reaches a simulated event by stepping the page's clock (helpers.mjs
// `runUntil`, `runFor`) or by awaiting what the page shows, never by
// sleeping on the wall clock, which a busy machine outruns.

import { test } from "node:test";
import assert from "node:assert/strict";
import { readFileSync, readdirSync } from "node:fs";
import { dirname, join, resolve } from "node:path";
import { fileURLToPath } from "node:url";

const ROOT = resolve(dirname(fileURLToPath(import.meta.url)), "..", "..");

test("no end-to-end test sleeps: no waitForTimeout in tests/e2e or tests/hosts", () => {
  const found = [];
  for (const dir of ["tests/e2e", "tests/hosts"]) {
    for (const name of readdirSync(join(ROOT, dir)).filter((n) => n.endsWith(".mjs"))) {
      readFileSync(join(ROOT, dir, name), "utf8")
        .split("\n")
        .forEach((line, i) => {
          if (/\.waitForTimeout\(/.test(line)) found.push(`${dir}/${name}:${i + 1}: ${line.trim()}`);
        });
    }
  }
  assert.deepEqual(found, []);
});

test("a tab icon the browser cancelled on navigation is not a page problem; any other failed request is", async () => {
  const { browserCancelledIcon } = await import("./helpers.mjs");
  const base = "http://127.0.0.1:8000/labs/";
  assert.equal(browserCancelledIcon(`${base}favicon.svg?v=1a2b`, "net::ERR_ABORTED"), true);
  assert.equal(browserCancelledIcon(`${base}favicon.svg`, "NS_BINDING_ABORTED"), true);
  assert.equal(browserCancelledIcon(`${base}favicon.svg`, "net::ERR_FAILED"), false);
  assert.equal(browserCancelledIcon(`${base}pkg/astar.1a2b.wasm`, "net::ERR_ABORTED"), false);
  assert.equal(browserCancelledIcon(`${base}index.html`, "net::ERR_ABORTED"), false);
});
