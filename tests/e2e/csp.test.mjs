// The strict Content-Security-Policy (issue 17 §5): dist/index.html carries
// it as a <meta http-equiv>, and every page runs under it with zero
// `securitypolicyviolation` events and still works.

import { test } from "node:test";
import assert from "node:assert/strict";
import { readFile } from "node:fs/promises";
import { join } from "node:path";
import { DIST, builtExperimentIds, experimentIds, open, screenshot, settle, useLab, withPage } from "./helpers.mjs";

const lab = useLab();

const POLICY =
  "default-src 'self'; script-src 'self' 'wasm-unsafe-eval'; style-src 'self'; " +
  "img-src 'self' data: blob:; worker-src 'self'; object-src 'none'; base-uri 'self'";

// Registered before any of the page's own code runs: every violation of the
// page's lifetime is kept.
const RECORD_VIOLATIONS = () => {
  window.__cspViolations = [];
  document.addEventListener("securitypolicyviolation", (e) => {
    window.__cspViolations.push(
      `${e.effectiveDirective} blocked ${e.blockedURI || "(inline)"} at ${e.sourceFile}:${e.lineNumber} ` +
        `sample ${JSON.stringify(e.sample)}`,
    );
  });
};

/** The violations so far, after the queued reports have been delivered. */
async function violations(page) {
  await settle(page);
  await settle(page);
  return page.evaluate(() => window.__cspViolations);
}

/** The simulation canvas is in place and holds more than one colour. */
async function assertCanvasDrawn(page, where) {
  const canvas = page.locator("article.exp:not([hidden]) canvas.sim-canvas[data-view]");
  await canvas.waitFor();
  await settle(page);
  const colours = await canvas.evaluate((c) => {
    const d = c.getContext("2d").getImageData(0, 0, c.width, c.height).data;
    const seen = new Set();
    for (let i = 0; i < d.length && seen.size < 3; i += 4 * 97) seen.add(d[i] * 65536 + d[i + 1] * 256 + d[i + 2]);
    return seen.size;
  });
  assert.ok(colours >= 2, `${where}: the canvas is drawn (${colours} colour)`);
}

test("dist/index.html carries the policy as its first <head> rule and has nothing inline", async () => {
  const html = await readFile(join(DIST, "index.html"), "utf8");
  const meta = `<meta http-equiv="Content-Security-Policy" content="${POLICY}">`;
  assert.ok(html.includes(meta), "the meta policy, exactly");
  const at = html.indexOf(meta);
  for (const tag of ["<link", "<script", "<style", "<svg", "<img"]) {
    const first = html.indexOf(tag);
    assert.ok(first === -1 || first > at, `the policy comes before the first ${tag}`);
  }
  assert.doesNotMatch(html, /<script(?![^>]*\bsrc=)[^>]*>/i, "no inline <script> (nor an import map)");
  assert.doesNotMatch(html, /<style[\s>]/i, "no <style> element");
  assert.doesNotMatch(html, /\sstyle=/i, "no style attribute");
  assert.doesNotMatch(html, /\son[a-z]+=/i, "no inline event handler");
  assert.doesNotMatch(html, /javascript:/i, "no javascript: URL");
});

test("the listener sees a violation when there is one (the policy is in force)", () =>
  withPage(lab, { initScript: RECORD_VIOLATIONS, allowConsoleErrors: true }, async (page) => {
    await open(lab, page, "#/");
    assert.deepEqual(await violations(page), []);
    await page.evaluate(() => {
      document.body.insertAdjacentHTML("beforeend", '<p id="csp-probe" style="color: red">x</p>');
    });
    // One violation, reported once per copy of the policy in force: the
    // <meta> and the header `cargo xtask serve` sends (a host may send none).
    const seen = await violations(page);
    assert.ok(seen.length >= 1 && seen.length <= 2, seen.join("\n"));
    assert.equal(new Set(seen).size, 1, seen.join("\n"));
    assert.match(seen[0], /^style-src/);
    assert.notEqual(
      await page.$eval("#csp-probe", (p) => getComputedStyle(p).color),
      "rgb(255, 0, 0)",
      "the inline style was not applied",
    );
  }));

