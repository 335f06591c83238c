// Offline after one visit (issue 17 §1): the service worker caches the whole
// site on the first visit; with the network off, every experiment — also the
// ones never opened — loads, draws and steps, and survives a reload.

import { test } from "node:test";
import assert from "node:assert/strict";
import { builtExperimentIds, open, useLab, waitReady, withPage, workerReady } from "./helpers.mjs";

const lab = useLab();

/** The Simulation tab of `id` is mounted, drawn, and one step advances it. */
async function drawsAndSteps(page, id) {
  const canvas = page.locator(`article.exp[data-experiment=${id}]:not([hidden]) canvas.sim-canvas`);
  await canvas.waitFor({ state: "visible" });
  // A resize (the tab shown, the layout settling) clears the canvas until
  // the next frame paints it: wait for ink rather than sample one moment.
  const inked = await page
    .waitForFunction(
      (sel) => {
        const c = document.querySelector(sel);
        if (!c || c.width === 0 || c.height === 0) return false;
        const data = c.getContext("2d").getImageData(0, 0, c.width, c.height).data;
        for (let i = 3; i < data.length; i += 4 * 97) if (data[i] > 0) return true;
        return false;
      },
      `article.exp[data-experiment=${id}]:not([hidden]) canvas.sim-canvas`,
      { timeout: 20_000 },
    )
    .then(() => true, () => false);
  assert.ok(inked, `${id}: the canvas is drawn`);
  const steps = () => canvas.evaluate((c) => Number(c.dataset.steps ?? 0));
  const before = await steps();
  const step = page.locator(`article.exp[data-experiment=${id}]:not([hidden]) button[data-time=step]`);
  if ((await step.count()) > 0) {
    const play = page.locator(`article.exp[data-experiment=${id}]:not([hidden]) button[data-time=play]`);
    if ((await play.getAttribute("aria-pressed")) === "true") await play.click();
    await step.click();
    await page.waitForFunction(
      ([sel, n]) => Number(document.querySelector(sel)?.dataset.steps ?? 0) > n,
      [`article.exp[data-experiment=${id}]:not([hidden]) canvas.sim-canvas`, before],
    );
  }
}

test("offline after one visit: every experiment's Simulation tab opens, draws, steps and reloads with the network off", () =>
  withPage(lab, { serviceWorkers: "allow" }, async (page, context) => {
    const ids = builtExperimentIds();
    await open(lab, page, "#/");
    await open(lab, page, "#/pid/simulation");
    const { scope, cached } = await workerReady(page);
    assert.ok(scope.startsWith(lab.server.base), `the worker's scope is the lab's folder: ${scope}`);
    assert.ok(cached > 20, `the whole site is cached (${cached} files)`);
    await context.setOffline(true);
    for (const id of ids) {
      await page.goto(`${lab.server.base}index.html#/${id}/simulation`);
      await waitReady(page);
      await drawsAndSteps(page, id);
      await page.reload();
      await waitReady(page);
      await drawsAndSteps(page, id);
    }
    // The lab report too: its module was never fetched while online (a
    // report was never made), yet the worker holds it.
    const [download] = await Promise.all([
      page.waitForEvent("download"),
      page.locator(`article.exp:not([hidden]) button[data-export=report]`).click(),
    ]);
    assert.equal(download.suggestedFilename(), `${ids.at(-1)}-report.html`, "a report is made offline");
    // The home page too, from the folder URL.
    await page.goto(lab.server.base);
    await page.waitForSelector("[data-page=home]:not([hidden]) a.card");
    await context.setOffline(false);
  }));

/**
 * A lab report as the lab writes one, reduced to what "Check a report" reads:
 * fk's 12 questions drawn from seed 123, none answered, 0 / 12.
 */
const UNANSWERED_FK_REPORT = `<!doctype html><html lang="en"><head><meta charset="utf-8"><title>fk report</title></head><body>
<h1>Robot arm forward kinematics</h1>
<section class="quiz"><p class="score">Score: 0 / 12 (0%)</p></section>
<script type="application/json" id="lab-report-data">${JSON.stringify({
  id: "fk",
  quiz: { seed: "123", answers: Array(12).fill(null), score: [0, 12] },
})}</script>
</body></html>`;

test("check.html offline: after one visit to the lab, the Check a report page opens with its styles and grades a report with the network off", () =>
  withPage(lab, { serviceWorkers: "allow" }, async (page, context) => {
    await open(lab, page, "#/");
    await workerReady(page);
    // Never opened online: neither the page nor its files are in the
    // browser's HTTP cache, only in the worker's.
    await context.setOffline(true);
    await page.goto(`${lab.server.base}check.html`);
    assert.equal(await page.locator("h1").innerText(), "Check a lab report", "the check page, not the lab's home page");
    const styled = await page.evaluate(() => ({
      drop: getComputedStyle(document.querySelector(".check-drop")).borderTopStyle,
      sheets: [...document.styleSheets].map((s) => new URL(s.href).pathname.split("/").pop()),
    }));
    assert.equal(styled.drop, "dashed", "check.css applies");
    assert.deepEqual(styled.sheets.sort(), ["check.css", "style.css"], "both style sheets load");
    await page.setInputFiles("#check-file", {
      name: "fk-report.html",
      mimeType: "text/html",
      buffer: Buffer.from(UNANSWERED_FK_REPORT),
    });
    await page.waitForFunction(() => ["good", "bad"].includes(document.getElementById("check-result").dataset.verdict));
    const result = await page.locator("#check-result").innerText();
    assert.match(result, /✓ The printed score, 0 \/ 12, matches the answers in the file/, "fk's module was loaded and graded");
    await context.setOffline(false);
  }));

test("the site is installable: a manifest with icons, under the sub-path", () =>
  withPage(lab, {}, async (page) => {
    await open(lab, page, "#/");
    const href = await page.getAttribute("link[rel=manifest]", "href");
    const url = new URL(href, page.url());
    assert.ok(url.pathname.startsWith(new URL(lab.server.base).pathname), `manifest under the sub-path: ${url}`);
    const manifest = await (await page.request.get(url.href)).json();
    assert.equal(manifest.start_url, "./");
    assert.equal(manifest.scope, "./");
    assert.equal(manifest.display, "standalone");
    for (const size of ["192x192", "512x512"]) {
      const icon = manifest.icons.find((i) => i.sizes === size);
      assert.ok(icon, `a ${size} icon`);
      const res = await page.request.get(new URL(icon.src, url).href);
      assert.equal(res.status(), 200);
      assert.equal(res.headers()["content-type"], "image/png");
    }
    const themes = await page.$$eval("meta[name=theme-color]", (ms) => ms.map((m) => m.media));
    assert.deepEqual(themes.sort(), ["(prefers-color-scheme: dark)", "(prefers-color-scheme: light)"]);
  }));

test("a new deployment is announced quietly on the next visit", () =>
  withPage(lab, {}, async (page) => {
    await open(lab, page, "#/");
    assert.ok(await page.locator("#updated").isHidden(), "no notice on a first visit");
    await page.evaluate(() => localStorage.setItem("lab-version", "00000000"));
    await page.reload();
    await page.waitForSelector("[data-page=home]:not([hidden])");
    const notice = page.locator("#updated");
    await notice.waitFor({ state: "visible" });
    assert.match(await notice.innerText(), /updated/);
    await notice.locator("button").click();
    assert.ok(await notice.isHidden());
  }));
