// Tabs, sub-path hosting, keyboard use: the lab as a reader moves through it.

import { test } from "node:test";
import assert from "node:assert/strict";
import {
  BASE_PATH,
  DESKTOP,
  TABS,
  builtExperimentIds,
  experimentIds,
  open,
  screenshot,
  settle,
  useLab,
  waitReady,
  withPage,
} from "./helpers.mjs";

const lab = useLab();

async function assertOnlyPanelVisible(page, slug) {
  const tab = page.locator(`article.exp:not([hidden]) [role=tab][data-tab="${slug}"]`);
  assert.equal(await tab.getAttribute("aria-selected"), "true", `tab ${slug} is selected`);
  for (const other of TABS) {
    const panel = page.locator(`article.exp:not([hidden]) [role=tabpanel][data-panel="${other}"]`);
    assert.equal(await panel.isVisible(), other === slug, `panel ${other} visible iff ${slug}`);
  }
}

test("every experiment shows each of its six tabs when clicked, without errors", async (t) => {
  for (const id of await experimentIds(lab)) {
    await t.test(`experiment ${id}`, () =>
      withPage(lab, { viewport: DESKTOP }, async (page) => {
        await open(lab, page, `#/${id}/aim`);
        assert.equal(await page.locator("article.exp:not([hidden]) [role=tab]").count(), 6, "six tabs");
        await assertOnlyPanelVisible(page, "aim");
        for (const slug of TABS) {
          await page.click(`article.exp:not([hidden]) [role=tab][data-tab="${slug}"]`);
          await assertOnlyPanelVisible(page, slug);
          const text = await page.locator(`article.exp:not([hidden]) [role=tabpanel][data-panel="${slug}"]`).innerText();
          assert.ok(text.trim().length > 0, `panel ${slug} of ${id} has content`);
          if (slug === "theory") {
            const maths = await page.locator('article.exp:not([hidden]) [data-panel="theory"] math').count();
            assert.ok(maths >= 1, `theory of ${id} has MathML`);
          }
          if (slug === "references") {
            const refs = await page.locator('article.exp:not([hidden]) [data-panel="references"] ol > li').count();
            assert.ok(refs >= 3, `references of ${id} list at least three sources`);
          }
          if (slug === "simulation") {
            await settle(page);
            await screenshot(page, `${id}-simulation-desktop`);
          }
        }
      }),
    );
  }
});

test("home page links every experiment from its cards (one click) and from the grouped menu (two clicks)", () =>
  withPage(lab, {}, async (page) => {
    await open(lab, page, "#/");
    const cards = await page.$$eval("a.card[data-experiment]", (as) =>
      as.map((a) => [a.dataset.experiment, a.getAttribute("href")]),
    );
    for (const [id, href] of cards) assert.ok(href.endsWith(`#/${id}/aim`), `card ${id}: ${href}`);
    // Every experiment in five groups, numbered 1, 2, … in the lab's order.
    const groups = await page.$$eval("[data-page=home] section.group h2", (hs) => hs.map((h) => h.textContent));
    assert.deepEqual(groups, ["Kinematics", "Mobile robots", "Planning", "Control", "Estimation"]);
    const numbers = await page.$$eval("#lab-nav .num", (ns) => ns.map((n) => Number(n.textContent)).sort((a, b) => a - b));
    assert.deepEqual(numbers, builtExperimentIds().map((_, i) => i + 1));
    const nav = await page.$$eval("nav#lab-nav a[data-experiment]", (as) =>
      as.map((a) => a.dataset.experiment),
    );
    assert.deepEqual([...nav].sort(), cards.map(([id]) => id).sort(), "nav reaches every experiment");
    await page.click("nav#lab-nav summary");
    await page.click(`nav#lab-nav a[data-experiment="${nav[nav.length - 1]}"]`);
    await page.locator("article.exp:not([hidden]) [role=tablist]").waitFor();
    assert.ok((await page.evaluate(() => location.hash)).startsWith(`#/${nav[nav.length - 1]}/`));
  }));

