// Graceful degradation: no 2D canvas context (old or locked-down browsers,
// some privacy modes). Reading material must still work; the simulation
// says clearly that it cannot draw.

import { test } from "node:test";
import assert from "node:assert/strict";
import { existsSync, readFileSync, statSync } from "node:fs";
import { createServer } from "node:http";
import { extname, join, resolve, sep } from "node:path";
import { BASE_PATH, DIST, open, screenshot, useLab, withPage } from "./helpers.mjs";

const lab = useLab();

/**
 * A host with a minimal type map, as lighttpd's tutorial has it: dist/ under
 * BASE_PATH, every file as it is, no header but the type, and `.js` as
 * application/octet-stream. Returns its base URL and a stop function.
 */
async function serveJsAsOctetStream() {
  const types = {
    ".html": "text/html",
    ".css": "text/css",
    ".svg": "image/svg+xml",
    ".wasm": "application/wasm",
    ".json": "application/json",
    ".png": "image/png",
  };
  const server = createServer((req, res) => {
    const path = decodeURIComponent(new URL(req.url, "http://host").pathname);
    const file = resolve(DIST, path.slice(BASE_PATH.length) || "index.html");
    if (!path.startsWith(BASE_PATH) || !file.startsWith(DIST + sep) || !existsSync(file) || !statSync(file).isFile()) {
      res.writeHead(404).end();
      return;
    }
    res.writeHead(200, { "Content-Type": types[extname(file)] ?? "application/octet-stream" });
    res.end(readFileSync(file));
  });
  await new Promise((ok) => server.listen(0, "127.0.0.1", ok));
  return {
    base: `http://127.0.0.1:${server.address().port}${BASE_PATH}`,
    stop: () => new Promise((ok) => server.close(ok)),
  };
}

test("scripts served with a wrong type (.js as application/octet-stream): the page says the lab could not start and names the type, not “Loading…” forever; the policy holds", async () => {
  // Not withPage: the refused module script is the point of this test.
  const host = await serveJsAsOctetStream();
  const context = await lab.browser.newContext({ serviceWorkers: "block" });
  try {
    await context.addInitScript(() => {
      window.__cspViolations = [];
      document.addEventListener("securitypolicyviolation", (e) => window.__cspViolations.push(e.effectiveDirective));
    });
    const page = await context.newPage();
    const uncaught = [];
    page.on("pageerror", (e) => uncaught.push(e.message));
    for (const [address, script] of [["index.html#/fk/aim", "main.js"], ["check.html", "check.js"]]) {
      await page.goto(host.base + address);
      const fatal = page.locator("#fatal");
      await fatal.waitFor({ state: "visible" });
      await page.waitForFunction(() => /octet-stream/.test(document.querySelector("#fatal").textContent));
      const text = await fatal.innerText();
      assert.match(text, new RegExp(`The lab could not start: the server sent ${script.replace(".", "\\.")} as “application/octet-stream”`));
      assert.match(text, /text\/javascript/);
      assert.match(text, /docs\/hosting\.md, “File types”/);
      assert.equal(await page.locator(".loading").count(), 0, `${address}: no “Loading…” left`);
      assert.equal(await page.evaluate(() => window.labStarted), undefined, `${address}: the module did not run`);
      assert.deepEqual(await page.evaluate(() => window.__cspViolations), [], `${address}: no policy violation`);
      await page.setViewportSize({ width: 1280, height: 800 });
      await screenshot(page, `wrong-type-${script}`);
      await page.setViewportSize({ width: 390, height: 844 });
      await screenshot(page, `wrong-type-${script}-phone`);
    }
    assert.deepEqual(uncaught, []);
  } finally {
    await context.close();
    await host.stop();
  }
});

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
