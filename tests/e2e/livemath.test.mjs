// "The math" on the Simulation tab (issue 27 §2): each equation in symbols,
// with the student's numbers put in, and the readout it gives — updated as
// the student moves a control, read by screen readers as text.

import { test } from "node:test";
import assert from "node:assert/strict";
import { open, readouts, runFor, runUntil, runUntilReadout, screenshot, settle, useLab, withPage } from "./helpers.mjs";

const lab = useLab();

/** The text twin of every equation in the panel. */
function equationTexts(page) {
  return page.$$eval(".live-math .equation-text", (els) => els.map((e) => e.textContent.trim()));
}

/** Evaluates "a m × cos b° + c m × cos d°"-style substituted text, as the panel writes it. */
function evaluate(substituted) {
  const js = substituted
    .replace(/ m(?=[ )]|$)/g, "")
    .replace(/×/g, "*")
    .replace(/−/g, "-")
    .replace(/cos /g, "Math.cos")
    .replace(/sin /g, "Math.sin")
    .replace(/(-?\d+(?:\.\d+)?)°/g, "(($1)*Math.PI/180)");
  return Function(`"use strict"; return (${js});`)();
}

test("live math: fk's panel writes x and y with the student's numbers, and they are the readouts", () =>
  withPage(lab, { clock: true }, async (page) => {
    await open(lab, page, "#/fk/simulation?t1=35&t2=60&l1=1&l2=0.8");
    await assert.doesNotReject(page.locator(".live-math h3", { hasText: "The math" }).waitFor());
    let [x, y] = await equationTexts(page);
    // Every number with its unit (issue 53 §6).
    assert.equal(x, "x = L1 cos θ1 + L2 cos (θ1 + θ2) = 1.00 m × cos 35.0° + 0.80 m × cos (35.0° + 60.0°) = 0.749 m");
    assert.match(y, /^y = L1 sin θ1 \+ L2 sin \(θ1 \+ θ2\) = 1\.00 m × sin 35\.0° \+ 0\.80 m × sin \(35\.0° \+ 60\.0°\) = /);
    // A slider moved: the numbers and the result follow, and still agree.
    await page.locator("#p-t1").fill("60");
    await runFor(page, 400);
    [x, y] = await equationTexts(page);
    const r = await readouts(page);
    for (const [text, key] of [[x, "x"], [y, "y"]]) {
      const [, , substituted, result] = text.split(" = ");
      assert.equal(result, r[key], `${key}: the panel's result is the readout`);
      assert.ok(
        Math.abs(evaluate(substituted) - Number.parseFloat(r[key])) <= 0.0005 + 1e-9,
        `${key}: ${substituted} evaluates to the readout ${r[key]}`,
      );
    }
    assert.match(x, /= 1\.00 m × cos 60\.0° \+ 0\.80 m × cos \(60\.0° \+ 60\.0°\) = 0\.100 m$/);
    // MathML is drawn; assistive technology reads the text twin instead.
    // x and y alike: the symbols a <math> a term (2); the numbers a <math> a
    // factor of each term ("1.00 m", "× cos 35.0°", "+0.80 m",
    // "× cos(35.0° + 60.0°)": 4, a sum of two numbers in brackets kept
    // whole), so that a line can break between them.
    assert.equal(await page.locator(".live-math .equation-forms math").count(), 12, "x and y: 2 + 4 <math> each");
    // The numbers and results are hidden from it; the symbols stay reachable
    // (each quantity's symbol takes the keyboard's focus, issue 27 §3).
    assert.equal(await page.locator(".live-math .equation-forms > [aria-hidden=true]").count(), 4);
    await screenshot(page, "livemath-fk-1280");
  }));

test("live math: on a phone the panel sits right after the readouts", () =>
  withPage(lab, { viewport: { width: 390, height: 844 }, hasTouch: true, isMobile: true, clock: true }, async (page) => {
    await open(lab, page, "#/fk/simulation");
    const readoutsBox = await page.locator("dl.readouts").boundingBox();
    const mathBox = await page.locator(".live-math").boundingBox();
    assert.ok(mathBox.y >= readoutsBox.y + readoutsBox.height - 1, "below the readouts");
    assert.ok(mathBox.y - (readoutsBox.y + readoutsBox.height) < 40, "right after them");
    assert.ok(mathBox.width <= 390, "fits the phone's width");
    await page.locator(".live-math").scrollIntoViewIfNeeded();
    await screenshot(page, "livemath-fk-390");
  }));