test("the lab works when hosted under a sub-path and never leaves its origin", () =>
  withPage(lab, {}, async (page) => {
    const requests = [];
    page.on("request", (r) => requests.push(r.url()));
    const wasmTypes = [];
    page.on("response", (r) => {
      if (r.url().split("?")[0].endsWith(".wasm")) wasmTypes.push(r.headers()["content-type"]);
    });
    // The folder URL itself (no index.html), as a static host serves it.
    await page.goto(lab.server.base);
    await page.waitForSelector("[data-page=home]:not([hidden])");
    await page.waitForLoadState("networkidle");
    assert.ok(!requests.some((u) => /\.wasm|\/pkg\//.test(u)), "the home page does not download the engine");
    await page.click("a.card[data-experiment]");
    await waitReady(page);
    await page.locator("article.exp:not([hidden]) [role=tablist]").waitFor();
    assert.ok(requests.length > 0);
    for (const url of requests) {
      const u = new URL(url);
      if (u.protocol === "data:" || u.protocol === "blob:") continue;
      assert.equal(u.origin, lab.server.origin, `same origin: ${url}`);
      assert.ok(u.pathname.startsWith(BASE_PATH), `stays under ${BASE_PATH}: ${url}`);
    }
    assert.deepEqual(wasmTypes, ["application/wasm"], "one wasm module, served as application/wasm");
    const glue = requests.filter((u) => /\/pkg\/[a-z]+\.[0-9a-f]{8}\.js$/.test(new URL(u).pathname));
    assert.equal(glue.length, 1, `the JS glue is fetched once: ${glue.join(", ")}`);
  }));

test("keyboard: ArrowRight/ArrowLeft/Home/End on the tab list select and focus tabs", () =>
  withPage(lab, {}, async (page) => {
    await open(lab, page, "#/fk/aim");
    const selected = () =>
      page.$eval("article.exp:not([hidden]) [role=tab][aria-selected=true]", (el) => el.dataset.tab);
    const focused = () => page.evaluate(() => document.activeElement?.dataset?.tab ?? null);
    await page.focus("article.exp:not([hidden]) [role=tab][aria-selected=true]");
    await page.keyboard.press("ArrowRight");
    assert.equal(await selected(), "theory", "ArrowRight selects the next tab");
    assert.equal(await focused(), "theory", "and focuses it");
    await assertOnlyPanelVisible(page, "theory");
    await page.keyboard.press("ArrowLeft");
    assert.equal(await selected(), "aim", "ArrowLeft goes back");
    await page.keyboard.press("End");
    assert.equal(await selected(), "references", "End selects the last tab");
    await page.keyboard.press("Home");
    assert.equal(await selected(), "aim", "Home selects the first tab");
  }));

test("keyboard: Tab reaches the sliders and ArrowRight on a slider changes the readouts", () =>
  withPage(lab, {}, async (page) => {
    await open(lab, page, "#/fk/simulation");
    await page.focus("article.exp:not([hidden]) [role=tab][aria-selected=true]");
    let onRange = false;
    for (let i = 0; i < 40 && !onRange; i++) {
      await page.keyboard.press("Tab");
      onRange = await page.evaluate(() => document.activeElement?.matches("input[type=range]"));
    }
    assert.ok(onRange, "Tab from the tab list reaches a slider within 40 presses");
    const before = await page.$$eval("[data-readout]", (els) => els.map((e) => e.textContent).join("|"));
    const valueBefore = await page.evaluate(() => document.activeElement.value);
    await page.keyboard.press("ArrowRight");
    await page.keyboard.press("ArrowRight");
    await settle(page);
    const valueAfter = await page.evaluate(() => document.activeElement.value);
    assert.notEqual(valueAfter, valueBefore, "ArrowRight moves the slider");
    const after = await page.$$eval("[data-readout]", (els) => els.map((e) => e.textContent).join("|"));
    assert.notEqual(after, before, "and the readouts follow");
  }));
