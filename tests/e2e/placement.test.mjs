// Issue 53 §4–§5: what a Procedure step names is where the student looks,
// and the phone's time bar says in words what the Procedures call its
// buttons. Every run is reached by stepping a stopped clock.

import { test } from "node:test";
import assert from "node:assert/strict";
import { DESKTOP, open, readouts, runUntil, screenshot, settle, useLab, withPage } from "./helpers.mjs";

const lab = useLab();
const PHONE_390 = { width: 390, height: 844 };
const ART = "article.exp:not([hidden])";

/** The box of the first match, in viewport px. */
const box = (page, selector) =>
  page.locator(`${ART} ${selector}`).first().evaluate((el) => el.getBoundingClientRect().toJSON());

/**
 * Whether the first match shows at least `share` of its height on the
 * first screen: inside the viewport and inside every scrolling box around
 * it (the laptop's plots column scrolls on its own).
 */
const shownShare = (page, selector) =>
  page.locator(`${ART} ${selector}`).first().evaluate((el) => {
    const r = el.getBoundingClientRect();
    let top = Math.max(r.top, 0);
    let bottom = Math.min(r.bottom, window.innerHeight);
    for (let p = el.parentElement; p; p = p.parentElement) {
      const o = getComputedStyle(p).overflowY;
      if (o === "auto" || o === "scroll" || o === "hidden") {
        const pr = p.getBoundingClientRect();
        top = Math.max(top, pr.top);
        bottom = Math.min(bottom, pr.bottom);
      }
    }
    return Math.max(0, bottom - top) / r.height;
  });

/**
 * A thing a step names is where the student looks: on a laptop, its title
 * and most of it on the first screen (inside the plots column where that
 * scrolls); on a phone, above the readouts and within one screen's swipe
 * under the time bar (`bar`, its box).
 */
async function near(page, bar, selector, what) {
  const vh = page.viewportSize().height;
  if (vh < 900 && page.viewportSize().width < 500) {
    const r = await box(page, selector);
    const readoutsTop = (await box(page, "dl.readouts")).top;
    assert.ok(r.top - bar.bottom < vh, `${what}: ${Math.round(r.top - bar.bottom)} px under the time bar`);
    assert.ok(r.top < readoutsTop, `${what}: above the readouts`);
  } else {
    const share = await shownShare(page, selector);
    assert.ok(share > 0.6, `${what}: ${Math.round(share * 100)} % of it on the first screen`);
  }
}

const waitStatus = (page, re) =>
  runUntil(page, (s) => new RegExp(s).test(document.querySelector("article.exp:not([hidden]) .sim-status")?.textContent ?? ""), re.source, {
    what: `status ${re}`,
  });

test("§4 at 390×844 the time bar's buttons are words of 44 × 44 px or more, and Pause becoming Play moves none of them", () =>
  withPage(lab, { viewport: PHONE_390, hasTouch: true, clock: true }, async (page) => {
    await open(lab, page, "#/pid/simulation");
    await settle(page);
    const words = { step: "Step", back: "Back", end: "Run to end", mark: "Mark", reset: "Reset" };
    const boxes = () =>
      page.locator(`${ART} .timebar > button`).evaluateAll((bs) =>
        bs.map((b) => {
          const r = b.getBoundingClientRect();
          return { time: b.dataset.time, left: r.left, top: r.top, width: r.width, height: r.height };
        }),
      );
    for (const [time, word] of Object.entries(words)) {
      const button = page.locator(`${ART} .timebar button[data-time=${time}]`);
      // The word is shown: its text box is laid out, not clipped to a pixel.
      const text = await button.locator(".tb-text").evaluate((el) => {
        const r = el.getBoundingClientRect();
        return { text: el.textContent.trim(), width: r.width, height: r.height };
      });
      assert.equal(text.text, word);
      assert.ok(text.width > 20 && text.height > 10, `${time}: the word "${word}" shows (${text.width} × ${text.height} px)`);
      // No icon beside it (Mark's bookmark read as a drop-down's "▼").
      assert.equal(await button.locator("svg").evaluateAll((s) => s.filter((e) => e.getBoundingClientRect().width > 0).length), 0, `${time}: words, no icon`);
    }
    const before = await boxes();
    assert.equal(before.length, 6, "Play, Step, Back, Run to end, Mark, Reset");
    for (const b of before) assert.ok(b.width >= 44 && b.height >= 44, `${b.time}: ${b.width} × ${b.height} px`);
    const play = page.locator(`${ART} button[data-time=play]`);
    const label = await play.innerText();
    await play.click();
    await settle(page);
    assert.notEqual(await play.innerText(), label, "the play button changed its word");
    assert.deepEqual(await boxes(), before, "no button moved or changed size");
    await screenshot(page, "placement-timebar-390");
  }));

