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
        await page.click(`article.exp:not([hidden]) [role=tab][data-tab="${slug}"]`);
        const panel = page.locator(`article.exp:not([hidden]) [role=tabpanel][data-panel="${slug}"]`);
        assert.ok(await panel.isVisible(), `${slug} panel visible`);
        const text = (await panel.innerText()).trim();
        assert.ok(text.length > 40, `${slug} panel shows its text (${text.length} chars)`);
      }
      await page.click('article.exp:not([hidden]) [role=tab][data-tab="simulation"]');
      const error = page.locator('article.exp:not([hidden]) [data-panel="simulation"] .sim-error');
      await error.waitFor({ state: "visible" });
      assert.ok((await error.innerText()).trim().length > 0, "the error says what is wrong");
    },
  ));

test("with the wasm request blocked, the reading tabs show and work, and the page says the engine could not load", async () => {
  // Not withPage: the failed request is the point of this test.
  const context = await lab.browser.newContext({ serviceWorkers: "block" });
  try {
    const page = await context.newPage();
    await page.route(/\.wasm(\?|$)/, (route) => route.abort());
    await page.goto(`${lab.server.base}index.html#/fk/theory`);
    const article = page.locator("article.exp:not([hidden])");
    assert.equal(await article.getAttribute("data-experiment"), "fk");
    const theory = article.locator("[data-panel=theory]");
    await theory.waitFor({ state: "visible" });
    assert.ok((await theory.locator("math").count()) > 0, "the theory's formulas are there");
    assert.equal(await article.locator("[role=tab][aria-selected=true]").getAttribute("data-tab"), "theory");
    const fatal = page.locator("#fatal");
    await fatal.waitFor({ state: "visible" });
    assert.match(await fatal.innerText(), /could not|failed/i);
    // Tabs are links: they still switch without the wasm, and Back returns.
    // Each click is a navigation: wait until it is in the history before the
    // next step, or Back may return past it on a busy machine.
    await article.locator("[role=tab][data-tab=references]").click();
    await page.waitForURL(/#\/fk\/references$/);
    await article.locator("[data-panel=references] ol.refs li").first().waitFor({ state: "visible" });
    assert.ok(await theory.isHidden());
    await article.locator("[role=tab][data-tab=simulation]").click();
    await page.waitForURL(/#\/fk\/simulation$/);
    const simulation = article.locator("[data-panel=simulation]");
    await simulation.waitFor({ state: "visible" });
    assert.match(await simulation.innerText(), /could not start/);
    await page.goBack();
    await page.waitForURL(/#\/fk\/references$/);
    await article.locator("[data-panel=references]").waitFor({ state: "visible" });
    assert.ok(await simulation.isHidden());
    // The navigation works without the wasm too: two clicks to another experiment.
    await page.locator("#lab-nav summary").click();
    await page.locator("#lab-nav a[data-experiment=dls]").click();
    await page.locator("article.exp[data-experiment=dls]:not([hidden]) [data-panel=aim]").waitFor({ state: "visible" });
  } finally {
    await context.close();
  }
});

test("a tab chosen while the engine is still downloading is shown at once, also by Back", async () => {
  // Not withPage: the wasm request is held, then refused, on purpose.
  const context = await lab.browser.newContext({ serviceWorkers: "block" });
  try {
    const page = await context.newPage();
    const held = [];
    await page.route(/\.wasm(\?|$)/, (route) => {
      held.push(route);
    });
    await page.goto(`${lab.server.base}index.html#/fk/simulation`);
    const article = page.locator("article.exp:not([hidden])");
    await article.locator("[data-panel=simulation]").waitFor({ state: "visible" });
    await page.waitForFunction(() => performance.getEntriesByType("resource").length > 0);
    await article.locator("[role=tab][data-tab=references]").click();
    await page.waitForURL(/#\/fk\/references$/);
    await article.locator("[data-panel=references] ol.refs li").first().waitFor({ state: "visible" });
    await page.goBack();
    await page.waitForURL(/#\/fk\/simulation$/);
    await article.locator("[data-panel=simulation]").waitFor({ state: "visible" });
    assert.ok(held.length > 0, "the wasm was asked for and is still held");
    for (const route of held) await route.abort();
    await page.locator("#fatal").waitFor({ state: "visible" });
    // Forward again, after the failure: the reading tab still shows.
    await page.goForward();
    await page.waitForURL(/#\/fk\/references$/);
    await article.locator("[data-panel=references]").waitFor({ state: "visible" });
  } finally {
    await context.close();
  }
});

test("on a high-DPI screen the canvas backing store matches the device pixels", async () => {
  const context = await lab.browser.newContext({
    serviceWorkers: "block",
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