/** The panel's results, `= 0.749 m` each, or nothing where an equation says in words why it has no numbers. */
function equationResults(page) {
  return page.$$eval(".live-math .equation-result", (els) => els.map((e) => e.textContent.trim()));
}

/**
 * Waits, running page time, until "The math" panel shows the numbers of the
 * step the readouts show (their `data-step`s agree): while a run plays, the
 * panel's equations are written one an idle time after the readouts, so for
 * a moment they are of two steps (issue 53 §10). Returns that step.
 */
async function mathOfReadoutsStep(page, link) {
  await runUntil(
    page,
    () => {
      const math = document.querySelector("article.exp:not([hidden]) .live-math")?.dataset.step;
      const shown = document.querySelector("article.exp:not([hidden]) dl.readouts")?.dataset.step;
      return math !== undefined && math === shown;
    },
    undefined,
    { sliceMs: 17, maxMs: 5000, what: `${link}: the panel and the readouts of one step` },
  );
  return Number(await page.locator("article.exp:not([hidden]) dl.readouts").getAttribute("data-step"));
}

/** Every experiment's panel, reached by a link (and a button where a run needs one). */
const PANELS = [
  { link: "#/workspace/simulation", keys: ["x", "outer", "hole"] },
  { link: "#/ik/simulation?tx=0.9&ty=0.8", keys: ["theta2"] },
  { link: "#/pid/simulation", keys: ["u", "omega_n", "zeta"] },
  { link: "#/pid/simulation?sat=1&umax=5", keys: ["u", "omega_n", "zeta"], name: "pid-limited" },
  { link: "#/pid/simulation?ki=0&kp=25&kd=5", keys: ["u", "omega_n", "zeta"], name: "pid-second-order" },
  { link: "#/diffdrive/simulation?w1x=6&w1y=4", keys: ["omega", "v", "xdot", "ydot"] },
  { link: "#/potential/simulation?gx=8&gy=3", keys: ["goal_distance", "f_att", "clearance", "f_rep"] },
  { link: "#/astar/simulation", action: "plan", keys: ["h", "f"] },
  { link: "#/cartpole/simulation", keys: ["force", "energy"] },
  { link: "#/dls/simulation?tx=1&ty=1", keys: ["error", "w", "condition"] },
  { link: "#/rrtstar/simulation", action: "grow", keys: ["radius"] },
  { link: "#/ekf/simulation", keys: ["innovation_range", "innovation_bearing", "trace", "nees"] },
];

