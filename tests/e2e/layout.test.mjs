// Layout: phone width without sideways scrolling, dark mode.

import { test } from "node:test";
import assert from "node:assert/strict";
import { PHONE, experimentIds, open, screenshot, settle, useLab, withPage } from "./helpers.mjs";

const lab = useLab();

const scrollWidth = (page) => page.evaluate(() => document.documentElement.scrollWidth);

test("at phone width (360×740) nothing scrolls sideways, on home and on every simulation", async (t) => {
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
        const width = await scrollWidth(page);
        await screenshot(page, `${id}-simulation-phone`);
        assert.ok(width <= PHONE.width, `${id} simulation is ${width} px wide`);
      }),
    );
  }
});

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
