// Layout: phone width without sideways scrolling, dark mode.

import { test } from "node:test";
import assert from "node:assert/strict";
import { PHONE, TABS, builtExperimentIds, experimentIds, open, runUntil, screenshot, settle, useLab, withPage } from "./helpers.mjs";

const lab = useLab();

const scrollWidth = (page) => page.evaluate(() => document.documentElement.scrollWidth);

test("at phone width (360×740) nothing scrolls sideways, on home and on every tab of every experiment", async (t) => {
  const ids = await experimentIds(lab);
  await withPage(lab, { viewport: PHONE, hasTouch: true }, async (page) => {
    await open(lab, page, "#/");
    await settle(page);
    assert.ok((await scrollWidth(page)) <= PHONE.width, "home fits 360 px");
  });
  for (const id of ids) {
    await t.test(`experiment ${id}`, () =>
      withPage(lab, { viewport: PHONE, hasTouch: true }, async (page) => {
        await open(lab, page, `#/${id}/simulation`);
        await settle(page);
        await screenshot(page, `${id}-simulation-phone`);
        for (const tab of TABS) {
          await page.locator(`article.exp:not([hidden]) [role=tab][data-tab=${tab}]`).click();
          await settle(page);
          const width = await scrollWidth(page);
          assert.ok(width <= PHONE.width, `${id} ${tab} is ${width} px wide`);
        }
      }),
    );
  }
});

test("the canvas stays put while the status badge changes during a drag", () =>
  withPage(lab, { viewport: PHONE, hasTouch: true }, async (page) => {
    await open(lab, page, "#/fk/simulation");
    const canvas = page.locator("canvas.sim-canvas");
    const before = await canvas.boundingBox();
    // Drag the tip far outside reach: the badge switches to "out of reach".
    const box = before;
    await page.mouse.move(box.x + box.width * 0.6, box.y + box.height * 0.35);
    await page.mouse.down();
    await page.mouse.move(box.x + box.width * 0.99, box.y + box.height * 0.02, { steps: 6 });
    await settle(page);
    assert.match(await page.locator(".sim-status").textContent(), /out of reach/);
    const during = await canvas.boundingBox();
    await page.mouse.up();
    assert.deepEqual(during, before, "the canvas did not move");
  }));

/** Relative luminance (WCAG) of a CSS `rgb(...)`/`rgba(...)` colour. */
function luminance(css) {
  const [r, g, b] = css.match(/[\d.]+/g).slice(0, 3).map(Number);
  const lin = (c) => ((c /= 255) <= 0.03928 ? c / 12.92 : ((c + 0.055) / 1.055) ** 2.4);
  return 0.2126 * lin(r) + 0.7152 * lin(g) + 0.0722 * lin(b);
}

const bodyBackground = (page) =>
  page.evaluate(() => getComputedStyle(document.body).backgroundColor);

test("dark colour scheme gives a dark page, light gives a light one", async () => {
  await withPage(lab, { colorScheme: "dark" }, async (page) => {
    await open(lab, page, "#/fk/simulation");
    const bg = await bodyBackground(page);
    assert.ok(luminance(bg) < 0.1, `dark body background ${bg}`);
    const text = await page.evaluate(() => getComputedStyle(document.body).color);
    assert.ok(luminance(text) > 0.5, `light text ${text} on the dark background`);
  });
  await withPage(lab, { colorScheme: "light" }, async (page) => {
    await open(lab, page, "#/fk/simulation");
    const bg = await bodyBackground(page);
    assert.ok(luminance(bg) > 0.7, `light body background ${bg}`);
  });
});

// Issue 13 §3: the scene, its time bar, its primary actions and its main plot in one view.

const ART = "article.exp:not([hidden])";

/** Client rectangles of the Simulation tab's key parts. */
const simBoxes = (page) =>
  page.evaluate((art) => {
    const box = (sel) => document.querySelector(`${art} ${sel}`)?.getBoundingClientRect().toJSON() ?? null;
    return {
      canvas: box("canvas.sim-canvas"),
      status: box(".sim-status"),
      timebar: box(".timebar"),
      actions: box(".sim-actions button, .sim-tools button"),
      plot: box(".sim-mainplot canvas.plot-canvas"),
      side: box(".sim-side"),
    };
  }, ART);

