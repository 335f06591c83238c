// Shared links (state in the URL hash) and what a malformed link does.

import { test } from "node:test";
import assert from "node:assert/strict";
import { open, readouts, settle, useLab, withPage } from "./helpers.mjs";

const lab = useLab();

const rad = (deg) => (deg * Math.PI) / 180;
const rangeValue = (page, key) =>
  page.$eval(`input[type=range][data-param="${key}"]`, (el) => Number(el.value));

test("a shared fk link restores its parameters and readouts in a fresh page", () =>
  withPage(lab, {}, async (page) => {
    await open(lab, page, "#/fk/simulation?t1=10&t2=20&l1=1.2&l2=0.8");
    assert.equal(await rangeValue(page, "t1"), 10);
    assert.equal(await rangeValue(page, "t2"), 20);
    assert.equal(await rangeValue(page, "l1"), 1.2);
    assert.equal(await rangeValue(page, "l2"), 0.8);
    const x = 1.2 * Math.cos(rad(10)) + 0.8 * Math.cos(rad(10 + 20));
    const y = 1.2 * Math.sin(rad(10)) + 0.8 * Math.sin(rad(10 + 20));
    const shown = await readouts(page);
    assert.ok(shown.x.startsWith(x.toFixed(3)), `readout x "${shown.x}" starts with ${x.toFixed(3)}`);
    assert.ok(shown.y.startsWith(y.toFixed(3)), `readout y "${shown.y}" starts with ${y.toFixed(3)}`);
  }));

test("after moving a slider, the page's own link reproduces the same state in a new page", () =>
  withPage(lab, {}, async (page, context) => {
    await open(lab, page, "#/fk/simulation?t1=10&t2=20&l1=1.2&l2=0.8");
    await page.focus('input[type=range][data-param="t2"]');
    for (let i = 0; i < 5; i++) await page.keyboard.press("ArrowRight");
    const t2 = await rangeValue(page, "t2");
    assert.ok(t2 > 20, `t2 moved up (now ${t2})`);
    // The hash is rewritten (throttled) once the value settles.
    await page.waitForFunction(
      (v) => new URLSearchParams(location.hash.split("?")[1] ?? "").get("t2") === String(v),
      t2,
    );
    const hash = await page.evaluate(() => location.hash);
    assert.match(hash, /^#\/fk\/simulation\?/, `hash keeps the route: ${hash}`);
    await settle(page);
    const before = await readouts(page);

    const second = await context.newPage();
    await open(lab, second, hash);
    await settle(second);
    assert.equal(await rangeValue(second, "t2"), t2, "t2 restored");
    const after = await readouts(second);
    for (const key of ["x", "y", "reach"]) {
      assert.equal(after[key], before[key], `readout ${key} restored from ${hash}`);
    }
  }));

const MALFORMED = [
  "#/fk/simulation?t1=abc&t2=9999",
  "#/nope",
  "#/fk/zzz",
  "#%%%",
];

test("malformed links show a notice and leave the lab usable", async (t) => {
  for (const hash of MALFORMED) {
    await t.test(`link ${hash}`, () =>
      withPage(lab, {}, async (page) => {
        await open(lab, page, hash);
        const notice = page.locator("#notice");
        await notice.waitFor({ state: "visible" });
        assert.ok((await notice.innerText()).trim().length > 0, "the notice says something");
        if (hash.startsWith("#/fk/simulation")) {
          assert.equal(await rangeValue(page, "t2"), 180, "t2=9999 is clamped to 180");
          const t1 = await rangeValue(page, "t1");
          assert.ok(Number.isFinite(t1), "t1=abc falls back to a number");
          const shown = await readouts(page);
          assert.ok(!/NaN|inf/i.test(Object.values(shown).join(" ")), JSON.stringify(shown));
        }
        // Usable: the nav still takes the reader to an experiment (two clicks).
        await page.click("nav#lab-nav summary");
        await page.click("nav#lab-nav a[data-experiment]");
        await page.locator("article.exp:not([hidden]) [role=tablist]").waitFor();
        await page.click('article.exp:not([hidden]) [role=tab][data-tab="simulation"]');
        await page.locator('article.exp:not([hidden]) [role=tabpanel][data-panel="simulation"] canvas.sim-canvas').waitFor();
      }),
    );
  }
});
