// Graceful degradation: no 2D canvas context (old or locked-down browsers,
// some privacy modes). Reading material must still work; the simulation
// says clearly that it cannot draw.

import { test } from "node:test";
import assert from "node:assert/strict";
import { open, useLab, withPage } from "./helpers.mjs";

const lab = useLab();

test("without a 2D canvas context the reading tabs still work and the simulation shows .sim-error", () =>
  withPage(
    lab,
    {
      // Console errors are expected here; uncaught exceptions still fail the test.
      allowConsoleErrors: true,
      initScript: () => {
        HTMLCanvasElement.prototype.getContext = function () {
          return null;
        };
      },
    },
    async (page) => {
      await open(lab, page, "#/fk/aim");
      for (const slug of ["aim", "theory"]) {
        await page.click(`[role=tab][data-tab="${slug}"]`);
        const panel = page.locator(`[role=tabpanel][data-panel="${slug}"]`);
        assert.ok(await panel.isVisible(), `${slug} panel visible`);
        const text = (await panel.innerText()).trim();
        assert.ok(text.length > 40, `${slug} panel shows its text (${text.length} chars)`);
      }
      await page.click('[role=tab][data-tab="simulation"]');
      const error = page.locator('[data-panel="simulation"] .sim-error');
      await error.waitFor({ state: "visible" });
      assert.ok((await error.innerText()).trim().length > 0, "the error says what is wrong");
    },
  ));

test("when the simulation engine cannot load, the page says so visibly", async () => {
  // Not withPage: the failed request is the point of this test.
  const context = await lab.browser.newContext();
  try {
    const page = await context.newPage();
    await page.route(/labweb_bg\.wasm/, (route) => route.abort());
    await page.goto(`${lab.server.base}index.html#/fk/aim`);
    const fatal = page.locator("#fatal");
    await fatal.waitFor({ state: "visible" });
    assert.match(await fatal.innerText(), /could not|failed/i);
    assert.match(await page.locator("#app").innerText(), /could not start/);
  } finally {
    await context.close();
  }
});

test("on a high-DPI screen the canvas backing store matches the device pixels", async () => {
  const context = await lab.browser.newContext({
    viewport: { width: 800, height: 700 },
    deviceScaleFactor: 2,
  });
  try {
    const page = await context.newPage();
    const errors = [];
    page.on("pageerror", (e) => errors.push(e.message));
    await page.goto(`${lab.server.base}index.html#/fk/simulation`);
    await page.waitForFunction(() => document.body.dataset.ready === "1");
    await page.waitForFunction(() => document.querySelector("canvas.sim-canvas").width > 300);
    const size = await page.evaluate(() => {
      const c = document.querySelector("canvas.sim-canvas");
      return { css: c.getBoundingClientRect().width, backing: c.width, dpr: devicePixelRatio };
    });
    assert.equal(size.dpr, 2);
    assert.ok(Math.abs(size.backing - size.css * 2) <= 1, `backing ${size.backing} for ${size.css} CSS px`);
    // Resizing the window resizes the backing store too.
    await page.setViewportSize({ width: 500, height: 700 });
    await page.waitForFunction(() => {
      const c = document.querySelector("canvas.sim-canvas");
      return Math.abs(c.width - c.getBoundingClientRect().width * 2) <= 1;
    });
    assert.deepEqual(errors, []);
  } finally {
    await context.close();
  }
});