test("live math: every experiment's panel shows results equal to its readouts, at a laptop's width", () =>
  withPage(lab, { clock: true }, async (page) => {
    for (const { link, action, keys, name } of PANELS) {
      await open(lab, page, link);
      if (action) await page.locator(`button[data-action=${action}]`).click();
      // Read as a student reads it, in view: out of the window the panel
      // waits for the run to stop (issue 27, cost). Scrolled to again after
      // the run began: a live table above it (astar's open list, issue 53
      // §5) grows in its first steps and moves it down.
      await page.locator(".live-math").scrollIntoViewIfNeeded();
      await runFor(page, 700);
      await page.locator(".live-math").scrollIntoViewIfNeeded();
      await mathOfReadoutsStep(page, link);
      const texts = await equationTexts(page);
      assert.equal(texts.length, keys.length, `${link}: ${keys.length} equations`);
      assert.deepEqual(
        await page.$$eval(".live-math .equation", (els) => els.map((e) => e.dataset.key)),
        keys,
        `${link}: the equations by key`,
      );
      const r = await readouts(page);
      for (const result of await equationResults(page)) {
        if (result === "") continue;
        assert.ok(
          Object.values(r).some((value) => `= ${value}` === result),
          `${link}: the panel's ${result} is one of the readouts`,
        );
      }
      // At least one equation has a number to show once the run has gone on.
      assert.ok((await equationResults(page)).some((t) => t !== ""), `${link}: a result`);
      // No number is followed by dashes: where there are no numbers, words say why (issue 53 §6).
      const words = await page.$$eval(".live-math .equation", (els) =>
        els.map((e) => ({ key: e.dataset.key, result: e.querySelector(".equation-result").textContent.trim(), why: e.querySelector(".equation-absent")?.textContent.trim() ?? "" })),
      );
      for (const w of words) {
        assert.ok(w.result !== "" || w.why.length > 10, `${link}: ${w.key} has neither numbers nor words`);
      }
      assert.ok(!texts.some((t) => t.includes("--")), `${link}: dashes in ${JSON.stringify(texts)}`);
      if (link === "#/pid/simulation") {
        // Ki = 2: ωn and ζ hold for Ki = 0 only, and say so.
        assert.deepEqual(words.slice(1).map((w) => w.why.startsWith("Only with Ki = 0")), [true, true]);
      }
      // Each equation holds its own layout: its screen-reader twin (placed
      // absolutely) is laid out in it, not from the page's root, and it
      // spans the panel's width (its contained inline size is the panel's).
      const boxes = await page.$$eval(".live-math .equation", (els) =>
        els.map((e) => ({
          twinIn: e.querySelector(".equation-text")?.offsetParent === e,
          contain: getComputedStyle(e).contain,
          width: e.getBoundingClientRect().width,
          panel: e.parentElement.getBoundingClientRect().width,
        })),
      );
      for (const b of boxes) {
        assert.ok(b.twinIn && /layout/.test(b.contain), `${link}: an equation contains its layout: ${JSON.stringify(b)}`);
        assert.ok(b.width > 0.8 * b.panel, `${link}: an equation spans the panel: ${JSON.stringify(b)}`);
      }
      if (link.includes("sat=1")) {
        // The limit chose the other law: symbols and numbers both clamp.
        assert.match(texts[0], /^u = clamp\(Kp e \+ Ki ∫e dt − Kd x\u0307, ±umax\) = clamp\(/);
        assert.match(await page.locator(".live-math .equation-caption").first().textContent(), /actuator limit/);
      }
      if (link.includes("ki=0")) {
        // ωn = √(Kp/m) = √(25.0 / 1.0) = 5.000 rad/s, ζ = (c + Kd)/(2√(m Kp)) = 0.600.
        assert.equal(texts[1], "ωn = √((Kp) / (m)) = √((25.0 N/m) / (1.0 kg)) = 5.000 rad/s");
        assert.equal(texts[2], "ζ = (c + Kd) / (2 √(m Kp)) = (1.0 N·s/m + 5.0 N·s/m) / (2 × √(1.0 kg × 25.0 N/m)) = 0.600");
      }
      await page.locator(".live-math").scrollIntoViewIfNeeded();
      const shot = name ?? link.split("/")[1];
      await page.locator(".live-math").screenshot({ path: `target/e2e-shots/livemath-${shot}.png` });
    }
  }));

test("live math: while a run plays, every time the panel names the readouts' step its results are those readouts", () =>
  withPage(lab, { clock: true }, async (page) => {
    for (const link of ["#/diffdrive/simulation?w1x=6&w1y=4", "#/pid/simulation", "#/ekf/simulation"]) {
      await open(lab, page, link);
      await page.locator(".live-math").scrollIntoViewIfNeeded();
      const steps = new Set();
      // Every frame of two seconds of a run, read as it stands.
      for (let t = 0; t < 2000; t += 17) {
        await runFor(page, 17);
        const seen = await page.evaluate(() => {
          const article = document.querySelector("article.exp:not([hidden])");
          const values = [...article.querySelectorAll("dl.readouts [data-readout]")].map((e) => e.textContent.trim());
          return {
            math: article.querySelector(".live-math")?.dataset.step,
            shown: article.querySelector("dl.readouts")?.dataset.step,
            values,
            results: [...article.querySelectorAll(".live-math .equation-result")].map((e) => e.textContent.trim()),
          };
        });
        if (seen.math === undefined || seen.math !== seen.shown) continue;
        steps.add(seen.math);
        for (const result of seen.results) {
          if (result === "") continue;
          assert.ok(
            seen.values.some((value) => `= ${value}` === result),
            `${link} at step ${seen.math}: the panel's ${result} is one of that step's readouts ${JSON.stringify(seen.values)}`,
          );
        }
      }
      // The run moved on, and the panel caught up with it more than once.
      assert.ok(steps.size >= 3, `${link}: the panel named the readouts' step at ${steps.size} steps`);
    }
  }));

test("live math: on a phone every panel sits with the readouts and every formula wraps to its width", () =>
  withPage(lab, { viewport: { width: 390, height: 844 }, hasTouch: true, isMobile: true, clock: true }, async (page) => {
    for (const { link, action, name } of PANELS) {
      await open(lab, page, link);
      if (action) await page.locator(`button[data-action=${action}]`).click();
      await runFor(page, 700);
      const readoutsBox = await page.locator("dl.readouts").boundingBox();
      const mathBox = await page.locator(".live-math").boundingBox();
      assert.ok(mathBox.y >= readoutsBox.y + readoutsBox.height - 1, `${link}: below the readouts`);
      assert.ok(mathBox.y - (readoutsBox.y + readoutsBox.height) < 40, `${link}: right after them`);
      assert.ok(mathBox.x >= 0 && mathBox.x + mathBox.width <= 390, `${link}: within the phone's width`);
      // Every box of every formula (symbols and numbers) lies within its
      // paragraph: the lines break between terms and factors, none scrolls.
      const astray = await page.$$eval(".live-math .equation-forms", (forms) =>
        forms.flatMap((f) => {
          const box = f.getBoundingClientRect();
          const out = [...f.querySelectorAll("math")].filter((m) => {
            const r = m.getBoundingClientRect();
            return r.left < box.left - 0.5 || r.right > box.right + 0.5;
          });
          return out.map((m) => m.textContent).concat(f.scrollWidth > f.clientWidth ? [`scrolls: ${f.textContent}`] : []);
        }),
      );
      assert.deepEqual(astray, [], `${link}: formula boxes past the panel's width`);
      await page.locator(".live-math").scrollIntoViewIfNeeded();
      if (["ekf", "potential", "cartpole", "dls", "workspace"].some((id) => link.includes(id))) {
        await screenshot(page, `livemath-${name ?? link.split("/")[1]}-390`);
      }
    }
  }));

/** Waits (in page time) until the canvas shows step `n` and its readouts. */
async function atStep(page, n) {
  await runUntil(page, (k) => Number(document.querySelector("canvas.sim-canvas").dataset.steps) === k, n, {
    what: `step ${n}`,
  });
  await settle(page);
}

test("live math: a past step on the timeline shows that step's numbers, and the present ones again after", () =>
  withPage(lab, { clock: true }, async (page) => {
    await open(lab, page, "#/pid/simulation");
    await runUntilReadout(page, "x", ">", 0.5);
    await page.locator("button[data-time=play]").click();
    await runUntil(page, () => document.querySelector("button[data-time=play]").getAttribute("aria-pressed") === "false");
    await settle(page);
    const s = Number(await page.locator("canvas.sim-canvas").getAttribute("data-steps"));
    const now = await equationTexts(page);
    // Back to the middle of the run: the force law with that step's error.
    const k = Math.floor(s / 2);
    await page.locator(".tb-scrub").fill(String(k));
    await atStep(page, k);
    const past = await equationTexts(page);
    assert.notEqual(past[0], now[0], "the force law's numbers are the past step's");
    const r = await readouts(page);
    assert.equal(past[0].split(" = ").at(-1), r.force, "its result is that step's force readout");
    // One step on and back with the keys: the same numbers again.
    await page.locator("canvas.sim-canvas").focus();
    await page.keyboard.press(".");
    await atStep(page, k + 1);
    await page.keyboard.press(",");
    await atStep(page, k);
    assert.deepEqual(await equationTexts(page), past);
    // Forward to the end of the record: the present numbers.
    await page.locator(".tb-scrub").fill(String(s));
    await atStep(page, s);
    assert.deepEqual(await equationTexts(page), now);
  }));
