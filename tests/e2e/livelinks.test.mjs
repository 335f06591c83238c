// Symbols that point at what they name (issue 27 §3): a symbol marked
// \live{key}{…} on the Theory tab, or a quantity's symbol in "The math",
// is reached by the keyboard; hovering or focusing it draws what it names in
// the scene as a halo, and shows its value from the student's current run.

import { test } from "node:test";
import assert from "node:assert/strict";
import { open, runFor, screenshot, useLab, withPage } from "./helpers.mjs";

const lab = useLab();
const SIM = "article.exp:not([hidden]) [data-panel=simulation]";
const THEORY = "article.exp:not([hidden]) [data-panel=theory]";

/** The canvas's pixels (RGBA) as the page has drawn them. */
function pixels(page) {
  return page.$eval(`${SIM} canvas.sim-canvas`, (c) =>
    Array.from(c.getContext("2d").getImageData(0, 0, c.width, c.height).data));
}

/** How many pixels differ between two captures, and their bounding box. */
function changed(a, b, width) {
  let n = 0;
  const box = { x0: Infinity, y0: Infinity, x1: -1, y1: -1 };
  for (let i = 0; i < a.length; i += 4) {
    if (a[i] !== b[i] || a[i + 1] !== b[i + 1] || a[i + 2] !== b[i + 2]) {
      n += 1;
      const p = i / 4;
      const x = p % width;
      const y = Math.floor(p / width);
      box.x0 = Math.min(box.x0, x); box.y0 = Math.min(box.y0, y);
      box.x1 = Math.max(box.x1, x); box.y1 = Math.max(box.y1, y);
    }
  }
  return { n, box };
}

/** Presses Tab until a [data-live] element inside `scope` has the focus; returns its key. */
async function tabTo(page, scope, key) {
  for (let i = 0; i < 80; i += 1) {
    await page.keyboard.press("Tab");
    const at = await page.evaluate(
      ([scope, key]) => {
        const a = document.activeElement;
        return a && a.closest(scope) && a.getAttribute("data-live") === key;
      },
      [scope, key],
    );
    if (at) return;
  }
  assert.fail(`Tab never reached the symbol ${key} in ${scope}`);
}

test("live links: focusing θ1 in the panel by keyboard draws its arc in the scene, and leaving it takes the halo away", () =>
  withPage(lab, { clock: true }, async (page) => {
    await open(lab, page, "#/fk/simulation?t1=35&t2=60&l1=1&l2=0.8");
    await runFor(page, 100);
    const width = await page.$eval(`${SIM} canvas.sim-canvas`, (c) => c.width);
    const before = await pixels(page);
    await page.focus(`${SIM} canvas.sim-canvas`);
    await tabTo(page, `${SIM} .live-math`, "t1");
    await runFor(page, 50);
    assert.equal(await page.$eval(`${SIM} canvas.sim-canvas`, (c) => c.dataset.live), "t1");
    const lit = await pixels(page);
    const diff = changed(before, lit, width);
    await screenshot(page, "livelinks-fk-theta1-1280");
    assert.ok(diff.n > 200, `the halo changed ${diff.n} pixels`);
    // θ1's arc runs from the x axis to the first link around the shoulder
    // (the origin, at the canvas's centre): the changed pixels sit right of
    // and above it, within the first link's length, not over the whole arm.
    const centre = await page.$eval(`${SIM} canvas.sim-canvas`, (c) => [c.width / 2, c.height / 2]);
    assert.ok(diff.box.x0 >= centre[0] - 8 && diff.box.y1 <= centre[1] + 8, JSON.stringify({ centre, box: diff.box }));
    assert.ok(diff.box.x1 - diff.box.x0 < width / 4, `a small arc, not the arm: ${JSON.stringify(diff.box)}`);
    // The keyboard's focus is drawn on the symbol.
    const outline = await page.evaluate(() => getComputedStyle(document.activeElement).outlineStyle);
    assert.notEqual(outline, "none");
    // Its value is read out as a status (the panel's numbers show it).
    const tip = page.locator("article.exp:not([hidden]) .live-tip");
    assert.equal(await tip.getAttribute("role"), "status");
    assert.equal((await tip.textContent()).trim(), "θ1 = 35.0°");
    assert.equal(await tip.evaluate((t) => t.classList.contains("sr-only")), true);
    // Focus leaves: the halo and the tip go.
    await page.focus(`${SIM} canvas.sim-canvas`);
    await runFor(page, 50);
    assert.equal(await page.$eval(`${SIM} canvas.sim-canvas`, (c) => c.dataset.live), undefined);
    assert.equal(changed(before, await pixels(page), width).n, 0, "the picture is as before");
    assert.equal(await tip.evaluate((t) => t.hidden), true);
  }));

