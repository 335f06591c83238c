// Issue 26 §3, marks, driven as a student would on a stopped page clock:
// run to the end, scrub back to a moment, mark it (button or M), see the
// mark on every plot, in the link and in the lab report. Every moment is
// reached by stepping the simulation, never by waiting on the wall clock.

import { test } from "node:test";
import assert from "node:assert/strict";
import { mkdirSync } from "node:fs";
import { readFile, writeFile } from "node:fs/promises";
import { join } from "node:path";
import { DESKTOP, SHOTS, open, readouts, runUntil, screenshot, settle, useLab, withPage } from "./helpers.mjs";

const lab = useLab();
const PHONE_TALL = { width: 390, height: 844 };
const ART = "article.exp:not([hidden])";

/** Moves the timeline slider to step `n` and waits until the page shows it. */
async function scrubTo(page, n) {
  await page.locator(`${ART} .tb-scrub`).fill(String(n));
  await runUntil(page, (k) => Number(document.querySelector("canvas.sim-canvas").dataset.steps) === k, n, {
    what: `step ${n}`,
  });
  await settle(page);
}

/** The steps the marks' list shows. */
const listed = (page) => page.$$eval(`${ART} .tb-mark`, (els) => els.map((e) => e.dataset.mark));

/** Pid's Procedure step 9 on the page: Run to end, back to the peak, mark it. */
async function pidPeakMarked(page) {
  await open(lab, page, "#/pid/simulation?kp=25&ki=0&kd=2&c=1&run=0");
  await page.locator(`${ART} button[data-time=end]`).click();
  await runUntil(page, () => document.querySelector(".timebar").dataset.clock === "ended", undefined, {
    what: "the run's end",
  });
  // The peak: Position x reads its largest, 1.374 m, at steps 39 and 40;
  // the response curve's top sample (t = 0.66 s on the plot) is step 40's.
  const x = async (k) => {
    await scrubTo(page, k);
    return (await readouts(page)).x;
  };
  assert.ok(Number.parseFloat(await x(38)) < 1.374);
  assert.ok(Number.parseFloat(await x(41)) < 1.374);
  assert.equal(await x(39), "1.374 m");
  assert.equal(await x(40), "1.374 m");
  await page.locator(`${ART} button[data-time=mark]`).click();
  await settle(page);
  await runUntil(page, () => /[?&]marks=0\.67(&|$)/.test(location.hash), undefined, { what: "the link's marks" });
}

test("marks: pid's peak, scrubbed to and marked, is a triangle on every plot, in the link and in the report", () =>
  withPage(lab, { clock: true, viewport: DESKTOP }, async (page) => {
    await pidPeakMarked(page);
    assert.deepEqual(await listed(page), ["40"]);
    assert.equal(await page.locator(`${ART} button[data-time=mark]`).getAttribute("aria-pressed"), "true");
    // Every plot draws the mark, at its own sample of that step.
    const drawn = await page.$$eval(`${ART} figure.plot canvas`, (cs) => cs.map((c) => c.dataset.marks ?? ""));
    assert.ok(drawn.length >= 2 && drawn.every((d) => d.length > 0), JSON.stringify(drawn));
    const [t, y] = drawn[0].split(" ")[0].split(",").map(Number);
    assert.equal(t.toFixed(2), "0.66");
    assert.equal(y.toFixed(3), "1.374");
    await screenshot(page, "marks-pid-desktop");
    // Live again at the end: M marks that moment too.
    const end = Number(await page.locator(`${ART} .tb-scrub`).getAttribute("max"));
    await scrubTo(page, end);
    await page.locator("canvas.sim-canvas").focus();
    await page.keyboard.press("m");
    await settle(page);
    assert.deepEqual(await listed(page), ["40", String(end)]);
    // The report: a section per mark, the first with the peak's readouts.
    const [download] = await Promise.all([
      page.waitForEvent("download"),
      page.locator(`${ART} button[data-export=report]`).click(),
    ]);
    const html = await readFile(await download.path(), "utf8");
    assert.match(html, /<h2>Marked moments<\/h2>/);
    const first = html.slice(html.indexOf('<section class="mark" data-mark-t="0.67">'));
    assert.match(first, /^<section class="mark" data-mark-t="0.67"><h3>Mark 1: t = 0.67 s<\/h3>/);
    const section = first.slice(0, first.indexOf("</section>"));
    assert.match(section, /<tr data-readout="x"><th scope="row">Position x<\/th><td class="num">1.374 m<\/td><\/tr>/);
    assert.match(section, /<svg/);
    assert.match(html, new RegExp(`<h3>Mark 2: t = ${(end / 60).toFixed(2)} s</h3>`));
    mkdirSync(SHOTS, { recursive: true });
    const file = join(SHOTS, "marks-pid-report.html");
    await writeFile(file, html);
    const report = await page.context().newPage();
    await report.setContent(html);
    await report.evaluate(() => document.querySelector("section.marks").scrollIntoView());
    await report.screenshot({ path: join(SHOTS, "marks-pid-report.png") });
    await report.setViewportSize(PHONE_TALL);
    await report.evaluate(() => document.querySelector("section.marks").scrollIntoView());
    await report.screenshot({ path: join(SHOTS, "marks-pid-report-phone.png") });
    await report.close();
    // The remove button takes the first mark away, from the plots too.
    await page.locator(`${ART} [data-unmark="40"]`).click();
    await settle(page);
    assert.deepEqual(await listed(page), [String(end)]);
  }));

test("marks: on a phone the time bar lists the mark and the plots draw it", () =>
  withPage(lab, { clock: true, viewport: PHONE_TALL, hasTouch: true, isMobile: true }, async (page) => {
    await pidPeakMarked(page);
    assert.deepEqual(await listed(page), ["40"]);
    await screenshot(page, "marks-pid-phone");
    await page.locator(`${ART} figure.plot`).first().scrollIntoViewIfNeeded();
    await screenshot(page, "marks-pid-phone-plot");
  }));

test("marks: a link's marks come back; a malformed marks= says so and the lab runs on, with no console error", () =>
  withPage(lab, { clock: true }, async (page) => {
    await open(lab, page, "#/pid/simulation?marks=0.50,1.00&run=0&at=1.50");
    assert.deepEqual(await listed(page), ["30", "60"]);
    await open(lab, page, "#/pid/simulation?marks=1.2,soon");
    const notice = page.locator("#notice");
    // The notice says what is wrong (it goes by itself after a while).
    await runUntil(page, () => /Marks:/.test(document.querySelector("#notice").textContent), undefined, {
      what: "the notice",
    });
    assert.match(await notice.textContent(), /Marks: “soon” is not a time in seconds from 0 to 600/);
    assert.deepEqual(await listed(page), []);
    await runUntil(page, () => Number(document.querySelector("canvas.sim-canvas").dataset.steps) > 30, undefined, {
      what: "the run going on",
    });
  }));
