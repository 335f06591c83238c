// Layout: phone width without sideways scrolling, dark mode.

import { test } from "node:test";
import assert from "node:assert/strict";
import { PHONE, TABS, experimentIds, open, screenshot, settle, useLab, withPage } from "./helpers.mjs";

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