test("live links: hovering L2 highlights the second link; ik's x points at the goal", () =>
  withPage(lab, { clock: true }, async (page) => {
    await open(lab, page, "#/fk/simulation?t1=35&t2=60&l1=1&l2=0.8");
    await runFor(page, 100);
    const width = await page.$eval(`${SIM} canvas.sim-canvas`, (c) => c.width);
    const before = await pixels(page);
    await page.hover(`${SIM} .live-math [data-live=l2]`);
    await runFor(page, 50);
    assert.equal(await page.$eval(`${SIM} canvas.sim-canvas`, (c) => c.dataset.live), "l2");
    assert.ok(changed(before, await pixels(page), width).n > 200);
    await open(lab, page, "#/ik/simulation?tx=0.9&ty=0.8");
    await runFor(page, 100);
    const ikBefore = await pixels(page);
    await page.focus(`${SIM} .live-math [data-live=px]`);
    await runFor(page, 50);
    assert.equal(await page.$eval(`${SIM} canvas.sim-canvas`, (c) => c.dataset.live), "px");
    assert.ok(changed(ikBefore, await pixels(page), width).n > 200);
    assert.equal((await page.locator("article.exp:not([hidden]) .live-tip").textContent()).trim(), "x = 0.900 m");
  }));

for (const [scheme, viewport, name] of [
  ["light", { width: 1280, height: 800 }, "1280"],
  ["dark", { width: 1280, height: 800 }, "1280-dark"],
  ["light", { width: 390, height: 844 }, "390"],
  ["dark", { width: 390, height: 844 }, "390-dark"],
]) {
  test(`live links: the Theory tab shows θ1 from the current run after a slider move (${name})`, () =>
    withPage(lab, { clock: true, colorScheme: scheme, viewport }, async (page) => {
      await open(lab, page, "#/fk/simulation?t1=35&t2=60&l1=1&l2=0.8");
      await page.locator("#p-t1").fill("50");
      await runFor(page, 200);
      await page.evaluate(() => (location.hash = "#/fk/theory"));
      await page.waitForSelector(`${THEORY}:not([hidden])`);
      const symbol = page.locator(`${THEORY} .formula [data-live=t1]`).first();
      await symbol.scrollIntoViewIfNeeded();
      await symbol.hover();
      const tip = page.locator("article.exp:not([hidden]) .live-tip");
      await tip.waitFor();
      assert.equal((await tip.textContent()).trim(), "θ1 = 50.0°");
      // The tip sits under the symbol, on screen.
      const [s, t] = [await symbol.boundingBox(), await tip.boundingBox()];
      assert.ok(t.y >= s.y + s.height - 1 && t.y - (s.y + s.height) < 20, JSON.stringify([s, t]));
      assert.ok(t.x >= 0 && t.x + t.width <= viewport.width + 1, JSON.stringify(t));
      await screenshot(page, `livelinks-theory-${name}`);
      // The keyboard reaches the Theory's symbols too, and the tip follows.
      await page.mouse.move(0, 0);
      await tabTo(page, THEORY, "l2");
      assert.equal((await tip.textContent()).trim(), "L2 = 0.80 m");
      // Back on the Simulation tab, θ2 in the panel lights its arc.
      await page.evaluate(() => (location.hash = "#/fk/simulation"));
      await page.waitForSelector(`${SIM}:not([hidden])`);
      await page.locator(`${SIM} .live-math [data-live=t2]`).first().focus();
      await runFor(page, 50);
      assert.equal(await page.$eval(`${SIM} canvas.sim-canvas`, (c) => c.dataset.live), "t2");
      await page.locator(`${SIM} canvas.sim-canvas`).scrollIntoViewIfNeeded();
      await screenshot(page, `livelinks-fk-theta2-${name}`);
    }));
}

test("live links: pid's gains and error in the Theory formula show the run's values", () =>
  withPage(lab, { clock: true }, async (page) => {
    await open(lab, page, "#/pid/simulation");
    await runFor(page, 500);
    await page.evaluate(() => (location.hash = "#/pid/theory"));
    await page.waitForSelector(`${THEORY}:not([hidden])`);
    const tip = page.locator("article.exp:not([hidden]) .live-tip");
    const kp = await page.$eval("#p-kp", (i) => Number(i.value));
    await page.locator(`${THEORY} .formula [data-live=kp]`).first().focus();
    assert.equal((await tip.textContent()).trim(), `Kp = ${kp.toFixed(1)} N/m`);
    await page.locator(`${THEORY} .formula [data-live=e]`).first().focus();
    assert.match((await tip.textContent()).trim(), /^e = -?\d+\.\d{4} m$/);
  }));

test("live math: the panel shows exactly the equations the content names, in its order", () =>
  withPage(lab, { clock: true }, async (page) => {
    const keys = () => page.$$eval(`${SIM} .live-math .equation`, (els) => els.map((e) => e.dataset.key));
    await open(lab, page, "#/pid/simulation");
    await runFor(page, 100);
    assert.deepEqual(await keys(), ["u", "omega_n", "zeta"]);
    await open(lab, page, "#/ekf/simulation");
    await runFor(page, 100);
    assert.deepEqual(await keys(), ["innovation_range", "innovation_bearing", "trace", "nees"]);
  }));