const inView = (r, vp) => r.top >= 0 && r.left >= 0 && r.bottom <= vp.height + 0.5 && r.right <= vp.width + 0.5;
const overlap = (a, b) => a.left < b.right && b.left < a.right && a.top < b.bottom && b.top < a.bottom;

for (const viewport of [{ width: 1280, height: 800 }, { width: 1440, height: 900 }]) {
  test(`at ${viewport.width}×${viewport.height} every experiment shows its canvas, time bar, primary actions and main plot together without scrolling`, async (t) => {
    const ids = await experimentIds(lab);
    assert.deepEqual([...ids].sort(), builtExperimentIds().sort(), `every built experiment (${ids.join(", ")})`);
    await withPage(lab, { viewport }, async (page) => {
      for (const id of ids) {
        await t.test(id, async () => {
          await open(lab, page, `#/${id}/simulation`);
          await settle(page);
          const b = await simBoxes(page);
          const hasPlots = (await page.locator(`${ART} figure.plot`).count()) > 0;
          const parts = ["canvas", "status", "actions", ...(hasPlots ? ["plot"] : [])];
          for (const part of parts) {
            assert.ok(b[part], `${id}: has its ${part}`);
            assert.ok(inView(b[part], viewport), `${id}: ${part} in view (${JSON.stringify(b[part])})`);
          }
          if (b.timebar) assert.ok(inView(b.timebar, viewport), `${id}: time bar in view`);
          if (hasPlots) assert.ok(b.plot.left >= b.canvas.right, `${id}: the main plot is beside the canvas`);
          assert.ok(b.canvas.height >= 300, `${id}: a large canvas (${b.canvas.height} px)`);
          if (viewport.width === 1280) await screenshot(page, `${id}-simulation-1280`);
        });
      }
    });
  });
}

test("on a phone (390×844) the canvas, its status strip, time bar, the actions that start a run and the main plot come in this order", async (t) => {
  const ids = await experimentIds(lab);
  await withPage(lab, { viewport: { width: 390, height: 844 }, hasTouch: true }, async (page) => {
    for (const id of ids) {
      await t.test(id, async () => {
        await open(lab, page, `#/${id}/simulation`);
        await settle(page);
        const b = await simBoxes(page);
        if (!b.plot) return; // an experiment without plots (fk, ik)
        const under = b.timebar ?? b.status;
        assert.ok(b.plot.top >= under.bottom, `${id}: plot below the time bar`);
        // Nothing but the actions that start a run, and the plot's own
        // caption and legend, between them (issue 23 §1: the action sits
        // right under the canvas).
        const between = await page.evaluate((art) => {
          const plot = document.querySelector(`${art} .sim-mainplot`).getBoundingClientRect();
          const bar = (document.querySelector(`${art} .timebar`) ?? document.querySelector(`${art} .sim-statusbar`)).getBoundingClientRect();
          const others = [".sim-actions", ".sim-tools", ".readouts", ".sim-controls", ".tables:not(:empty)"]
            .map((s) => document.querySelector(`${art} ${s}`))
            .filter((el) => el && el.getBoundingClientRect().height > 0)
            .filter((el) => {
              const r = el.getBoundingClientRect();
              return r.top >= bar.bottom - 1 && r.bottom <= plot.top + 1;
            });
          return others.map((el) => el.className);
        }, ART);
        const actions = (await page.locator(`${ART} .sim-actions button`).count()) > 0;
        assert.deepEqual(between, actions ? ["sim-actions"] : [], `${id}: only the actions between the time bar and the main plot`);
        if (["pid", "diffdrive", "astar", "ekf"].includes(id)) await screenshot(page, `${id}-simulation-390`);
      });
    }
  });
});

test("the status badge sits outside the canvas (it never covers a handle), at 1280 px and on a phone", async () => {
  const ids = await experimentIds(lab);
  for (const viewport of [{ width: 1280, height: 800 }, { width: 390, height: 844 }]) {
    await withPage(lab, { viewport }, async (page) => {
      for (const id of ids) {
        await open(lab, page, `#/${id}/simulation`);
        await settle(page);
        const b = await simBoxes(page);
        assert.ok(!overlap(b.status, b.canvas), `${id} at ${viewport.width}: badge ${JSON.stringify(b.status)} off the canvas ${JSON.stringify(b.canvas)}`);
        const notice = page.locator(`${ART} .sim-notice`);
        assert.equal(await notice.getAttribute("aria-live"), "polite", `${id}: notices are announced politely`);
      }
    });
  }
});

