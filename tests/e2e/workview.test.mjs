// One view while you work (issue 23 §1 and §3): the scene and its main plot
// stay in view while any control is used, every plot a Procedure step names
// is in view together with that step's controls, the action that starts a
// run sits under the canvas on a phone, touch targets are finger-sized, and
// Describe shows what it says.

import { test } from "node:test";
import assert from "node:assert/strict";
import { builtExperimentIds, experimentIds, open, screenshot, settle, useLab, withPage } from "./helpers.mjs";

const lab = useLab();
const ART = "article.exp:not([hidden])";
const SIM = `${ART} [data-panel=simulation]`;
const LAPTOPS = [
  { width: 1280, height: 800 },
  { width: 1440, height: 900 },
];
const PHONE = { width: 390, height: 844 };
/** A phone with a touch screen: `(pointer: coarse)` matches. */
const TOUCH_PHONE = { viewport: PHONE, hasTouch: true, isMobile: true };

/**
 * The share (0 to 1) of the element matched by `selector` that a student
 * sees: points sampled over its box where it (or something inside it) is
 * the topmost thing on the screen. Off-screen parts, parts under the sticky
 * top bar, clipped by a scrolling column or covered by another element do
 * not count.
 */
function seenShare(page, selector) {
  return page.evaluate((sel) => {
    const el = document.querySelector(sel);
    const r = el?.getBoundingClientRect();
    if (!r || r.width < 1 || r.height < 1) return 0;
    let seen = 0;
    const [nx, ny] = [9, 7];
    for (let i = 0; i < nx; i++) {
      for (let j = 0; j < ny; j++) {
        const x = r.left + (r.width * (i + 0.5)) / nx;
        const y = r.top + (r.height * (j + 0.5)) / ny;
        if (x < 0 || y < 0 || x >= innerWidth || y >= innerHeight) continue;
        const hit = document.elementFromPoint(x, y);
        if (hit && (hit === el || el.contains(hit))) seen++;
      }
    }
    return seen / (nx * ny);
  }, selector);
}

const CANVAS = `${SIM} canvas.sim-canvas`;
const MAIN_PLOT = `${SIM} .sim-mainplot canvas.plot-canvas`;
const plotCanvas = (key) => `${SIM} figure.plot[data-plot="${key}"] canvas.plot-canvas`;

/** Asserts that the canvas and the main plot (when there is one) are at least `share` in view. */
async function assertSceneInView(page, what, share = 0.9) {
  const canvas = await seenShare(page, CANVAS);
  assert.ok(canvas >= share, `${what}: ${(canvas * 100).toFixed(0)} % of the canvas in view`);
  if ((await page.locator(MAIN_PLOT).count()) > 0) {
    const plot = await seenShare(page, MAIN_PLOT);
    assert.ok(plot >= share, `${what}: ${(plot * 100).toFixed(0)} % of the main plot in view`);
  }
}

/** Scrolls the element matched by `selector` into view as `scrollIntoView` does, with `block`. */
const scrollTo = (page, selector, block) =>
  page.evaluate(([sel, b]) => document.querySelector(sel).scrollIntoView({ block: b }), [selector, block]);

/** Opens every collapsed group of controls (a student opens one to reach its controls). */
const openGroups = (page) =>
  page.$$eval(`${SIM} details.ctl-group, ${SIM} details.presets`, (ds) => ds.forEach((d) => { d.open = true; }));

/**
 * Every control of the Simulation tab, as unique selectors: each
 * parameter's row, the Move a point form's fields and button, and the
 * experiment's actions.
 */
