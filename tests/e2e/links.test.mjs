// Shared links (state in the URL hash) and what a malformed link does.

import { test } from "node:test";
import assert from "node:assert/strict";
import { open, readouts, settle, until, useLab, withPage } from "./helpers.mjs";

const lab = useLab();

const rad = (deg) => (deg * Math.PI) / 180;
const rangeValue = (page, key) =>
  page.$eval(`input[type=range][data-param="${key}"]`, (el) => Number(el.value));

test("a shared fk link restores its parameters and readouts in a fresh page", () =>
  withPage(lab, { clock: true }, async (page) => {
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
  withPage(lab, { clock: true }, async (page, context) => {
    await open(lab, page, "#/fk/simulation?t1=10&t2=20&l1=1.2&l2=0.8");
    await page.focus('input[type=range][data-param="t2"]');
    for (let i = 0; i < 5; i++) await page.keyboard.press("ArrowRight");
    const t2 = await rangeValue(page, "t2");
    assert.ok(t2 > 20, `t2 moved up (now ${t2})`);
    // The hash is rewritten (throttled) once the value settles.
    await until(page, 
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
      withPage(lab, { clock: true }, async (page) => {
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

// Issue 13 §2: a link with parameters opened in a tab that already shows the
// experiment rebuilds it from its defaults, exactly as a fresh page does.

/** Clicks the canvas at the world point (x, y) (from the canvas's `data-view`). */
async function clickWorld(page, x, y) {
  const c = page.locator("article.exp:not([hidden]) canvas.sim-canvas");
  const box = await c.boundingBox();
  const [x0, y0, x1, y1] = (await c.getAttribute("data-view")).split(",").map(Number);
  const s = Math.min(box.width / (x1 - x0), box.height / (y1 - y0));
  await page.mouse.click(box.x + box.width / 2 + (x - (x0 + x1) / 2) * s, box.y + box.height / 2 - (y - (y0 + y1) / 2) * s);
}

/** The link's parameters without the shell's own (run, speed). */
const linkParams = (hash) => {
  const q = new URLSearchParams(hash.split("?")[1] ?? "");
  q.delete("run");
  q.delete("speed");
  return q.toString();
};

test("diffdrive: pasting the default link again after three waypoints gives what a fresh page gives (no waypoints)", () =>
  withPage(lab, { clock: true }, async (page, context) => {
    await open(lab, page, "#/diffdrive/simulation");
    await until(page, () => location.hash.includes("?"));
    const defaultLink = await page.evaluate(() => location.hash);
    const fresh = await context.newPage();
    await open(lab, fresh, defaultLink);
    await settle(fresh);
    const freshWaypoints = (await readouts(fresh)).waypoints;

    const view = (await page.locator("article.exp:not([hidden]) canvas.sim-canvas").getAttribute("data-view")).split(",").map(Number);
    const at = (fx, fy) => [view[0] + fx * (view[2] - view[0]), view[1] + fy * (view[3] - view[1])];
    for (const [fx, fy] of [[0.3, 0.8], [0.6, 0.25], [0.8, 0.7]]) await clickWorld(page, ...at(fx, fy));
    await settle(page);
    assert.notEqual((await readouts(page)).waypoints, freshWaypoints, "the clicks added waypoints");
    await until(page, (d) => location.hash !== d, defaultLink);

    // Paste the default link into the same tab.
    await page.evaluate((h) => { location.hash = h; }, defaultLink);
    await until(page, (fw) => document.querySelector('[data-readout="waypoints"]').textContent.trim() === fw, freshWaypoints);
    await settle(page);
    assert.equal((await readouts(page)).waypoints, freshWaypoints);
    assert.equal(linkParams(await page.evaluate(() => location.hash)), linkParams(defaultLink), "the link is the default one again");
  }));

test("a link changes only what it names relative to the defaults, not relative to the tab's state", () =>
  withPage(lab, { clock: true }, async (page, context) => {
    await open(lab, page, "#/fk/simulation?t1=10&t2=20");
    await page.evaluate(() => { location.hash = "#/fk/simulation?t1=40"; });
    await until(page, () => Number(document.querySelector('input[type=range][data-param="t1"]').value) === 40);
    const second = await context.newPage();
    await open(lab, second, "#/fk/simulation?t1=40");
    assert.equal(await rangeValue(page, "t2"), await rangeValue(second, "t2"), "t2 took its default, as in a fresh page");
    assert.deepEqual(await readouts(page), await readouts(second));
  }));

test("a tab link without parameters keeps the state", () =>
  withPage(lab, { clock: true }, async (page) => {
    await open(lab, page, "#/fk/simulation?t1=10&t2=20");
    await page.click('article.exp:not([hidden]) [role=tab][data-tab="theory"]');
    await page.click('article.exp:not([hidden]) [role=tab][data-tab="simulation"]');
    await settle(page);
    assert.equal(await rangeValue(page, "t2"), 20);
  }));

test("the shell's own state comes from the link too: a link without speed or pause opened in the tab plays at 1×", () =>
  withPage(lab, { clock: true }, async (page) => {
    await open(lab, page, "#/pid/simulation?kp=12&speed=2&run=0");
    const art = "article.exp:not([hidden])";
    assert.equal(await page.locator(`${art} select[data-time=speed]`).inputValue(), "2");
    assert.equal(await page.locator(`${art} button[data-time=play]`).getAttribute("aria-pressed"), "false");
    const plain = "#/pid/simulation?kp=12";
    await page.evaluate((h) => { location.hash = h; }, plain);
    await until(page, (a) => document.querySelector(`${a} select[data-time=speed]`).value === "1", art);
    assert.equal(await page.locator(`${art} button[data-time=play]`).getAttribute("aria-pressed"), "true", "playing, as a fresh page");
  }));
