// Experiments 7 (PID) and 8 (cart-pole) driven like a student would: watch
// the readouts move, press the actions, pause and single-step with the time
// bar, and download a plot's CSV.

import { test } from "node:test";
import assert from "node:assert/strict";
import { readFile } from "node:fs/promises";
import { join } from "node:path";
import { DESKTOP, SHOTS, open, readouts, runFor, runUntil, runUntilReadout, screenshot, settle, useLab, withPage } from "./helpers.mjs";

const lab = useLab();
const PHONE_TALL = { width: 390, height: 844 };

const num = (text) => Number.parseFloat(text);

/**
 * Runs the page's frozen clock until `[data-readout=key]`'s number (its
 * magnitude with `abs`) is `op` (">" or "<") `bound`: simulated time, so a
 * busy machine cannot make it miss (helpers.mjs `runUntilReadout`).
 */
const waitReadout = runUntilReadout;

/** Clicks a plot's CSV button and returns the downloaded text. */
async function downloadCsv(page, key) {
  const [download] = await Promise.all([
    page.waitForEvent("download"),
    page.locator(`button[data-plot-csv="${key}"]`).click(),
  ]);
  assert.match(download.suggestedFilename(), new RegExp(`${key}\\.csv$`));
  return readFile(await download.path(), "utf8");
}

/** A screenshot of the whole page into target/e2e-shots/. */
async function fullPage(page, name) {
  await page.screenshot({ path: join(SHOTS, `${name}.png`), fullPage: true });
}

/** Pauses with the time bar, then checks one Step advances exactly one fixed step. */
async function pauseAndStep(page) {
  const play = page.locator("button[data-time=play]");
  await play.click();
  await runUntil(
      page,
    () => document.querySelector("button[data-time=play]").getAttribute("aria-pressed") === "false",
  );
  const canvas = page.locator("canvas.sim-canvas");
  const before = Number(await canvas.getAttribute("data-steps"));
  await settle(page);
  assert.equal(Number(await canvas.getAttribute("data-steps")), before, "paused: the clock stands still");
  await page.locator("button[data-time=step]").click();
  await runUntil(
      page,
    (n) => Number(document.querySelector("canvas.sim-canvas").dataset.steps) === n + 1,
    before,
  );
  assert.match(await page.evaluate(() => location.hash), /run=0/);
  await play.click();
  await runUntil(
      page,
    () => document.querySelector("button[data-time=play]").getAttribute("aria-pressed") === "true",
  );
}

