// Issue 53 §7, small things a student sees, on a laptop (1280×800) and a
// phone (390×844): words that stay whole in plot titles, table headings and
// switches; tables no wider than their box; two labelled ticks on every
// plot axis, each label whole on its canvas; a "Hide basin map" button only
// with a basin map; a link's time that is no step of the run says where it
// opened. Every moment is reached by stepping the page's stopped clock.
// (Firefox's hyphenated switch is tested in browsers.test.mjs.)

import { test } from "node:test";
import assert from "node:assert/strict";
import { DESKTOP, open, runFor, runUntil, screenshot, settle, useLab, withPage } from "./helpers.mjs";

const lab = useLab();
const PHONE_TALL = { width: 390, height: 844 };
const SIZES = [
  ["laptop", DESKTOP],
  ["phone", PHONE_TALL],
];
const ART = "article.exp:not([hidden])";

/**
 * The words of the elements `selector` matches that the page lays out
 * across two lines or more ("Step respon|se", "mea-sure-ment"): a word's
 * range whose boxes stand on more than one line. Each as `text: word`.
 */
function splitWords(selector) {
  const split = [];
  for (const el of document.querySelectorAll(selector)) {
    if (!el.getClientRects().length) continue;
    const walker = document.createTreeWalker(el, NodeFilter.SHOW_TEXT);
    for (let node = walker.nextNode(); node; node = walker.nextNode()) {
      for (const m of node.textContent.matchAll(/\S+/g)) {
        const range = document.createRange();
        range.setStart(node, m.index);
        range.setEnd(node, m.index + m[0].length);
        const lines = new Set([...range.getClientRects()].filter((r) => r.width > 0).map((r) => Math.round(r.top)));
        if (lines.size > 1) split.push(`${el.textContent.trim()}: ${m[0]}`);
      }
    }
  }
  return split;
}

/** Each visible table of the Simulation tab wider than its box: `key scrollWidth > clientWidth`. */
function clippedTables(art) {
  return [...document.querySelectorAll(`${art} .live-table`)]
    .filter((t) => t.getClientRects().length && t.scrollWidth > t.clientWidth)
    .map((t) => `${t.dataset.table} ${t.scrollWidth} > ${t.clientWidth}`);
}

/**
 * What is wrong with the axes of each drawn plot (from the canvas'
 * `data-layout`): fewer than two labelled ticks on an axis, or a tick label
 * not wholly on the canvas.
 */
function axisFaults(art) {
  const faults = [];
  for (const figure of document.querySelectorAll(`${art} figure.plot`)) {
    const canvas = figure.querySelector("canvas");
    if (!canvas.dataset.layout || !canvas.getClientRects().length) continue;
    const layout = JSON.parse(canvas.dataset.layout);
    const key = figure.dataset.plot;
    for (const axis of ["xticks", "yticks"]) {
      const labels = layout[axis].map((t) => t[0]);
      if (labels.length < 2) faults.push(`${key} ${axis}: ${JSON.stringify(labels)}`);
      for (const [text, [x, y, w, h]] of layout[axis]) {
        if (x < 0 || y < 0 || x + w > canvas.clientWidth + 0.5 || y + h > canvas.clientHeight + 0.5) {
          faults.push(`${key} ${axis}: “${text}” at ${x},${y} (${w}×${h}) is cut by the ${canvas.clientWidth}×${canvas.clientHeight} canvas`);
        }
      }
    }
  }
  return faults;
}

/** Whether every plot of the tab has been drawn with data (not "No data yet"). */
function plotsDrawn(art) {
  const canvases = [...document.querySelectorAll(`${art} figure.plot canvas`)].filter((c) => c.getClientRects().length);
  return canvases.length > 0 && canvases.every((c) => c.dataset.layout && JSON.parse(c.dataset.layout).xticks.length > 0);
}

/** Waits until the run's status badge says it ended. */
function runEnded(page, what) {
  return runUntil(page, (art) => document.querySelector(`${art} .sim-status`)?.dataset.phase === "ended", ART, {
    what,
    maxMs: 120_000,
  });
}

