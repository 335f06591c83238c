// Issue 53, "Done when": after a whole visit (every Procedure step played
// in order, tests/e2e/procedures.mjs), walk the timeline of the run the
// page shows and check at each moment visited that
// - the slider spans the current run, from its start, on the run's own
//   clock (the slider, the time bar and the link say one time);
// - the readouts and "The math" are of the step the slider is at, the plots
//   follow the scrub (their cursors move with it), and the link reopens
//   that moment with the same readouts;
// - the time keys work from the slider and from the time bar's buttons.
// Every moment is reached by the slider and a stopped clock (helpers'
// runFor), never by waiting on the machine.

import assert from "node:assert/strict";
import { open, runFor } from "./helpers.mjs";

const ART = "article.exp:not([hidden])";
const FRAME_MS = 1000 / 60;
const DT_S = 1 / 60;
/** How many moments of the run are visited, its end included. */
const MOMENTS = 6;

/** What the page shows now, as text: the slider, time bar, link, readouts, their step, the plots' cursors. */
function shown(page) {
  return page.evaluate((art) => {
    const a = document.querySelector(art);
    const slider = a.querySelector(".tb-scrub");
    if (!slider) return null;
    const list = a.querySelector("dl.readouts");
    const math = a.querySelector(".live-math");
    return {
      min: Number(slider.min),
      max: Number(slider.max),
      value: Number(slider.value),
      sliderText: slider.getAttribute("aria-valuetext") ?? "",
      bar: a.querySelector(".tb-time").textContent.trim(),
      hash: location.hash,
      readoutsStep: list?.dataset.step ?? null,
      mathStep: math && !math.closest("[hidden]") ? (math.dataset.step ?? null) : null,
      readouts: [...a.querySelectorAll(".readout")].map((r) => r.textContent.trim().replace(/\s+/g, " ")),
      cursors: [...a.querySelectorAll("figure.plot canvas.plot-canvas")].map((c) =>
        c.hasAttribute("data-cursor") ? Number(c.getAttribute("data-cursor")) : null,
      ),
    };
  }, ART);
}

/** The seconds a "t = 1.23 s" text says. */
function secondsOf(text) {
  const m = /t = (-?\d+(?:\.\d+)?) s/.exec(text);
  assert.ok(m, `a time in “${text}”`);
  return Number(m[1]);
}

/** The slider put at step `n` as a drag leaves it, then read once the page has written its text and link. */
async function scrubTo(page, n) {
  await page.locator(`${ART} .tb-scrub`).fill(String(n));
  // The page writes its text once the slider has rested (150 ms) and the
  // address bar every 250 ms: read after both, on the stopped clock.
  await runFor(page, 250 + 3 * FRAME_MS);
  return shown(page);
}

/** Checks one moment: one clock, one step, one run. */
function checkMoment(id, s) {
  const where = `${id}, slider at step ${s.value} of ${s.min}..${s.max}`;
  assert.equal(s.min, 0, `${where}: the slider spans the current run from its start`);
  const t = secondsOf(s.sliderText);
  assert.ok(Math.abs(t - s.value * DT_S) < DT_S / 2, `${where}: the slider says t = ${t} s, its step is ${(s.value * DT_S).toFixed(2)} s (the run's own clock)`);
  assert.equal(secondsOf(s.bar), t, `${where}: the time bar says “${s.bar}”, the slider “${s.sliderText}”`);
  if (s.readoutsStep !== null) assert.equal(Number(s.readoutsStep), s.value, `${where}: the readouts are of step ${s.readoutsStep}`);
  if (s.mathStep !== null) assert.equal(Number(s.mathStep), s.value, `${where}: "The math" is of step ${s.mathStep}`);
  // Every moment's link names it, a moment after an input the run was
  // given on its way (a Nudge, a drag) too: the link carries those inputs
  // (`then=`).
  const at = /[?&]at=([^&]*)/.exec(s.hash);
  if (s.value > 0) {
    assert.ok(at, `${where}: the link names no moment: ${s.hash}`);
    assert.ok(Math.abs(Number(at[1]) - t) < DT_S / 2, `${where}: the link says at=${at[1]}, the page t = ${t} s`);
  }
  return Boolean(at);
}