function controlSelectors(page) {
  return page.evaluate((sim) => {
    const shown = (el) => el.getClientRects().length > 0;
    const out = [];
    for (const row of document.querySelectorAll(`${sim} :is(.sim-controls, .sim-actions) [data-ctl]`)) {
      if (shown(row)) out.push({ sel: `${sim} [data-ctl="${row.dataset.ctl}"]`, kind: "param" });
    }
    const move = document.querySelector(`${sim} .sim-move`);
    if (move && shown(move)) {
      // A handle on a track (PID's setpoint) has no y box to type in.
      for (const id of ["move-handle", "move-x", "move-y"]) {
        const box = move.querySelector(`#${id}`);
        if (box && shown(box)) out.push({ sel: `${sim} .sim-move #${id}`, kind: "move" });
      }
      out.push({ sel: `${sim} .sim-move button[type=submit]`, kind: "move" });
    }
    // A hidden button ("Hide basin map" without a map) is no control a
    // student can use.
    for (const b of document.querySelectorAll(`${sim} .sim-actions button[data-action]:not([hidden])`)) {
      out.push({ sel: `${sim} .sim-actions button[data-action="${b.dataset.action}"]`, kind: "action" });
    }
    return out;
  }, SIM);
}

/** Uses the control a student would: nudges a slider, re-enters a number, picks another choice and back, flips a toggle and back. */
async function operate(page, control) {
  const row = page.locator(control.sel);
  if (control.kind === "action") {
    await row.click();
    return;
  }
  if (control.kind === "move") {
    const tag = await row.evaluate((el) => el.tagName);
    if (tag === "BUTTON") await row.click();
    else if (tag === "SELECT") await row.selectOption({ index: 0 });
    else await row.fill(await row.inputValue());
    return;
  }
  const kind = await row.evaluate((el) => el.className);
  if (/ctl-slider/.test(kind)) {
    const range = row.locator("input[type=range]");
    if (await range.isDisabled()) return;
    await range.focus();
    await page.keyboard.press("ArrowRight");
    await page.keyboard.press("ArrowLeft");
  } else if (/ctl-choice/.test(kind)) {
    const select = row.locator("select");
    const was = await select.inputValue();
    const count = await select.locator("option").count();
    await select.selectOption({ index: (Number(was) + 1) % count });
    await select.selectOption(was);
  } else if (/ctl-toggle/.test(kind)) {
    const off = row.locator("input[type=radio]:not(:checked)");
    const on = row.locator("input[type=radio]:checked");
    const back = await on.getAttribute("value");
    await off.check({ force: true });
    await row.locator(`input[type=radio][value="${back}"]`).check({ force: true });
  } else {
    const box = row.locator("input[type=text]");
    await box.fill(await box.inputValue());
    await box.press("Enter");
  }
}

for (const viewport of LAPTOPS) {
  test(`at ${viewport.width}×${viewport.height}, with every control scrolled into view and used, the canvas and the main plot stay in view, on every experiment`, async (t) => {
    const ids = await experimentIds(lab);
    assert.deepEqual([...ids].sort(), builtExperimentIds().sort(), `every built experiment (${ids.join(", ")})`);
    for (const id of ids) {
      await t.test(id, () =>
        withPage(lab, { viewport }, async (page) => {
          await open(lab, page, `#/${id}/simulation?run=0`);
          await settle(page);
          await openGroups(page);
          const controls = await controlSelectors(page);
          assert.ok(controls.length > 0, `${id}: has controls`);
          for (const control of controls) {
            const what = `${id} ${control.sel.replace(SIM, "").trim()}`;
            await page.evaluate(() => scrollTo(0, 0));
            await scrollTo(page, control.sel, "nearest");
            await assertSceneInView(page, `${what} (scrolled to, nearest)`);
            await scrollTo(page, control.sel, "center");
            await assertSceneInView(page, `${what} (scrolled to, centred)`);
            await operate(page, control);
            await settle(page);
            await assertSceneInView(page, `${what} (used)`);
            assert.ok((await seenShare(page, control.sel)) >= 0.9, `${what}: the control itself is in view`);
          }
          if (viewport.width === 1280) {
            const last = controls.filter((c) => c.kind === "param").at(-1);
            if (last) await scrollTo(page, last.sel, "center");
            await screenshot(page, `${id}-workview-1280-control`);
          }
        }),
      );
    }
  });
}