for (const [name, viewport] of SIZES) {
  test(`pid (${name}): the plot titles keep their words whole once “Fit latest run” shows`, () =>
    withPage(lab, { viewport, clock: true }, async (page) => {
      await open(lab, page, "#/pid/simulation");
      await runFor(page, 1000);
      await page.locator(`${ART} button[data-action=pin]`).click();
      await runFor(page, 500);
      const fit = page.locator(`${ART} figure.plot[data-plot=response] button[data-plot-fit]`);
      assert.ok(await fit.isVisible(), "a pinned run brings “Fit latest run”");
      assert.deepEqual(await page.evaluate(splitWords, `${ART} .plot-title, ${ART} .plot-tools button`), []);
      await page.locator(`${ART} figure.plot[data-plot=response]`).scrollIntoViewIfNeeded();
      await screenshot(page, `small-pid-titles-${name}`);
    }));

  test(`rrtstar Compare (${name}): table headings keep their words whole, the table fits its box, the last x tick is whole`, () =>
    withPage(lab, { viewport, clock: true }, async (page) => {
      await open(lab, page, "#/rrtstar/simulation");
      await page.locator(`${ART} button[data-action=compare]`).click();
      await runEnded(page, "the comparison's end");
      await runUntil(page, plotsDrawn, ART, { what: "the plots" });
      await settle(page);
      const seen = {
        split: await page.evaluate(splitWords, `${ART} .live-table th`),
        clipped: await page.evaluate(clippedTables, ART),
        axes: await page.evaluate(axisFaults, ART),
      };
      assert.deepEqual(seen, { split: [], clipped: [], axes: [] });
      // "4000" under the right edge of the plot (it showed as "400").
      const xticks = await page.$eval(`${ART} figure.plot canvas`, (c) => JSON.parse(c.dataset.layout).xticks.map((t) => t[0]));
      assert.ok(xticks.includes("4000"), JSON.stringify(xticks));
      await page.locator(`${ART} .tables`).scrollIntoViewIfNeeded();
      await screenshot(page, `small-rrtstar-compare-${name}`);
    }));

  test(`astar 512 × 512 (${name}): the Open list fits its box, f column included`, () =>
    withPage(lab, { viewport, clock: true }, async (page) => {
      await open(lab, page, "#/astar/simulation?size=5&speed=50");
      await page.locator(`${ART} button[data-action=maze]`).click();
      await page.locator(`${ART} button[data-action=plan]`).click();
      // Five-digit costs: the widest the open list gets on this maze.
      await runUntil(
        page,
        (art) => [...document.querySelectorAll(`${art} .live-table[data-table=open] td`)].some((td) => Number.parseFloat(td.textContent) >= 10000),
        ART,
        { what: "costs of five digits", maxMs: 120_000 },
      );
      await settle(page);
      assert.deepEqual(await page.evaluate(clippedTables, ART), []);
      assert.deepEqual(await page.evaluate(splitWords, `${ART} .live-table th`), []);
      const f = await page.$eval(`${ART} .live-table[data-table=open] tbody tr:first-child td:last-child`, (td) => {
        const box = td.closest(".live-table").getBoundingClientRect();
        const r = td.getBoundingClientRect();
        return { right: r.right, box: box.right, text: td.textContent };
      });
      assert.ok(f.right <= f.box + 0.5, `f “${f.text}” ends at ${f.right}, the box at ${f.box}`);
      // The word stays in the page's text (the row is the one expanding).
      assert.equal(await page.locator(`${ART} .live-table[data-table=open] tr.current td`).first().innerText(), "expanding");
      await page.locator(`${ART} .tables`).scrollIntoViewIfNeeded();
      await screenshot(page, `small-astar-open-${name}`);
    }));

  test(`ekf and cartpole (${name}): every plot axis has two labelled ticks, each whole on its canvas`, () =>
    withPage(lab, { viewport, clock: true }, async (page) => {
      await open(lab, page, "#/ekf/simulation");
      await page.locator(`${ART} button[data-action=check]`).click();
      await runFor(page, 6000);
      await runUntil(page, plotsDrawn, ART, { what: "every ekf plot drawn", maxMs: 120_000 });
      await settle(page);
      const ekf = await page.evaluate(axisFaults, ART);
      await page.locator(`${ART} figure.plot`).last().scrollIntoViewIfNeeded();
      await screenshot(page, `small-ekf-axes-${name}`);
      await open(lab, page, "#/cartpole/simulation");
      await runFor(page, 6000);
      await runUntil(page, plotsDrawn, ART, { what: "every cartpole plot drawn" });
      await settle(page);
      const cartpole = await page.evaluate(axisFaults, ART);
      await page.locator(`${ART} figure.plot[data-plot=force]`).scrollIntoViewIfNeeded();
      await screenshot(page, `small-cartpole-axes-${name}`);
      assert.deepEqual({ ekf, cartpole }, { ekf: [], cartpole: [] });
    }));

}

