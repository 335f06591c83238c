// Issue 26 §1 (the rest) and §2 in the browser: a point clicked on a plot
// moves the timeline there (cursor on every plot, the scene and readouts of
// that moment), and a change made there branches, keeping the old run on
// the plots under a name that says where it branched. Every moment is
// reached by stepping the simulation, never by waiting on the wall clock.

import { test } from "node:test";
import assert from "node:assert/strict";
import { DESKTOP, open, readouts, runUntil, runUntilReadout, screenshot, settle, useLab, withPage } from "./helpers.mjs";

const lab = useLab();
const PHONE_TALL = { width: 390, height: 844 };

const steps = (page) => page.locator("canvas.sim-canvas").getAttribute("data-steps").then(Number);

async function pause(page) {
  await page.locator("button[data-time=play]").click();
  await runUntil(page, () => document.querySelector("button[data-time=play]").getAttribute("aria-pressed") === "false");
  await settle(page);
}

/** Clicks the plot `key` at `fraction` of its canvas's width, half-way down. */
async function clickPlot(page, key, fraction) {
  const canvas = page.locator(`figure[data-plot=${key}] canvas.plot-canvas`);
  await canvas.scrollIntoViewIfNeeded();
  const box = await canvas.boundingBox();
  await page.mouse.click(box.x + fraction * box.width, box.y + box.height / 2);
  await settle(page);
}

for (const [name, viewport, phone] of [
  ["desktop", DESKTOP, false],
  ["phone", PHONE_TALL, true],
]) {
  test(`timeline (${name}): a pid plot point moves the run there, and a change there keeps the old run by name`, () =>
    withPage(lab, { clock: true, viewport, hasTouch: phone, isMobile: phone }, async (page) => {
      await open(lab, page, "#/pid/simulation");
      await runUntilReadout(page, "x", ">", 0.5);
      await pause(page);
      const end = await steps(page);
      const atEnd = await readouts(page);
      assert.equal(await page.locator("figure[data-plot=response] canvas").getAttribute("data-cursor"), null);
      // A point early on the response plot: the run as it was then, paused.
      await clickPlot(page, "response", 0.3);
      const k = await steps(page);
      assert.ok(k > 0 && k < end, `${k} of ${end}`);
      const atK = await readouts(page);
      assert.ok(Number.parseFloat(atK.x) < Number.parseFloat(atEnd.x), `the cart was behind: ${atK.x} < ${atEnd.x}`);
      for (const key of ["response", "effort"]) {
        const cursor = await page.locator(`figure[data-plot=${key}] canvas`).getAttribute("data-cursor");
        assert.ok(cursor !== null && Number(cursor) < (k + 1) / 60, `${key} cursor at ${cursor}`);
      }
      assert.equal(await page.locator(".tb-scrub").inputValue(), String(k));
      assert.match(await page.locator(".sim-live").textContent(), new RegExp(`^t = ${(k / 60).toFixed(2)} s, `));
      // Step on from there: one step, along the old run.
      await page.locator("button[data-time=step]").click();
      await runUntil(page, (n) => Number(document.querySelector("canvas.sim-canvas").dataset.steps) === n, k + 1);
      // Kp 60 from this moment replays the step from x = 0 (issue 53 §3):
      // the old run is kept, named as the restart it is.
      await page.locator("input[type=range][data-param=kp]").fill("60");
      await settle(page);
      const kept = "before Kp 12 N/m → 60 N/m restarted the run";
      const legend = page.locator("figure[data-plot=response] .legend-item[data-series]", { hasText: kept });
      assert.equal(await legend.count(), 1, kept);
      assert.equal(await legend.isVisible(), true);
      await page.locator("button[data-time=play]").click();
      await runUntilReadout(page, "x", ">", 0.5);
      await pause(page);
      await page.locator("figure[data-plot=response]").scrollIntoViewIfNeeded();
      // A plot below the fold is repainted at most once a second (of page time).
      await page.clock.runFor(1100);
      await settle(page);
      await screenshot(page, `timeline-pid-branched-${name}`);
    }));

  test(`timeline (${name}): cartpole scrubbed back shows a cursor on every plot`, () =>
    withPage(lab, { clock: true, viewport, hasTouch: phone, isMobile: phone }, async (page) => {
      await open(lab, page, "#/cartpole/simulation?kth=15");
      await runUntil(page, () => Number(document.querySelector("canvas.sim-canvas").dataset.steps) >= 240);
      await pause(page);
      await page.locator(".tb-scrub").fill("150");
      await runUntil(page, () => Number(document.querySelector("canvas.sim-canvas").dataset.steps) === 150);
      await settle(page);
      for (const key of ["angle", "position", "force"]) {
        const cursor = await page.locator(`figure[data-plot=${key}] canvas`).getAttribute("data-cursor");
        assert.ok(cursor !== null && Math.abs(Number(cursor) - 2.5) < 0.02, `${key} cursor at ${cursor}`);
      }
      await screenshot(page, `timeline-cartpole-scrubbed-${name}`);
    }));
}

// Cartpole's Procedure step 8, as a student does it: the pole falls with
// kθ = 15 (the other gains at their defaults), the timeline goes back to
// t = 6.00 s, kθ = 120 there catches it, and the old fall stays on the
// angle plot under its name.
test("timeline: cartpole step 8, branched before the fall, the pole is caught and the fall is kept", () =>
  withPage(lab, { clock: true, viewport: DESKTOP }, async (page) => {
    await open(lab, page, "#/cartpole/simulation?kth=15");
    await runUntil(page, () => document.querySelector(".timebar").dataset.clock === "ended", undefined, {
      what: "the fall",
    });
    assert.equal((await readouts(page)).status, "fallen at 8.60 s");
    await page.locator(".tb-scrub").fill("360");
    await runUntil(page, () => Number(document.querySelector("canvas.sim-canvas").dataset.steps) === 360);
    await settle(page);
    assert.equal((await readouts(page)).theta, "31.3°");
    await page.locator("input[type=range][data-param=kth]").fill("120");
    await settle(page);
    const kept = page.locator("figure[data-plot=angle] .legend-item[data-series]", {
      hasText: "before kθ 15 N/rad → 120 N/rad at t = 6.00 s",
    });
    assert.equal(await kept.count(), 1);
    assert.equal(await kept.isVisible(), true);
    // The change plays, as the text says (issue 53 §3): ten seconds on,
    // caught, never leaning further than 31.3°.
    assert.equal(await page.locator("button[data-time=play]").getAttribute("aria-pressed"), "true");
    let peak = 0;
    for (let k = 0; k < 20; k++) {
      const shown = await steps(page);
      await runUntil(page, (n) => Number(document.querySelector("canvas.sim-canvas").dataset.steps) >= n, shown + 30);
      peak = Math.max(peak, Math.abs(Number.parseFloat((await readouts(page)).theta)));
    }
    assert.ok(peak <= 31.3, `${peak}°`);
    assert.doesNotMatch((await readouts(page)).status, /fallen/);
    await screenshot(page, "timeline-cartpole-step8-desktop");
  }));