// The plots a Procedure step names. Each phrase must still be in its
// experiment's Procedure (the test fails when the text changes), every step
// that speaks of a plot, a curve or a strip must name one through a phrase or
// the plot's own title, and every key must be a plot on the page.
const PLOT_PHRASES = {
  pid: [["response plot", ["response"]], ["the plot gets crowded", ["response"]], ["effort strip", ["effort"]], ["D term", ["effort"]]],
  cartpole: [["θ, x and F plots", ["angle", "position", "force"]], ["F plot", ["force"]]],
  ekf: [["x and y errors", ["error_x", "error_y"]], ["the NEES", ["nees"]], ["average-NEES curve", ["anees"]]],
  diffdrive: [["In the plot", ["motion"]]],
  potential: [["the plot shows", ["run"]]],
  rrtstar: [["plot of best length", ["cost"]], ["three curves", ["cost"]]],
};

/** The words of a plot title that name it in prose: the title up to a colon, a bracket, "with", "of" or "over" (two words at least). */
function titleName(title) {
  const name = title.split(/:|\(| with | of | over /)[0].trim();
  return name.split(/\s+/).length >= 2 ? name : null;
}

const escapeRegExp = (s) => s.replace(/[.*+?^${}()|[\]\\]/g, "\\$&");
/** Whether `text` contains `word` as a whole word (letters and digits of any script count as word characters). */
const hasWord = (text, word) => new RegExp(`(?<![\\p{L}\\p{N}_])${escapeRegExp(word)}(?![\\p{L}\\p{N}_])`, "u").test(text);

/**
 * The controls a step names: a parameter whose label (or the label without
 * its trailing symbol, such as "Sensor noise" of "Sensor noise σ") the text
 * contains, or whose symbol (two characters at least: "Ki", "kθ") it
 * contains as a word; an action whose label it contains.
 */
function namedControls(step, params, actions) {
  const lower = step.toLowerCase();
  const out = [];
  for (const { key, label } of params) {
    const words = label.split(/\s+/);
    const prefix = words.length > 1 ? words.slice(0, -1).join(" ") : null;
    const symbol = words.at(-1);
    if (
      lower.includes(label.toLowerCase()) ||
      (prefix && prefix.length >= 4 && lower.includes(prefix.toLowerCase())) ||
      (symbol.length >= 2 && hasWord(step, symbol))
    ) {
      out.push({ sel: `${SIM} [data-ctl="${key}"]`, name: label });
    }
  }
  for (const { key, label } of actions) {
    if (step.includes(label)) out.push({ sel: `${SIM} .sim-actions button[data-action="${key}"]`, name: label });
  }
  return out;
}

for (const viewport of LAPTOPS) {
  test(`at ${viewport.width}×${viewport.height}, every plot a Procedure step names is in view with the scene, the main plot and that step's controls`, async (t) => {
    const ids = await experimentIds(lab);
    let checked = 0;
    for (const id of ids) {
      await t.test(id, () =>
        withPage(lab, { viewport }, async (page) => {
          await open(lab, page, `#/${id}/simulation?run=0`);
          await settle(page);
          await openGroups(page);
          const { steps, plots, params, actions } = await page.evaluate((art) => ({
            steps: [...document.querySelectorAll(`${art} [data-panel=procedure] ol.steps > li`)].map((li) => li.textContent.replace(/\s+/g, " ")),
            plots: [...document.querySelectorAll(`${art} [data-panel=simulation] figure.plot`)].map((f) => ({
              key: f.dataset.plot,
              title: f.querySelector(".plot-title").textContent,
            })),
            params: [...document.querySelectorAll(`${art} [data-panel=simulation] :is(.sim-controls, .sim-actions) [data-ctl]`)].map((row) => ({
              key: row.dataset.ctl,
              label: row.querySelector("label, legend").textContent.trim(),
            })),
            actions: [...document.querySelectorAll(`${art} [data-panel=simulation] .sim-actions button[data-action]:not([hidden])`)].map((b) => ({
              key: b.dataset.action,
              label: b.textContent.trim(),
            })),
          }), ART);
          assert.ok(steps.length >= 5, `${id}: the Procedure's steps are on the page (${steps.length})`);
          const keys = new Set(plots.map((p) => p.key));
          const phrases = PLOT_PHRASES[id] ?? [];
          for (const [phrase, named] of phrases) {
            assert.ok(steps.some((s) => s.includes(phrase)), `${id}: the Procedure still says “${phrase}”`);
            for (const key of named) assert.ok(keys.has(key), `${id}: “${phrase}” names plot ${key}, which is on the page`);
          }
          for (const [k, step] of steps.entries()) {
            const named = new Set();
            for (const [phrase, plotKeys] of phrases) if (step.includes(phrase)) plotKeys.forEach((p) => named.add(p));
            for (const { key, title } of plots) {
              const name = titleName(title);
              if (name && step.toLowerCase().includes(name.toLowerCase())) named.add(key);
            }
            if (plots.length > 0 && /\b(plot|plots|curve|curves|strip)\b/i.test(step)) {
              assert.ok(named.size > 0, `${id} step ${k + 1} speaks of a plot but names none known to this test: “${step.slice(0, 120)}…”`);
            }
            if (named.size === 0) continue;
            const controls = namedControls(step, params, actions);
            // A step without a control of its own is read at the page's
            // first view, as it opens.
            const at = controls.length > 0 ? controls : [null];
            for (const control of at) {
              await page.evaluate(() => scrollTo(0, 0));
              if (control) await scrollTo(page, control.sel, "nearest");
              for (const key of named) {
                // The student brings the plot into view: the page (or the
                // plots' own column) scrolls as little as it can.
                await scrollTo(page, plotCanvas(key), "nearest");
                const what = `${id} step ${k + 1}${control ? ` with ${control.name}` : ""}, plot ${key}`;
                await assertSceneInView(page, what);
                const share = await seenShare(page, plotCanvas(key));
                assert.ok(share >= 0.9, `${what}: ${(share * 100).toFixed(0)} % of the plot in view`);
                if (control) {
                  const c = await seenShare(page, control.sel);
                  assert.ok(c >= 0.9, `${what}: the control is still in view (${(c * 100).toFixed(0)} %)`);
                }
                checked++;
              }
            }
          }
        }),
      );
    }
    assert.ok(checked >= 20, `${checked} step, control and plot combinations checked`);
  });
}

/**
 * Runs `body(page, id)` as a subtest of `t` for every experiment, on a
 * touch phone, with its Simulation tab open and settled.
 */
async function onEveryPhoneSim(t, body) {
  for (const id of await experimentIds(lab)) {
    await t.test(id, () =>
      withPage(lab, TOUCH_PHONE, async (page) => {
        await open(lab, page, `#/${id}/simulation`);
        await settle(page);
        await body(page, id);
      }),
    );
  }
}

test("on a phone (390×844) the action that starts a run sits right under the canvas, in its first screen, and tapping it keeps 80 % of the canvas in view", async (t) => {
  await onEveryPhoneSim(t, async (page, id) => {
    const action = page.locator(`${SIM} .sim-actions button[data-action]`).first();
    if ((await action.count()) === 0) return; // fk and ik: the canvas is the action
    const [canvas, button, plot] = await page.evaluate((sim) => {
      const box = (sel) => document.querySelector(sel)?.getBoundingClientRect().toJSON() ?? null;
      return [box(`${sim} canvas.sim-canvas`), box(`${sim} .sim-actions button`), box(`${sim} .sim-mainplot`)];
    }, SIM);
    assert.ok(button.bottom <= PHONE.height, `${id}: the main action ends at ${button.bottom} px, inside the first screen`);
    assert.ok(button.top >= canvas.bottom, `${id}: the main action is under the canvas`);
    if (plot) assert.ok(button.bottom <= plot.top, `${id}: the main action comes before the main plot`);
    await action.tap();
    await settle(page);
    await assertSceneInView(page, `${id}: after tapping ${await action.textContent()}`, 0);
    const share = await seenShare(page, CANVAS);
    assert.ok(share >= 0.8, `${id}: ${(share * 100).toFixed(0)} % of the canvas in view after the tap`);
  });
});

test("touch targets: on a touch screen every visible button, field, choice and slider of the Simulation tab is at least 44 CSS px tall", async (t) => {
  await onEveryPhoneSim(t, async (page, id) => {
    assert.ok(await page.evaluate(() => matchMedia("(pointer: coarse)").matches), "a coarse pointer");
    await openGroups(page);
    await page.$$eval(`${ART} details.instructor-panel`, (ds) => ds.forEach((d) => { d.open = true; }));
    // The panel is built when first opened (its code is fetched then).
    await page.locator(`${ART} details.instructor-panel .instructor-link`).waitFor({ state: "attached" });
    const small = await page.evaluate((art) => {
      const els = document.querySelectorAll(
        `.top summary, ${art} [role=tab], ${art} [data-panel=simulation] :is(button, input, select, summary)`,
      );
      return [...els]
        .filter((el) => {
          const r = el.getBoundingClientRect();
          const cs = getComputedStyle(el);
          // Skipped: not shown, and the visually hidden file input.
          return r.width > 1 && r.height > 1 && cs.visibility !== "hidden" && !el.closest("[hidden]");
        })
        .map((el) => ({ el, h: el.getBoundingClientRect().height }))
        .filter(({ h }) => h < 44 - 0.01)
        .map(({ el, h }) => `${el.tagName.toLowerCase()}${el.type ? `[${el.type}]` : ""} “${(el.textContent || el.getAttribute("aria-label") || el.id || "").trim().slice(0, 30)}” ${h.toFixed(1)} px`);
    }, ART);
    assert.deepEqual(small, [], `${id}: controls under 44 px`);
    if (id === "pid") await screenshot(page, "pid-touch-390");
  });
});

test("astar on a phone: the Moves select shows its whole choice (“8-connected”), and so does every select of every experiment", async (t) => {
  await onEveryPhoneSim(t, async (page, id) => {
    await openGroups(page);
    await settle(page);
    const cut = await page.evaluate((sim) =>
      [...document.querySelectorAll(`${sim} select`)]
        .filter((s) => s.getClientRects().length > 0)
        .map((s) => {
          // The width the select takes to show its chosen option where
          // nothing squeezes it.
          const free = s.cloneNode(true);
          [...free.options].filter((o) => o.value !== s.value).forEach((o) => o.remove());
          free.style.cssText = "position:absolute;left:0;top:0;width:auto;min-width:0;max-width:none;visibility:hidden";
          s.parentElement.append(free);
          const natural = free.getBoundingClientRect().width;
          free.remove();
          const shown = s.getBoundingClientRect();
          return { id: s.id, natural, width: shown.width, right: shown.right };
        })
        .filter((s) => s.width < s.natural - 0.5 || s.right > innerWidth),
    SIM);
    assert.deepEqual(cut, [], `${id}: selects narrower than their choice or past the screen's edge`);
    if (id === "astar") {
      const moves = await page.locator(`${SIM} #p-conn`).boundingBox();
      assert.ok(moves.x + moves.width <= PHONE.width, "the Moves select ends on the screen");
      await page.locator(`${SIM} #p-conn`).scrollIntoViewIfNeeded();
      await screenshot(page, "astar-moves-390");
    }
  });
});

for (const [name, options] of [["1280×800", { viewport: LAPTOPS[0] }], ["390×844", TOUCH_PHONE]]) {
  test(`Describe shows its description on the page as well as announcing it (${name})`, () =>
    withPage(lab, options, async (page) => {
      for (const id of ["pid", "astar", "fk"]) {
        await open(lab, page, `#/${id}/simulation`);
        const shown = page.locator(`${SIM} .sim-description`);
        assert.equal(await shown.isVisible(), false, `${id}: nothing shown before Describe`);
        await page.click(`${SIM} [data-a11y=describe]`);
        await settle(page);
        const [text, live] = await page.evaluate((sim) => [
          document.querySelector(`${sim} .sim-description`).textContent,
          document.querySelector(`${sim} .sim-live`).textContent,
        ], SIM);
        assert.ok(text.length > 20, `${id}: a description is shown (${text})`);
        assert.equal(live.replace(/\u00a0/g, "").trim(), text.trim(), `${id}: the page shows what was announced`);
        const share = await seenShare(page, `${SIM} .sim-description`);
        assert.ok(share >= 0.9, `${id}: the description is in view (${(share * 100).toFixed(0)} %)`);
        assert.equal(await shown.getAttribute("aria-live"), null, "announced once, by the live region");
        if (id === "pid") await screenshot(page, `pid-described-${name}`);
      }
    }));
}
