// axe-core (the npm package, injected from node_modules: no CDN) finds no
// WCAG 2.2 A/AA violation on the home page or on any tab of any experiment,
// in light and dark, once the wasm has mounted (issue 17 §6).

import { test } from "node:test";
import assert from "node:assert/strict";
import { createRequire } from "node:module";
import { TABS, experimentIds, open, settle, useLab, withPage } from "./helpers.mjs";

const lab = useLab();
const AXE = createRequire(import.meta.url).resolve("axe-core/axe.min.js");
const WCAG = ["wcag2a", "wcag2aa", "wcag21a", "wcag21aa", "wcag22aa"];

/** The violations axe finds on the page as it is now, in a readable form. */
async function violations(page) {
  if (!(await page.evaluate(() => typeof window.axe === "object"))) {
    await page.addScriptTag({ path: AXE });
  }
  return page.evaluate(async (tags) => {
    const result = await window.axe.run(document, {
      runOnly: { type: "tag", values: tags },
      resultTypes: ["violations"],
    });
    return result.violations.map((v) => ({
      rule: v.id,
      impact: v.impact,
      help: v.help,
      nodes: v.nodes.slice(0, 4).map((n) => `${n.target.join(" ")} :: ${n.failureSummary}`),
    }));
  }, WCAG);
}

/** Shows `tab` of the experiment on the page (a hash change, no reload). */
async function showTab(page, id, tab) {
  await page.evaluate((h) => (location.hash = h), `#/${id}/${tab}`);
  await page.waitForSelector(
    `article.exp:not([hidden]) [role=tabpanel][data-panel="${tab}"]:not([hidden])`,
  );
  await settle(page);
}

for (const scheme of ["light", "dark"]) {
  test(`axe: no WCAG 2.2 A/AA violation on the home page (${scheme})`, () =>
    withPage(lab, { colorScheme: scheme, bypassCSP: true }, async (page) => {
      await open(lab, page, "#/");
      assert.deepEqual(await violations(page), [], "home page");
    }));

  test(`axe: no WCAG 2.2 A/AA violation on any tab of any experiment (${scheme})`, async () => {
    const ids = await experimentIds(lab);
    for (const id of ids) {
      await withPage(lab, { colorScheme: scheme, bypassCSP: true }, async (page) => {
        // The Simulation tab first: the wasm mounts, then every tab is checked.
        await open(lab, page, `#/${id}/simulation`);
        await page.waitForSelector("article.exp:not([hidden]) canvas.sim-canvas");
        const found = {};
        for (const tab of TABS) {
          await showTab(page, id, tab);
          const v = await violations(page);
          if (v.length) found[tab] = v;
        }
        assert.deepEqual(found, {}, `${id} (${scheme})`);
      });
    }
  });
}

test("axe: the keyboard help dialog has no WCAG 2.2 A/AA violation", () =>
  withPage(lab, { bypassCSP: true }, async (page) => {
    await open(lab, page, "#/potential/simulation");
    await page.focus("article.exp:not([hidden]) canvas.sim-canvas");
    await page.keyboard.press("?");
    await page.waitForSelector("dialog#kbd-help[open]");
    assert.deepEqual(await violations(page), []);
  }));
