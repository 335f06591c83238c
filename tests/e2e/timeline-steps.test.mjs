// Issue 26: the Procedure steps that use the timeline, done on the page as
// the text says (pid's step 9 is in marks.test.mjs). The page's clock is
// stopped: every moment is reached by stepping the simulation.

import { test } from "node:test";
import assert from "node:assert/strict";
import { DESKTOP, open, readouts, runUntil, settle, useLab, withPage } from "./helpers.mjs";

const lab = useLab();
const ART = "article.exp:not([hidden])";

const steps = (page) => page.locator(`${ART} canvas.sim-canvas`).getAttribute("data-steps").then(Number);

async function atStep(page, n) {
  await runUntil(page, (k) => Number(document.querySelector("canvas.sim-canvas").dataset.steps) === k, n, {
    what: `step ${n}`,
  });
  await settle(page);
}

async function scrubTo(page, n) {
  await page.locator(`${ART} .tb-scrub`).fill(String(n));
  await atStep(page, n);
}

/** The Open list's rows as text cells. */
const openRows = (page) =>
  page.$$eval(`${ART} [data-table=open] tbody tr`, (rows) =>
    rows.map((r) => [...r.querySelectorAll("td")].map((td) => td.textContent)),
  );

test("astar step 8: after Run to end, back until the path disappears: the goal waits in the open list; six steps back (16, 13) is back", () =>
  withPage(lab, { clock: true, viewport: DESKTOP }, async (page) => {
    await open(lab, page, "#/astar/simulation?size=0&seed=1&w=1&rate=1");
    await page.locator(`${ART} button[data-action=maze]`).click();
    await settle(page);
    await page.locator(`${ART} button[data-action=plan]`).click();
    await page.locator(`${ART} button[data-time=end]`).click();
    await runUntil(page, () => document.querySelector(".timebar").dataset.clock === "ended", undefined, {
      what: "the run's end",
    });
    assert.equal(await page.locator(`${ART} .sim-status`).textContent().then((t) => t.includes("arrived: path cost 84.000")), true);
    assert.equal((await readouts(page)).expanded, "93");
    // Back along the record until the path disappears (the first step with a
    // path is found by halving; the slider goes anywhere at once).
    let [lo, hi] = [0, await steps(page)];
    while (hi - lo > 1) {
      const mid = Math.floor((lo + hi) / 2);
      await scrubTo(page, mid);
      if ((await readouts(page)).path_cells === "--") lo = mid;
      else hi = mid;
    }
    await scrubTo(page, lo);
    assert.match(await page.locator(`${ART} .sim-status`).textContent(), /searching… 92 expanded/);
    let rows = await openRows(page);
    assert.deepEqual(rows[1].slice(1), ["(17, 13)", "84", "0", "84"], JSON.stringify(rows));
    // Six presses of Back: one expansion fewer.
    await page.locator(`${ART} canvas.sim-canvas`).focus();
    for (let i = 1; i <= 6; i++) {
      await page.keyboard.press(",");
      await atStep(page, lo - i);
    }
    assert.equal((await readouts(page)).expanded, "91");
    rows = await openRows(page);
    assert.ok(rows.every((r) => r[1] !== "(17, 13)"), JSON.stringify(rows));
    assert.ok(
      rows.slice(1).some((r) => r.slice(1).join() === "(16, 13),83,1,84"),
      JSON.stringify(rows),
    );
  }));

test("ekf step 9: t = 22.25 s before the bottom-left sighting, one Step to t = 22.30 s: the uncertainty drops seven-fold", () =>
  withPage(lab, { clock: true, viewport: DESKTOP }, async (page) => {
    // Localisation, seed 1, from t = 0 (the defaults, as Reset leaves them).
    await open(lab, page, "#/ekf/simulation?mode=0&seed=1");
    await runUntil(page, () => Number(document.querySelector("canvas.sim-canvas").dataset.steps) > 23 * 60, undefined, {
      sliceMs: 500,
      what: "t past 23 s",
    });
    await page.locator(`${ART} button[data-time=play]`).click();
    await settle(page);
    await scrubTo(page, Math.round(22.25 * 60));
    assert.equal(await page.locator(`${ART} .tb-time`).textContent(), "t = 22.25 s");
    assert.equal((await readouts(page)).trace, "0.07448 m²");
    await page.locator(`${ART} button[data-time=step]`).click();
    await atStep(page, Math.round(22.25 * 60) + 3);
    assert.equal(await page.locator(`${ART} .tb-time`).textContent(), "t = 22.30 s");
    assert.equal((await readouts(page)).trace, "0.01034 m²");
    // Back: the moment before again, to the digit.
    await page.locator(`${ART} button[data-time=back]`).click();
    await atStep(page, Math.round(22.25 * 60));
    assert.equal((await readouts(page)).trace, "0.07448 m²");
  }));