// Issue 27 §3 for the seven labs after the arms and pid: a symbol in "The
// math" names a part of the scene, and hovering it there draws that part
// as a halo (the canvas names the key it lights).
const SEVEN = [
  // [lab, link, the action that starts a run, the key, what it names]
  ["diffdrive", "#/diffdrive/simulation?w1x=6&w1y=4", null, "d", "the line to the goal"],
  ["potential", "#/potential/simulation?gx=8&gy=3", null, "d0", "the nearest obstacle's influence circle"],
  ["astar", "#/astar/simulation", "plan", "h", "the line from the last cell expanded to the goal"],
  ["cartpole", "#/cartpole/simulation?th0=20", null, "th", "the pole angle's arc"],
  ["dls", "#/dls/simulation?tx=1&ty=1", null, "smax", "the velocity ellipse's long semi-axis"],
  ["rrtstar", "#/rrtstar/simulation?iters=1500&batch=60", "grow", "radius", "the circle of r(n) around the newest node"],
  ["ekf", "#/ekf/simulation?mode=0&seed=1", null, "pxx", "the 3σ ellipse"],
];

test("live links: in each of diffdrive, potential, astar, cartpole, dls, rrtstar and ekf, hovering a symbol in the math panel draws what it names", () =>
  withPage(lab, { clock: true }, async (page) => {
    for (const [id, link, action, key, what] of SEVEN) {
      await open(lab, page, link);
      if (action) await page.click(`${SIM} button[data-action=${action}]`);
      await runFor(page, 400);
      // Paused, so the picture changes only by the halo.
      const play = page.locator(`${SIM} button[data-time=play]`);
      if ((await play.getAttribute("aria-pressed")) === "true") await play.click();
      await runFor(page, 100);
      const width = await page.$eval(`${SIM} canvas.sim-canvas`, (c) => c.width);
      const before = await pixels(page);
      await page.hover(`${SIM} .live-math [data-live=${key}]`);
      await runFor(page, 50);
      assert.equal(await page.$eval(`${SIM} canvas.sim-canvas`, (c) => c.dataset.live), key, id);
      const diff = changed(before, await pixels(page), width);
      assert.ok(diff.n > 200, `${id}: hovering ${key} (${what}) changed ${diff.n} pixels`);
      await screenshot(page, `livelinks-${id}-${key}-1280`);
      await page.mouse.move(0, 0);
    }
  }));

for (const [viewport, name] of [
  [{ width: 1280, height: 800 }, "1280"],
  [{ width: 390, height: 844 }, "390"],
]) {
  test(`live links: diffdrive's e_θ, astar's h and ekf's P lit from the panel, and ekf's σ² on the Theory tab with the run's value (${name})`, () =>
    withPage(lab, { clock: true, viewport }, async (page) => {
      for (const [id, link, action, key] of [
        ["diffdrive", "#/diffdrive/simulation?w1x=6&w1y=4", null, "e"],
        ["astar", "#/astar/simulation", "plan", "h"],
        ["ekf", "#/ekf/simulation?mode=0&seed=1", null, "pxx"],
      ]) {
        await open(lab, page, link);
        if (action) await page.click(`${SIM} button[data-action=${action}]`);
        await runFor(page, 400);
        // A keyboard student: the pointer rests off the page's symbols
        // (where it pressed Plan & drive, the panel scrolled in by the
        // focus could put another symbol under it, and a hover lights that).
        await page.mouse.move(0, 0);
        await page.locator(`${SIM} .live-math [data-live=${key}]`).first().focus();
        await runFor(page, 50);
        assert.equal(await page.$eval(`${SIM} canvas.sim-canvas`, (c) => c.dataset.live), key, id);
        await page.locator(`${SIM} canvas.sim-canvas`).scrollIntoViewIfNeeded();
        await screenshot(page, `livelinks-${id}-${key}-focus-${name}`);
      }
      // The Theory tab: σx² + σy² names P's variances; hovering σx² shows P_xx from the run.
      await page.evaluate(() => (location.hash = "#/ekf/theory"));
      await page.waitForSelector(`${THEORY}:not([hidden])`);
      const symbol = page.locator(`${THEORY} [data-live=pxx]`).first();
      await symbol.scrollIntoViewIfNeeded();
      await symbol.hover();
      const tip = page.locator("article.exp:not([hidden]) .live-tip");
      await tip.waitFor();
      assert.match((await tip.textContent()).trim(), /^σx² = \d\.\d+ m²$/);
      await screenshot(page, `livelinks-ekf-theory-pxx-${name}`);
    }));
}