for (const viewport of [DESKTOP, PHONE_390]) {
  const w = viewport.width;
  const phone = w < 500;

  test(`§5 at ${w}px the plots a Procedure names (cartpole's Energy change, ekf's NEES and Average NEES) are on the first screen or close under the time bar`, () =>
    withPage(lab, { viewport, hasTouch: phone, clock: true }, async (page) => {
      for (const [id, keys] of [["cartpole", ["energy"]], ["ekf", ["nees", "anees"]]]) {
        await open(lab, page, `#/${id}/simulation`);
        await settle(page);
        const bar = await box(page, ".timebar");
        await screenshot(page, `placement-${id}-${w}`);
        for (const key of keys) {
          const plot = `figure.plot[data-plot=${key}]`;
          await near(page, bar, plot, `${id} ${key}`);
        }
      }
    }));

  test(`§5 at ${w}px astar's Open list and Compare table are where the student looks, and after Compare the Search progress plot has data`, () =>
    withPage(lab, { viewport, hasTouch: phone, clock: true }, async (page) => {
      await open(lab, page, "#/astar/simulation");
      await settle(page);
      const bar = await box(page, ".timebar");
      await page.click(`${ART} button[data-action=plan]`);
      await runUntil(page, () => document.querySelector("article.exp:not([hidden]) [data-table=open] tbody tr"), undefined, { what: "the open list" });
      await page.click(`${ART} button[data-time=play]`);
      await near(page, bar, "[data-table=open]", "the Open list");
      await page.click(`${ART} button[data-time=play]`);
      await waitStatus(page, /^arrived/);
      await page.click(`${ART} button[data-action=compare]`);
      await waitStatus(page, /compared 4 planners/);
      await settle(page);
      await screenshot(page, `placement-astar-compare-${w}`);
      assert.equal(await page.locator(`${ART} [data-table=compare] tbody tr`).count(), 4, "four planners in the table");
      await near(page, bar, "[data-table=compare]", "the Compare table");
      const summary = await page.locator(`${ART} figure.plot[data-plot=expanded] .plot-summary`).textContent();
      assert.doesNotMatch(summary, /no data yet/, summary);
      assert.match(summary, /expanded: \d+ samples/, summary);
    }));

  test(`§5 at ${w}px ekf's consistency verdict and its band read in full in a readout`, () =>
    withPage(lab, { viewport, hasTouch: phone, clock: true }, async (page) => {
      await open(lab, page, "#/ekf/simulation?runs=10");
      await settle(page);
      assert.equal((await readouts(page)).verdict, "--", "no check yet");
      await page.click(`${ART} button[data-action=check]`);
      await waitStatus(page, /over 10 runs$/);
      await settle(page);
      const status = (await page.locator(`${ART} .sim-status`).textContent()).trim();
      const verdict = page.locator(`${ART} [data-readout=verdict]`);
      assert.equal((await verdict.textContent()).trim(), status);
      assert.match(status, /inside \[1\.68, 4\.70\] over 10 runs$/);
      await verdict.scrollIntoViewIfNeeded();
      const cut = await verdict.evaluate((el) => el.scrollWidth > el.clientWidth + 1 || el.scrollHeight > el.clientHeight + 1);
      assert.ok(!cut, "the readout shows all of it");
      const r = await verdict.evaluate((el) => el.getBoundingClientRect().toJSON());
      assert.ok(r.left >= 0 && r.right <= w, `inside the screen (${r.left}–${r.right})`);
      await screenshot(page, `placement-ekf-verdict-${w}`);
    }));
}