/**
 * Walks the timeline of the run experiment `id`'s page shows after its
 * Procedure (see the file's comment). `lab` is helpers' useLab().
 */
export async function alongTheTimeline(lab, page, id) {
  const pause = page.locator(`${ART} .tb-play[data-offer=pause]`);
  if (await pause.count()) await pause.click();
  await runFor(page, 2 * FRAME_MS);
  const first = await shown(page);
  if (!first || first.max < 2) return; // no run in time (fk, ik): nothing to walk
  const steps = Array.from({ length: MOMENTS }, (_, k) => Math.round((first.max * (k + 1)) / MOMENTS));
  let before = null;
  let middle = null;
  // A past moment after inputs during the run (its link carries them).
  let afterInputs = null;
  const pastCursors = [];
  for (const n of steps) {
    const s = await scrubTo(page, n);
    const linked = checkMoment(id, s);
    // The plots follow the scrub: a cursor of the run shown never moves
    // back while the slider moves on (a plot of another run would stay).
    if (before) {
      s.cursors.forEach((c, i) => {
        if (c !== null && before.cursors[i] !== null)
          assert.ok(c >= before.cursors[i], `${id}: plot ${i + 1}'s cursor went from ${before.cursors[i]} to ${c} as the slider went from step ${before.value} to ${s.value}`);
      });
    }
    // At a past moment the plots of the run draw its cursor.
    if (n < first.max && first.cursors.length > 0) pastCursors.push(s.cursors.some((c) => c !== null));
    before = s;
    if (linked && n < first.max && (middle === null || middle.value < first.max / 2)) middle = s;
    if (linked && n < first.max && /[?&]then=/.test(s.hash)) afterInputs = s;
  }
  if (pastCursors.some(Boolean)) assert.ok(pastCursors.every(Boolean), `${id}: at some past moments no plot draws the cursor (${pastCursors})`);
  // The link of a past moment reopens it: the same time and readouts.
  // (The later first: a reopened link's run ends at its moment.)
  for (const moment of new Set([afterInputs, middle].filter(Boolean).sort((a, b) => b.value - a.value))) {
    await scrubTo(page, moment.value);
    await page.goto("about:blank");
    await open(lab, page, moment.hash);
    await runFor(page, 250 + 3 * FRAME_MS);
    const again = await shown(page);
    assert.equal(again.value, moment.value, `${id}: ${moment.hash} reopens step ${again.value}, not ${moment.value}`);
    assert.deepEqual(again.readouts, moment.readouts, `${id}: ${moment.hash} reopens other readouts`);
  }
  // The keys from the slider and from the buttons: , and . step (one of
  // the experiment's steps, as Step's title says: the EKF's is 0.05 s),
  // M marks.
  const title = await page.locator(`${ART} [data-time=step]`).getAttribute("title");
  const stepS = /One step: ([\d.]+) s/.exec(title);
  assert.ok(stepS, `${id}: Step's title says its step (${title})`);
  const k = Math.round(Number(stepS[1]) / DT_S);
  const at = (await shown(page)).value;
  const to = Math.max(k, Math.min(at, (await shown(page)).max - k));
  await scrubTo(page, to);
  const slider = page.locator(`${ART} .tb-scrub`);
  await slider.focus();
  await page.keyboard.press(",");
  await runFor(page, 250 + 3 * FRAME_MS);
  assert.equal((await shown(page)).value, to - k, `${id}: “,” with the slider focused steps back`);
  await page.keyboard.press(".");
  await runFor(page, 250 + 3 * FRAME_MS);
  assert.equal((await shown(page)).value, to, `${id}: “.” with the slider focused steps on`);
  await page.locator(`${ART} [data-time=back]`).focus();
  await page.keyboard.press(",");
  await runFor(page, 250 + 3 * FRAME_MS);
  assert.equal((await shown(page)).value, to - k, `${id}: “,” with Back focused steps back`);
  const marks = () => page.locator(`${ART} .tb-mark`).count();
  const had = await marks();
  await page.locator(`${ART} [data-time=mark]`).focus();
  await page.keyboard.press("m");
  await runFor(page, 250 + 3 * FRAME_MS);
  assert.equal(await marks(), had + 1, `${id}: “M” with Mark focused marks the moment`);
  checkMoment(id, await shown(page));
}
