// Issue 53: a moment after an input made during the run (cart-pole's Nudge
// pole, a drag on the canvas) had no link: the page left `at=` out,
// silently, so the moment could not be shared or reopened. The link now
// carries those inputs with their times (`then=`, labcore's run_input) and
// reopens the moment exactly. Every moment is reached by stepping a stopped
// clock.

import { test } from "node:test";
import assert from "node:assert/strict";
import { open, readouts, runFor, runUntil, useLab, withPage, worldToPage } from "./helpers.mjs";

const lab = useLab();
const ART = "article.exp:not([hidden])";

/** The step the page shows (the canvas's `data-steps`). */
const stepShown = (page) => page.locator(`${ART} canvas.sim-canvas`).getAttribute("data-steps").then(Number);

/** Pauses the run, then lets the page write its text and link (every 250 ms). */
async function pause(page) {
  await page.locator(`${ART} .tb-play[data-offer=pause]`).click();
  await runFor(page, 300);
}

/** What a reopened moment must show again: the step, the time bar, the readouts. */
async function moment(page) {
  return {
    step: await stepShown(page),
    time: await page.locator(`${ART} .tb-time`).textContent(),
    readouts: await readouts(page),
  };
}

/** Opens `hash` on a fresh page of the same context and returns its moment. */
async function reopened(page, hash) {
  await page.goto("about:blank");
  await open(lab, page, hash);
  await runFor(page, 300);
  return moment(page);
}

test("cartpole: a moment after Nudge pole has a link that carries the nudge and reopens the moment", () =>
  withPage(lab, { clock: true }, async (page) => {
    await open(lab, page, "#/cartpole/simulation");
    await runUntil(page, () => Number(document.querySelector("canvas.sim-canvas").dataset.steps) >= 60, null, {
      sliceMs: 16,
      what: "one second of the run",
    });
    await page.locator(`${ART} button[data-action=nudge]`).click();
    await runFor(page, 500);
    await pause(page);
    const hash = await page.evaluate(() => location.hash);
    assert.match(hash, /[?&]at=\d+\.\d\d(&|$)/, `the moment is named: ${hash}`);
    const then = /[?&]then=([^&]*)/.exec(hash);
    assert.ok(then, `the nudge is carried: ${hash}`);
    assert.match(decodeURIComponent(then[1]), /^\d+\.\d\d:a:nudge$/);
    const shown = await moment(page);
    assert.ok(shown.step > 60, `the run went on past the nudge (step ${shown.step})`);
    const again = await reopened(page, hash);
    assert.deepEqual(again, shown, `${hash} reopens the moment`);
    // Without the nudge the same time is another state: the link's inputs matter.
    const without = await reopened(page, hash.replace(/&then=[^&]*/, ""));
    assert.equal(without.step, shown.step);
    assert.notDeepEqual(without.readouts, shown.readouts, "the nudge changed the run");
  }));

test("potential: a moment after a drag on the canvas during the run has a link that reopens it", () =>
  withPage(lab, { clock: true }, async (page) => {
    await open(lab, page, "#/potential/simulation?o1x=4&o1y=3.6");
    const goal = await worldToPage(page, 7.4, 3);
    await page.mouse.click(goal.x, goal.y);
    await runFor(page, 400);
    // Drag the obstacle while the robot drives.
    const from = await worldToPage(page, 4, 3.6);
    const to = await worldToPage(page, 4.5, 4.2);
    await page.mouse.move(from.x, from.y);
    await page.mouse.down();
    await runFor(page, 50);
    await page.mouse.move(to.x, to.y, { steps: 4 });
    await runFor(page, 50);
    await page.mouse.up();
    await runFor(page, 400);
    await pause(page);
    const hash = await page.evaluate(() => location.hash);
    // The press moved the obstacle and started the run again from there
    // (its start is in the link's o1x, o1y); the rest of the drag came
    // during the new run, and the link carries it.
    assert.match(hash, /[?&]at=/, `the moment is named: ${hash}`);
    assert.match(hash, /[?&]o1x=4\.5&o1y=4\.2(&|$)/, `the run's start: ${hash}`);
    assert.match(hash, /[?&]then=([^&:]+:[mu]:[^&]*)$/, `the drag is carried: ${hash}`);
    const shown = await moment(page);
    assert.deepEqual(await reopened(page, hash), shown, `${hash} reopens the moment`);
  }));

test("a malformed then= says so, opens the moment without the inputs and the lab runs on, with no console error", () =>
  withPage(lab, { clock: true }, async (page) => {
    for (const bad of ["1.00:a", "x:a:nudge", "1.00:q:1,2", "2.00:a:nudge;1.00:a:nudge", "1.00:d:1,NaN"]) {
      await page.goto("about:blank");
      await open(lab, page, `#/cartpole/simulation?run=0&at=1.50&then=${encodeURIComponent(bad)}`);
      await runUntil(page, () => /The link's inputs/.test(document.querySelector("#notice").textContent), undefined, {
        what: `the notice for ${bad}`,
      });
      const notice = await page.locator("#notice").textContent();
      assert.match(notice, /The link's inputs during the run: “.+” is not one/, `${bad}: ${notice}`);
      assert.equal(await stepShown(page), 90, `${bad}: the moment opens`);
    }
    // An input the experiment does not take is said, and the rest opens.
    await page.goto("about:blank");
    await open(lab, page, "#/cartpole/simulation?run=0&at=1.50&then=1.00:a:nosuch");
    await runUntil(page, () => /The link's inputs/.test(document.querySelector("#notice").textContent), undefined, {
      what: "the notice for an unknown button",
    });
    assert.equal(await stepShown(page), 90);
  }));