test("pid: the cart chases the setpoint, runs can be pinned, the time bar steps and the CSV downloads", () =>
  withPage(lab, { clock: true }, async (page) => {
    await open(lab, page, "#/pid/simulation");
    let r = await readouts(page);
    assert.ok(num(r.x) < 0.5, `the cart starts near 0: ${r.x}`);
    assert.match(r.poles, /^-0\.18\d, /);
    assert.equal(r.stability, "stable");
    // The readouts follow the cart toward the 1 m setpoint.
    await waitReadout(page, "x", ">", 0.9);
    await waitReadout(page, "rise", ">", 0);
    r = await readouts(page);
    assert.match(r.overshoot, /^\d+\.\d%$/);
    assert.match(r.rise, /^\d+\.\d\d s$/);
    await pauseAndStep(page);

    // "Fit latest run" appears once a run is kept to compare with.
    const fit = page.locator("article.exp:not([hidden]) figure.plot [data-plot-fit]").first();
    assert.equal(await fit.isVisible(), false, "no pin yet: nothing to fit past");
    await page.locator("button[data-action=pin]").click();
    await runUntil(page, () => Boolean(document.querySelector("[data-readout=pinA]")));
    await runUntil(page, () => Boolean(document.querySelector("article.exp:not([hidden]) figure.plot [data-plot-fit]:not([hidden])")?.offsetParent));
    assert.match((await readouts(page)).pinA, /^Kp 12 · Ki 2 · Kd 6, overshoot \d+\.\d%, rise /);

    // A gain change replays the step from x = 0 with the pin kept.
    await page.locator("input[type=text][data-param=kd]").fill("2");
    await page.locator("input[type=text][data-param=kd]").press("Enter");
    await runUntil(page, () => /kd=2(&|$)/.test(location.hash));
    await waitReadout(page, "x", ">", 0.9);
    await page.locator("button[data-action=step]").click();
    await waitReadout(page, "x", "<", 0.5);
    await waitReadout(page, "x", ">", 0.5);
    assert.ok((await readouts(page)).pinA, "pins survive a new step");
    // Issue 13 §5: the legend names the pinned run's gains, as the CSV does.
    const legend = await page.$$eval("figure.plot .legend-item[data-series]:not([hidden])", (items) => items.map((i) => i.textContent));
    assert.ok(legend.includes("A: Kp 12, Ki 2, Kd 6"), `legend: ${legend.join(" | ")}`);

    const csv = await downloadCsv(page, "response");
    const header = csv.split("\r\n")[0];
    // A pinned run is named after its gains; the empty slots keep their names.
    const quote = (s) => (s.includes(",") ? `"${s}"` : s);
    const columns = ["position x", "A: Kp 12, Ki 2, Kd 6", "pinned run B", "pinned run C", "pinned run D"]
      .map((s) => `${quote(`${s} Time since step (s)`)},${quote(`${s} (m)`)}`)
      .join(",");
    assert.equal(header, columns);
    assert.ok(csv.split("\r\n").length > 20, "every sample is exported");
    // Sample times are k/100 s, written as such (0.07, not 0.07000000000000001).
    // Every series has its own time column (even columns); shorter ones end in empty cells.
    const times = csv
      .split("\r\n")
      .slice(1, -1)
      .flatMap((row) => row.split(",").filter((_, k) => k % 2 === 0))
      .filter((t) => t !== "");
    assert.ok(times.length > 20);
    assert.ok(times.every((t) => /^\d+(\.\d{1,2})?$/.test(t)), `time columns: ${times.slice(0, 12)}`);
    const effort = await downloadCsv(page, "effort");
    assert.equal(
      effort.split("\r\n")[0],
      "Time since step (s),u (applied) (N),P = Kp·e (N),I = Ki·∫e (N),D = Kd·de/dt (N)",
    );
    await page.locator("button[data-action=clear_pins]").click();
    await runUntil(page, () => !document.querySelector("[data-readout=pinA]"));
  }));

test("cartpole: the pole is caught, nudged, dropped and caught again; LQR gains go to the sliders", () =>
  withPage(lab, { clock: true }, async (page) => {
    await open(lab, page, "#/cartpole/simulation");
    let r = await readouts(page);
    assert.match(r.open_eig, /^3\.972, /);
    assert.equal(r.closed_verdict, "stable");
    // Caught from 6°: the angle readout falls toward zero.
    await waitReadout(page, "theta", "<", 1, { abs: true });
    await pauseAndStep(page);

    // Nudged while paused, the readouts show the kick itself (while a run
    // streams they follow it four times a second, and the kick is brief).
    const play = page.locator("button[data-time=play]");
    await play.click();
    await runUntil(page, () => document.querySelector("button[data-time=play]").getAttribute("aria-pressed") === "false");
    await page.locator("button[data-action=nudge]").click();
    await waitReadout(page, "omega", ">", 5, { abs: true });
    await play.click();
    await waitReadout(page, "theta", "<", 0.5, { abs: true });

    await page.locator("button[data-action=drop]").click();
    await runUntil(page, () => /control off/.test(document.querySelector(".sim-status").textContent));
    await waitReadout(page, "theta", ">", 3, { abs: true });
    // The Control toggle shows the drop: off is checked. Switching it on catches the pole.
    assert.ok(await page.locator("input[data-param=ctl][value='0']").isChecked(), "the toggle shows control off");
    await page.locator("input[data-param=ctl][value='1']").check();
    await waitReadout(page, "theta", "<", 1, { abs: true });
    // The status judges the recent swing, so it may still name the drop's
    // peak when θ first reads under 1°; the catch shows once that passes.
    await runUntil(page, () => /^balanc/.test(document.querySelector("article.exp:not([hidden]) [data-readout=status]").textContent));

    await page.locator("button[data-action=lqr]").click();
    const proposal = (await readouts(page)).lqr;
    const kth = /kθ ([\d.]+)/.exec(proposal)[1];
    await runUntil(page, (k) => location.hash.includes(`kth=${Number(k)}`), kth);
    assert.equal(await page.locator("input[type=text][data-param=kth]").inputValue(), String(Number(kth)));

    const csv = await downloadCsv(page, "angle");
    assert.equal(csv.split("\r\n")[0], "Time (s),θ (nonlinear) (°),θ (linear model) (°)");
    const energy = await downloadCsv(page, "energy");
    assert.equal(energy.split("\r\n")[0], "Time (s),(E − E₀)/E₀ (%)");
  }));

