// Experiment 11 (EKF localisation and EKF-SLAM) driven like a student would:
// watch the run, pause and single-step it with the time bar, switch to
// EKF-SLAM, run the Monte-Carlo consistency check and export a plot as CSV.

import { test } from "node:test";
import assert from "node:assert/strict";
import { readFile } from "node:fs/promises";
import { DESKTOP, open, readouts, runFor, runUntil, screenshot, settle, useLab, withPage } from "./helpers.mjs";

const lab = useLab();

/** Waits until the status badge matches `pattern`; returns its text. */
async function waitStatus(page, pattern, timeout = 10_000) {
  await runUntil(
      page,
    (source) => new RegExp(source).test(document.querySelector(".sim-status").textContent),
    pattern.source,
    { timeout },
  );
  return (await page.locator(".sim-status").textContent()).trim();
}

/** Waits until the play button's aria-pressed is `value` (updated on the next frame). */
function waitPressed(page, value) {
  return runUntil(
      page,
    (v) => document.querySelector("button[data-time=play]").getAttribute("aria-pressed") === v,
    value,
  );
}

/** Clicks a plot's CSV button and returns the downloaded file's name and text. */
async function downloadCsv(page, key) {
  const [download] = await Promise.all([
    page.waitForEvent("download"),
    page.locator(`button[data-plot-csv=${key}]`).click(),
  ]);
  const path = await download.path();
  return { name: download.suggestedFilename(), text: await readFile(path, "utf8") };
}

test("ekf: the run moves, pauses and single-steps, maps landmarks in SLAM mode, passes the consistency check and exports CSV", () =>
  withPage(lab, { clock: true }, async (page) => {
    await open(lab, page, "#/ekf/simulation");
    await waitStatus(page, /^EKF localisation, known map$/);
    for (const key of ["error", "heading_error", "trace", "nees", "obs_per_loop", "dr_error", "landmarks"]) {
      assert.ok(await page.locator(`[data-readout=${key}]`).count(), `readout ${key} is shown`);
    }
    // The readouts change while the robot drives.
    const first = await readouts(page);
    await runUntil(
      page,
      (before) => document.querySelector("[data-readout=dr_error]").textContent.trim() !== before,
      first.dr_error,
    );
    assert.match(first.error, /^\d+\.\d{3} m$/);
    assert.match(first.heading_error, /^-?\d+\.\d°$/);
    assert.equal(first.landmarks, "6 (known map)");

    // Pause: nothing moves any more.
    const play = page.locator("button[data-time=play]");
    await play.click();
    await waitPressed(page, "false");
    await settle(page);
    const paused = await readouts(page);
    await runFor(page, 600);
    assert.deepEqual(await readouts(page), paused, "paused: the readouts hold still");
    // Single steps advance the run: each press is one filter step.
    const step = page.locator("button[data-time=step]");
    for (let i = 0; i < 10; i += 1) await step.click();
    await settle(page);
    const stepped = await readouts(page);
    assert.notDeepEqual(stepped, paused, "single steps moved the run");
    await runFor(page, 400);
    assert.deepEqual(await readouts(page), stepped, "still paused after stepping");

    // EKF-SLAM: the map starts empty and fills as landmarks are seen.
    await page.locator("select[data-param=mode]").selectOption("1");
    await waitStatus(page, /^EKF-SLAM: 0 of 6 landmarks mapped$/);
    // The link follows within its update interval.
    await runUntil(page, () => /mode=1/.test(location.hash));
    assert.match(await page.evaluate(() => location.hash), /run=0/, "still paused, and the link says so");
    await play.click();
    await waitPressed(page, "true");
    await waitStatus(page, /^EKF-SLAM: [1-6] of 6 landmarks mapped$/);
    assert.match((await readouts(page)).landmarks, /^[1-6] of 6$/);
    await screenshot(page, "ekf-slam-desktop");

    // The consistency check runs progressively and ends with a verdict.
    await page.locator("button[data-action=check]").click();
    await waitStatus(page, /^consistency check… \d+\/50 runs$/);
    const verdict = await waitStatus(
      page,
      /^(consistent|over-confident|under-confident|inconsistent at times): average NEES/,
      60_000,
    );
    assert.match(verdict, /over 50 runs$/);
    assert.match((await readouts(page)).anees, /^\d+\.\d{2}$/);

    // CSV export: the header names every column with its unit.
    const anees = await downloadCsv(page, "anees");
    assert.match(anees.name, /anees\.csv$/);
    const lines = anees.text.trim().split(/\r?\n/);
    assert.equal(lines[0], "Time (s),average NEES");
    assert.equal(lines.length, 1 + 1600, "one row per filter step of an 80 s run");
    assert.ok(lines.slice(1).every((l) => l.split(",").map(Number).every(Number.isFinite)));
    const errorX = await downloadCsv(page, "error_x");
    assert.equal(errorX.text.split(/\r?\n/)[0], "Time (s),x error (m),+3σx (m),−3σx (m)");
    const trace = await downloadCsv(page, "trace");
    assert.equal(trace.text.split(/\r?\n/)[0], "Time (s),σx² + σy² (m²)");
  }));

test("ekf: a setting changed under a consistency check leaves the status on the run (issue 13 §4)", () =>
  withPage(lab, { clock: true }, async (page) => {
    await open(lab, page, "#/ekf/simulation?runs=10");
    await waitStatus(page, /^EKF localisation, known map$/);
    await page.locator("button[data-action=check]").click();
    await waitStatus(page, /^consistency check… \d+\/10 runs$/);
    const sw = page.locator("input[type=text][data-param=sw]");
    await sw.fill("9");
    await sw.press("Enter");
    // The check is dropped and the badge tells the run's state again, for good.
    await waitStatus(page, /^EKF localisation, known map$/);
    await runFor(page, 1500);
    assert.equal((await page.locator(".sim-status").textContent()).trim(), "EKF localisation, known map");
  }));

test("ekf: the Simulation tab at desktop and phone sizes", async () => {
  for (const [name, viewport] of [
    ["desktop", DESKTOP],
    ["phone", { width: 390, height: 844 }],
  ]) {
    await withPage(lab, { viewport, clock: true }, async (page) => {
      await open(lab, page, "#/ekf/simulation");
      await runFor(page, 2500);
      const canvas = await page.locator("canvas.sim-canvas").boundingBox();
      assert.ok(canvas.width > 200 && canvas.height > 200, `canvas ${canvas.width}×${canvas.height}`);
      const overflow = await page.evaluate(
        () => document.documentElement.scrollWidth - document.documentElement.clientWidth,
      );
      assert.ok(overflow <= 0, `no sideways scrolling (${overflow} px)`);
      await screenshot(page, `ekf-simulation-${name}`);
    });
  }
});