test("home page: zero CSP violations, every card picture coloured", () =>
  withPage(lab, { initScript: RECORD_VIOLATIONS }, async (page) => {
    await open(lab, page, "#/");
    assert.deepEqual(await violations(page), []);
    // The thumbnails paint with theme colours through classes: a link in the
    // arm pictures is --c-link's blue, not the default black.
    const strokes = await page.$$eval("a.card .card-pic svg [stroke=currentColor]", (els) =>
      [...new Set(els.map((e) => getComputedStyle(e).stroke))],
    );
    assert.ok(strokes.length >= 3, `several colours in the pictures: ${strokes.join(", ")}`);
    assert.ok(strokes.includes("rgb(0, 114, 178)"), `--c-link #0072B2 among ${strokes.join(", ")}`);
    const background = await page.$eval("a.card .card-pic svg.thumb", (s) => getComputedStyle(s).backgroundColor);
    assert.equal(background, "rgb(255, 255, 255)", "the canvas colour behind the picture");
    await screenshot(page, "home-csp");
    // The skip link focuses the page without changing the hash.
    await page.keyboard.press("Tab");
    await page.keyboard.press("Enter");
    assert.equal(await page.evaluate(() => document.activeElement?.id), "app");
    assert.equal(await page.evaluate(() => location.hash), "#/");
  }));

test("every experiment's Simulation tab: zero CSP violations, the canvas drawn, a plot legend coloured", async (t) => {
  const ids = await experimentIds(lab);
  assert.deepEqual([...ids].sort(), builtExperimentIds().sort(), `every built experiment: ${ids.join(", ")}`);
  for (const id of ids) {
    await t.test(id, () =>
      withPage(lab, { initScript: RECORD_VIOLATIONS }, async (page) => {
        await open(lab, page, `#/${id}/simulation`);
        await assertCanvasDrawn(page, id);
        // Enter in a parameter's number box applies it and does not submit
        // (reload) the page: the listener that replaced `onsubmit` works.
        const box = page.locator("article.exp:not([hidden]) form.sim-controls input[type=text]").first();
        if (await box.count()) {
          await page.evaluate(() => { window.__stillHere = true; });
          await box.press("Enter");
          await settle(page);
          assert.equal(await page.evaluate(() => window.__stillHere), true, `${id}: no reload`);
        }
        const legend = page.locator("article.exp:not([hidden]) .plot-legend svg line[stroke=currentColor]");
        if (await legend.count()) {
          const stroke = await legend.first().evaluate((l) => getComputedStyle(l).stroke);
          assert.notEqual(stroke, "rgb(0, 0, 0)", `${id}: legend swatch takes its series colour`);
        }
        assert.deepEqual(await violations(page), [], `${id}: no CSP violation`);
      }),
    );
  }
});

test("the Instructor panel, opened (its code fetched then) and used: zero CSP violations", () =>
  withPage(lab, { initScript: RECORD_VIOLATIONS }, async (page) => {
    await open(lab, page, "#/pid/simulation");
    await page.click("article.exp:not([hidden]) details.instructor-panel > summary");
    await page.check('input[data-lock="kp"]');
    await page.fill(".instructor-note-input", "Watch the overshoot");
    await page.click('[data-instructor="copy"]');
    assert.match(await page.inputValue(".instructor-link"), /[?&]lock=kp&note=Watch%20the%20overshoot(&|$)/);
    assert.deepEqual(await violations(page), [], "instructor panel");
  }));

test("a reading tab and the quiz, submitted: zero CSP violations", () =>
  withPage(lab, { initScript: RECORD_VIOLATIONS }, async (page) => {
    await open(lab, page, "#/pid/theory");
    await page.locator("article.exp:not([hidden]) [role=tabpanel][data-panel=theory]").waitFor();
    assert.deepEqual(await violations(page), [], "theory tab");
    await open(lab, page, "#/pid/quiz");
    await page.locator("form.quiz .quiz-q").first().waitFor();
    await page.click("form.quiz button[type=submit]");
    if (await page.locator("form.quiz .quiz-confirm").isVisible()) {
      await page.click("form.quiz button[type=submit]");
    }
    await page.locator(".quiz-score").waitFor();
    assert.deepEqual(await violations(page), [], "quiz tab");
  }));