test("cartpole: with control off and RK4 the pole falls and the run ends", () =>
  withPage(lab, { clock: true }, async (page) => {
    await open(lab, page, "#/cartpole/simulation?ctl=0&integ=1&fall=1&th0=5");
    await runUntil(page, () => /pole fallen/.test(document.querySelector(".sim-status").textContent));
    const r = await readouts(page);
    assert.match(r.status, /^fallen at \d+\.\d\d s$/);
    assert.ok(Math.abs(num(r.theta)) > 12);
  }));

test("cartpole: with θ₀ = 0 the pole rests, and neither Play nor Step adds samples (issue 14)", () =>
  withPage(lab, { clock: true }, async (page) => {
    await open(lab, page, "#/cartpole/simulation?th0=0");
    await runUntil(page, () => /balanced/.test(document.querySelector(".sim-status").textContent));
    const rows = async () => (await downloadCsv(page, "angle")).trim().split("\r\n").length;
    const before = await rows();
    await settle(page);
    assert.equal(await rows(), before, "Play: the resting pole adds no samples");
    const play = page.locator("button[data-time=play]");
    await play.click();
    await runUntil(
      page,
      () => document.querySelector("button[data-time=play]").getAttribute("aria-pressed") === "false",
    );
    for (let i = 0; i < 20; i += 1) {
      await page.locator("button[data-time=step]").click();
    }
    await settle(page);
    assert.equal(await rows(), before, "Step: the resting pole adds no samples either");
    assert.equal((await readouts(page)).theta, "0.0°");
  }));

for (const [name, viewport] of [
  ["desktop", DESKTOP],
  ["phone", PHONE_TALL],
]) {
  test(`screenshots of both simulation tabs (${name})`, () =>
    withPage(lab, { viewport, clock: true }, async (page) => {
      await open(lab, page, "#/pid/simulation");
      await waitReadout(page, "x", ">", 0.95);
      await page.locator("button[data-action=pin]").click();
      await page.locator("input[type=text][data-param=kd]").fill("2");
      await page.locator("input[type=text][data-param=kd]").press("Enter");
      await waitReadout(page, "settling", ">", 0);
      await settle(page);
      await page.evaluate(() => window.scrollTo(0, 0));
      await screenshot(page, `pid-simulation-${name}`);
      await fullPage(page, `pid-full-${name}`);
      await open(lab, page, "#/cartpole/simulation?th0=20");
      await runFor(page, 1500);
      await settle(page);
      await screenshot(page, `cartpole-simulation-${name}`);
      await fullPage(page, `cartpole-full-${name}`);
    }));
}

// Issue 23 §3, pid step 8: the unstable tuning's growth is the step's lesson.
// Opened from its own link, the cart is still on the track two simulated
// seconds after the page is ready, swinging past the setpoint on both sides,
// and then runs off the track with the status saying so.
test("pid step 8: from its link the unstable run swings visibly before it leaves the track", () =>
  withPage(lab, { clock: true }, async (page) => {
    await open(lab, page, "#/pid/simulation?kp=20&ki=5&kd=0&c=0&d=0&sat=0");
    await runUntil(page, () => Number.parseFloat(document.querySelector("article.exp:not([hidden]) .tb-time").textContent.replace("t = ", "")) > 2);
    const status = await page.locator("article.exp:not([hidden]) .sim-status").textContent();
    assert.doesNotMatch(status, /off the track/, "still swinging after 2 s");
    await screenshot(page, "pid-step-8-swinging");
    await runUntil(page, () => /off the track at/.test(document.querySelector("article.exp:not([hidden]) .sim-status").textContent));
    await screenshot(page, "pid-step-8-off-the-track");
  }));
