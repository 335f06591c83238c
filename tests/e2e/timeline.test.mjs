// Issue 26 §1, the timeline in the time bar, driven as a student would on a
// stopped page clock: pause, step, step back, scrub the slider back and
// forth, run a search to its end. Every moment is reached by stepping the
// simulation, never by waiting on the wall clock.

import { test } from "node:test";
import assert from "node:assert/strict";
import { DESKTOP, open, readouts, runUntil, runUntilReadout, screenshot, settle, useLab, withPage } from "./helpers.mjs";

const lab = useLab();
const PHONE_TALL = { width: 390, height: 844 };

const steps = (page) => page.locator("canvas.sim-canvas").getAttribute("data-steps").then(Number);

/** Waits (in page time) until the canvas shows step `n` and its readouts. */
async function atStep(page, n) {
  await runUntil(page, (k) => Number(document.querySelector("canvas.sim-canvas").dataset.steps) === k, n, {
    what: `step ${n}`,
  });
  // The frame after the jump writes the readouts.
  await settle(page);
}

/** Moves the timeline slider to step `n`, as a drag does. */
async function scrubTo(page, n) {
  await page.locator(".tb-scrub").fill(String(n));
  await atStep(page, n);
}

test("timeline: pid pauses, steps, steps back and scrubs back to the readouts the run had", () =>
  withPage(lab, { clock: true }, async (page) => {
    await open(lab, page, "#/pid/simulation");
    await runUntilReadout(page, "x", ">", 0.5);
    await page.locator("button[data-time=play]").click();
    await runUntil(page, () => document.querySelector("button[data-time=play]").getAttribute("aria-pressed") === "false");
    await settle(page);
    const s = await steps(page);
    const atS = await readouts(page);
    // Step, then Step back: the readouts of step s again, to the digit.
    await page.locator("button[data-time=step]").click();
    await atStep(page, s + 1);
    await page.locator("button[data-time=back]").click();
    await atStep(page, s);
    assert.deepEqual(await readouts(page), atS);
    // The slider spans the run and says where it is.
    const slider = page.locator(".tb-scrub");
    assert.equal(await slider.getAttribute("max"), String(s + 1));
    assert.equal(await slider.inputValue(), String(s));
    // Scrub back to the middle of the run: paused there, its time and readouts.
    const k = Math.floor(s / 2);
    await scrubTo(page, k);
    const atK = await readouts(page);
    assert.ok(Number.parseFloat(atK.x) < Number.parseFloat(atS.x), `the cart was behind: ${atK.x} < ${atS.x}`);
    assert.equal(await page.locator(".tb-time").textContent(), `t = ${(k / 60).toFixed(2)} s`);
    assert.equal(await slider.getAttribute("aria-valuetext"), `t = ${(k / 60).toFixed(2)} s, Position x = ${atK.x}`);
    assert.equal(await page.locator("button[data-time=play]").getAttribute("aria-pressed"), "false");
    // `,` one step back, `.` one step on: the same readouts as before.
    await page.locator("canvas.sim-canvas").focus();
    await page.keyboard.press(",");
    await atStep(page, k - 1);
    await page.keyboard.press(".");
    await atStep(page, k);
    assert.deepEqual(await readouts(page), atK);
    // Forward to the end of the record: the state the run had there.
    await scrubTo(page, s);
    assert.deepEqual(await readouts(page), atS);
    await screenshot(page, "timeline-pid-desktop");
  }));

test("timeline: astar's Run to end finishes the search at once, then the slider scrubs back through it", () =>
  withPage(lab, { clock: true, viewport: DESKTOP }, async (page) => {
    await open(lab, page, "#/astar/simulation");
    await page.locator("button[data-action=plan]").click();
    await page.locator("button[data-time=end]").click();
    await runUntil(page, () => document.querySelector(".timebar").dataset.clock === "ended", undefined, {
      what: "the run's end",
    });
    const end = await steps(page);
    assert.ok(end > 2, `${end} steps`);
    assert.equal(await page.locator(".tb-scrub").getAttribute("max"), String(end));
    const expandedAtEnd = Number((await readouts(page)).expanded);
    // One step back (`,`), then to the search's first step: fewer cells
    // expanded, as the search had then.
    await page.locator("canvas.sim-canvas").focus();
    await page.keyboard.press(",");
    await atStep(page, end - 1);
    await scrubTo(page, 1);
    const expandedAtOne = Number((await readouts(page)).expanded);
    assert.ok(expandedAtOne > 0 && expandedAtOne < expandedAtEnd, `${expandedAtOne} then ${expandedAtEnd}`);
    // The slider's Home key: the start of the search.
    await page.locator(".tb-scrub").focus();
    await page.keyboard.press("Home");
    await atStep(page, 0);
    assert.equal((await readouts(page)).expanded, "0");
    await screenshot(page, "timeline-astar-desktop");
  }));