test("pid: the switches keep their words whole and clear of their names at every width", () =>
  withPage(lab, { viewport: DESKTOP, clock: true }, async (page) => {
    for (const width of [1280, 1024, 800, 600, 390, 360, 320]) {
      await page.setViewportSize({ width, height: 844 });
      await open(lab, page, "#/pid/simulation");
      assert.deepEqual(await page.evaluate(splitWords, `${ART} .ctl-toggle legend, ${ART} .ctl-toggle .seg span`), [], `${width} px`);
      const overlap = await page.$$eval(`${ART} .ctl-toggle`, (sets) =>
        sets.flatMap((set) => {
          const legend = set.querySelector("legend").getBoundingClientRect();
          const seg = set.querySelector(".seg").getBoundingClientRect();
          const room = (set.closest(".sim-controls") ?? document.body).getBoundingClientRect();
          const apart = legend.right <= seg.left || legend.bottom <= seg.top;
          const inside = seg.left >= room.left - 0.5 && seg.right <= room.right + 0.5;
          return apart && inside ? [] : [`${set.dataset.ctl}: legend to ${legend.right},${legend.bottom}; switch ${seg.left}–${seg.right} at ${seg.top} in ${room.left}–${room.right}`];
        }),
      );
      assert.deepEqual(overlap, [], `${width} px: each switch stands clear of its name, inside the column`);
      if (width === 1280 || width === 390) {
        await page.locator(`${ART} .ctl-toggle`).first().scrollIntoViewIfNeeded();
        await screenshot(page, `small-pid-switches-${width}`);
      }
    }
  }));

test("potential: “Hide basin map” is there only with a basin map, and hands the focus back when it goes", () =>
  withPage(lab, { viewport: DESKTOP, clock: true }, async (page) => {
    // The field's two obstacles and a goal (the basin map needs one).
    await open(lab, page, "#/potential/simulation?gx=7.4&gy=3");
    const hide = page.locator(`${ART} button[data-action=clear]`);
    const map = page.locator(`${ART} button[data-action=basin]`);
    assert.equal(await hide.isVisible(), false, "no basin map, no Hide basin map");
    await map.click();
    await settle(page);
    assert.equal(await hide.isVisible(), true);
    await hide.focus();
    await page.keyboard.press("Enter");
    await settle(page);
    assert.equal(await hide.isVisible(), false);
    assert.equal(await page.evaluate(() => document.activeElement?.dataset.action), "basin", "the focus is on Basin map");
    // A link with the map shows the button.
    await page.goto("about:blank");
    await open(lab, page, "#/potential/simulation?gx=7.4&gy=3&map=1");
    await settle(page);
    assert.equal(await hide.isVisible(), true);
  }));

test("pid: a link's time between two steps says where it opened; a step's time opens silently", () =>
  withPage(lab, { viewport: DESKTOP, clock: true }, async (page) => {
    const bar = () => page.locator(`${ART} .tb-time`).innerText();
    await open(lab, page, "#/pid/simulation?kp=25&ki=0&kd=2&c=1&run=0&at=0.65");
    await settle(page);
    assert.equal(await bar(), "t = 0.65 s");
    assert.doesNotMatch(await page.locator("body").innerText(), /is no step of the run/);
    // A fresh load (a link routed on the open page shows its notice, and
    // routing it a second time clears it).
    await page.goto("about:blank");
    await open(lab, page, "#/pid/simulation?kp=25&ki=0&kd=2&c=1&run=0&at=0.66");
    await settle(page);
    assert.equal(await bar(), "t = 0.67 s");
    assert.match(
      await page.locator("body").innerText(),
      /The link's t = 0\.66 s is no step of the run \(one every 1\/60 s, up to its end\): it opened at t = 0\.67 s, the nearest\./,
    );
  }));

test("pid: after Clear pins the response plot's text summary names no pinned run", () =>
  withPage(lab, { viewport: DESKTOP, clock: true }, async (page) => {
    await open(lab, page, "#/pid/simulation");
    await runFor(page, 500);
    await page.locator(`${ART} button[data-action=pin]`).click();
    await runFor(page, 500);
    const summary = () => page.$eval(`${ART} figure.plot[data-plot=response] .plot-summary`, (p) => p.textContent);
    await runUntil(page, (art) => /A: Kp/.test(document.querySelector(`${art} figure.plot[data-plot=response] .plot-summary`).textContent), ART, {
      what: "the pin in the summary",
    });
    await page.locator(`${ART} button[data-action=clear_pins]`).click();
    await runFor(page, 500);
    const text = await summary();
    assert.doesNotMatch(text, /pinned run|A: Kp|kept run/, text);
    assert.match(text, /position x: \d+ samples/, text);
  }));
