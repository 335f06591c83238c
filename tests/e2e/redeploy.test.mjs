// A redeploy under an open tab (issue 51 §5). A new deployment gives the
// wasm modules and reading pages new content-hashed names, and a host whose
// folder is replaced holds only those. A tab opened before then still names
// the old ones when the student moves to another experiment: the page must
// say that the lab was updated and offer a reload, not that a page "could
// not be loaded" (HTTP 404) or that the running experiment's engine "could
// not start".

import { after, before, test } from "node:test";
import assert from "node:assert/strict";
import { readFileSync, readdirSync, renameSync, rmSync, writeFileSync } from "node:fs";
import { basename, join, relative } from "node:path";
import { DIST, launchBrowser, open, poll, screenshot, startServer, waitReady, withPage } from "./helpers.mjs";

const lab = { server: null, browser: null };
before(async () => {
  // A copy of dist/ that the test redeploys, served as it is on disk.
  lab.server = await startServer({ copy: true, compress: false });
  lab.browser = await launchBrowser();
});
after(async () => {
  await lab.browser?.close();
  await lab.server?.close();
});

const HASHED = /\.([0-9a-f]{8})\.([a-z]+)$/;

/** Every file below `dir`, relative, with `/`. */
function filesBelow(dir, under = dir) {
  return readdirSync(dir, { withFileTypes: true }).flatMap((e) =>
    e.isDirectory() ? filesBelow(join(dir, e.name), under) : [relative(under, join(dir, e.name)).split("\\").join("/")],
  );
}

/**
 * What a redeploy of a changed build does to the host's folder: every
 * content-hashed file gets a new name (the old one is gone), the site's
 * `?v=` stamp changes, and the pages that name them are rewritten. Returns
 * the old names.
 */
function redeploy(dir) {
  const renamed = new Map();
  const files = filesBelow(dir).filter((f) => !/\.(br|gz)$/.test(f));
  for (const f of files) {
    const m = basename(f).match(HASHED);
    if (!m) continue;
    const fresh = (~Number.parseInt(m[1], 16) >>> 0).toString(16).padStart(8, "0");
    const name = basename(f).replace(HASHED, `.${fresh}.$2`);
    renameSync(join(dir, f), join(dir, f.slice(0, -basename(f).length) + name));
    for (const ext of [".br", ".gz"]) rmSync(join(dir, f + ext), { force: true });
    renamed.set(basename(f), name);
  }
  assert.ok(renamed.size > 10, `the build has content-hashed files (${renamed.size})`);
  const version = readFileSync(join(dir, "index.html"), "utf8").match(/main\.js\?v=([0-9a-f]+)/)?.[1];
  assert.ok(version, "index.html stamps main.js with the site's version");
  for (const f of filesBelow(dir).filter((f) => /\.(html|js)$/.test(f))) {
    const text = readFileSync(join(dir, f), "utf8");
    let next = text.replaceAll(`?v=${version}`, "?v=0redeploy");
    for (const [was, now] of renamed) next = next.replaceAll(was, now);
    if (next !== text) {
      writeFileSync(join(dir, f), next);
      for (const ext of [".br", ".gz"]) rmSync(join(dir, f + ext), { force: true });
    }
  }
  return new Set(renamed.keys());
}

/** Two experiments of different wasm modules, from the build's own list. */
function experimentsOfTwoModules() {
  const html = readFileSync(join(DIST, "index.html"), "utf8");
  const modules = [...html.matchAll(/<meta name="lab-module" content="[^"]+" data-experiments="([^"]+)"/g)].map((m) =>
    m[1].split(" "),
  );
  assert.ok(modules.length >= 2, "the build has two modules or more");
  return [modules[0][0], modules[1][0]];
}

test("a redeploy under an open tab: moving to another experiment says the lab was updated and offers a reload that opens it", async () => {
  const [first, other] = experimentsOfTwoModules();
  let gone = new Set();
  const missing = [];
  await withPage(
    lab,
    { expectHttpError: (url) => gone.has(basename(new URL(url).pathname)) },
    async (page) => {
      page.on("response", (r) => r.status() === 404 && missing.push(basename(new URL(r.url()).pathname)));
      await open(lab, page, `#/${first}/simulation`);
      gone = redeploy(lab.server.dir);
      await page.evaluate((id) => (location.hash = `#/${id}/simulation`), other);
      const stale = page.locator("#stale");
      await stale.waitFor({ state: "visible" });
      assert.match(await stale.innerText(), /The lab was updated on the server since this page was opened/);
      assert.ok(missing.length > 0 && missing.every((n) => gone.has(n)), `a file the redeploy removed was asked for: ${missing}`);
      assert.ok(await page.locator("#fatal").isHidden(), "no “could not be loaded” nor “could not start”");
      assert.doesNotMatch(await page.locator("#app").innerText(), /could not start|could not be loaded|HTTP 404/);
      await screenshot(page, "redeploy-updated");
      await page.setViewportSize({ width: 390, height: 844 });
      await screenshot(page, "redeploy-updated-phone");
      // The reload opens the new version where the student was going.
      const reload = stale.getByRole("button", { name: "Reload" });
      await reload.focus();
      await Promise.all([page.waitForEvent("load"), page.keyboard.press("Enter")]);
      await waitReady(page);
      await poll(
        page,
        (id) => Boolean(document.querySelector(`article.exp[data-experiment="${id}"]:not([hidden]) canvas.sim-canvas`)),
        other,
      );
      assert.ok(await page.locator("#stale").isHidden(), "the new version runs");
      assert.match(await page.evaluate(() => document.querySelector("script[type=module]").src), /\?v=0redeploy$/);
    },
  );
});