test("timeline: the time bar with its slider on a phone (pid, astar)", () =>
  withPage(lab, { clock: true, viewport: PHONE_TALL, hasTouch: true, isMobile: true }, async (page) => {
    await open(lab, page, "#/pid/simulation");
    await runUntilReadout(page, "x", ">", 0.5);
    await page.locator(".tb-scrub").scrollIntoViewIfNeeded();
    const box = await page.locator(".tb-scrub").boundingBox();
    assert.ok(box.width > 300, `the slider takes the bar's width: ${box.width}`);
    await screenshot(page, "timeline-pid-phone");
    await open(lab, page, "#/astar/simulation");
    await page.locator("button[data-action=plan]").click();
    await page.locator("button[data-time=end]").click();
    await runUntil(page, () => document.querySelector(".timebar").dataset.clock === "ended");
    await page.locator(".tb-scrub").scrollIntoViewIfNeeded();
    await screenshot(page, "timeline-astar-phone");
  }));

test("timeline: a real drag of the slider moves the scene at once, keeps the plots' pictures while it moves and repaints them at rest (cartpole)", () =>
  withPage(lab, { clock: true }, async (page) => {
    await open(lab, page, "#/cartpole/simulation");
    await page.locator("button[data-time=end]").click();
    // Run to end is done when the steps stop growing.
    await runUntil(
      page,
      () => {
        const n = Number(document.querySelector("canvas.sim-canvas").dataset.steps);
        const done = n > 0 && n === window.__lastSteps;
        window.__lastSteps = n;
        return done;
      },
      null,
      { sliceMs: 200, what: "the end of Run to end" },
    );
    const end = await steps(page);
    assert.ok(end / 60 > 25, `a run longer than the plots' 20 s window: ${end} steps`);
    const picture = () => page.locator("figure[data-plot=angle] canvas.plot-canvas").getAttribute("data-layout");
    const atEnd = await picture();
    const slider = page.locator(".tb-scrub");
    await slider.scrollIntoViewIfNeeded();
    const box = await slider.boundingBox();
    const y = box.y + box.height / 2;
    // The thumb sits at the right end (the run's last step).
    await page.mouse.move(box.x + box.width - 6, y);
    await page.mouse.down();
    const seen = [];
    for (let i = 1; i <= 8; i++) {
      await page.mouse.move(box.x + box.width * (1 - 0.1 * i), y, { steps: 2 });
      await settle(page);
      seen.push(await steps(page));
      assert.equal(await picture(), atEnd, `move ${i}: the plot keeps its picture while the drag moves`);
    }
    assert.ok(seen.every((s, i) => i === 0 || s < seen[i - 1]), `the scene follows every move back: ${seen}`);
    // The pointer rests, still down: the plots follow the moment shown.
    await page.clock.runFor(1200);
    assert.notEqual(await picture(), atEnd, "the plot is repainted once the drag rests");
    await page.mouse.up();
    await settle(page);
    const k = await steps(page);
    const t = (k / 60).toFixed(2);
    assert.equal(await page.locator(".tb-time").textContent(), `t = ${t} s`);
    const spoken = await slider.getAttribute("aria-valuetext");
    assert.ok(spoken.startsWith(`t = ${t} s, `), `the slider names the moment it stopped at: ${spoken}`);
    const cursor = page.locator("figure[data-plot=angle] .plot-cursor");
    assert.equal(await cursor.isVisible(), true, "the cursor is on the repainted plot");
  }));