test("controls: number boxes line up in one column, grouped controls sit under collapsed headings", () =>
  withPage(lab, { viewport: { width: 1280, height: 800 } }, async (page) => {
    for (const id of ["pid", "diffdrive", "ekf"]) {
      await open(lab, page, `#/${id}/simulation`);
      const groups = await page.$$eval(`${ART} details.ctl-group`, (ds) => ds.map((d) => d.open));
      assert.ok(groups.every((open) => !open), `${id}: groups start collapsed`);
      // Open every group: its rows keep the same columns.
      await page.$$eval(`${ART} details.ctl-group`, (ds) => ds.forEach((d) => { d.open = true; }));
      const lefts = await page.$$eval(`${ART} .sim-controls .ctl-num input[type=text]`, (els) =>
        els.filter((e) => e.getBoundingClientRect().width > 0).map((e) => Math.round(e.getBoundingClientRect().left)),
      );
      assert.ok(lefts.length > 0, `${id}: number boxes`);
      assert.equal(new Set(lefts).size, 1, `${id}: every number box starts at the same x (${[...new Set(lefts)]})`);
    }
  }));

// Issue 53 §7: pid's Ki unit, N/(m·s), ran past its card.
test("controls: every unit stands inside its control's row, at 1280 px and on a phone", async () => {
  for (const viewport of [{ width: 1280, height: 800 }, { width: 390, height: 844 }]) {
    await withPage(lab, { viewport }, async (page) => {
      for (const id of builtExperimentIds()) {
        await open(lab, page, `#/${id}/simulation`);
        await page.$$eval(`${ART} details.ctl-group`, (ds) => ds.forEach((d) => { d.open = true; }));
        const past = await page.$$eval(`${ART} .sim-controls .ctl`, (rows) =>
          rows.flatMap((row) => {
            const unit = row.querySelector(".unit");
            if (!unit || !unit.textContent.trim() || unit.getBoundingClientRect().width === 0) return [];
            // The text's own extent: the unit's box may be narrower than its text.
            const text = document.createRange();
            text.selectNodeContents(unit);
            const r = text.getBoundingClientRect();
            const card = row.getBoundingClientRect();
            return r.right > card.right + 0.5 ? [`${row.dataset.ctl} ${unit.textContent}: ${Math.round(r.right - card.right)} px past`] : [];
          }),
        );
        assert.deepEqual(past, [], `${id} at ${viewport.width} px`);
      }
    });
  }
});

test("astar on a phone: open-list numbers never wrap mid-number", () =>
  withPage(lab, { viewport: { width: 390, height: 844 }, hasTouch: true, clock: true }, async (page) => {
    await open(lab, page, "#/astar/simulation");
    await page.click(`${ART} button[data-action=plan]`);
    await runUntil(page, (art) => document.querySelectorAll(`${art} .live-table td:not(:first-child)`).length > 8, ART);
    await settle(page);
    // One synchronous look (the table is rebuilt while the search runs).
    const { cells, wrapped, style } = await page.evaluate((art) => {
      // The numbers: every column but the first, which names the row (a
      // rank, or "expanding", shown as its triangle) and may break between
      // words where a table names planners (issue 53 §7).
      const tds = [...document.querySelectorAll(`${art} .live-table td:not(:first-child)`)].filter((td) => td.textContent.trim().length > 0);
      const lines = (td) => {
        const range = document.createRange();
        range.selectNodeContents(td);
        return new Set([...range.getClientRects()].map((r) => Math.round(r.top))).size;
      };
      const cs = getComputedStyle(tds[0]);
      return {
        cells: tds.length,
        wrapped: tds.filter((td) => lines(td) !== 1).map((td) => td.textContent),
        style: [cs.whiteSpace, cs.fontVariantNumeric],
      };
    }, ART);
    assert.ok(cells > 4, `${cells} cells looked at`);
    assert.deepEqual(wrapped, [], "cells on more than one line");
    assert.deepEqual(style, ["nowrap", "tabular-nums"]);
    await screenshot(page, "astar-table-390");
  }));
