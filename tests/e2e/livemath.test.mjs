// "The math" on the Simulation tab (issue 27 §2): each equation in symbols,
// with the student's numbers put in, and the readout it gives — updated as
// the student moves a control, read by screen readers as text.

import { test } from "node:test";
import assert from "node:assert/strict";
import { open, readouts, runFor, screenshot, useLab, withPage } from "./helpers.mjs";

const lab = useLab();

/** The text twin of every equation in the panel. */
function equationTexts(page) {
  return page.$$eval(".live-math .equation-text", (els) => els.map((e) => e.textContent.trim()));
}

/** Evaluates "a·cos b° + c·cos d°"-style substituted text, as the panel writes it. */
function evaluate(substituted) {
  const js = substituted
    .replace(/·/g, "*")
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
    assert.equal(x, "x = L1 cos θ1 + L2 cos (θ1 + θ2) = 1.00·cos 35.0° + 0.80·cos (35.0° + 60.0°) = 0.749 m");
    assert.match(y, /^y = L1 sin θ1 \+ L2 sin \(θ1 \+ θ2\) = 1\.00·sin 35\.0° \+ 0\.80·sin \(35\.0° \+ 60\.0°\) = /);
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
    assert.match(x, /= 1\.00·cos 60\.0° \+ 0\.80·cos \(60\.0° \+ 60\.0°\) = 0\.100 m$/);
    // MathML is drawn; assistive technology reads the text twin instead.
    assert.equal(await page.locator(".live-math .equation-forms math").count(), 6, "x and y: the symbols, then a <math> a term");
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

test("live math: every experiment with a panel shows results equal to its readouts, at a laptop's width", () =>
  withPage(lab, { clock: true }, async (page) => {
    const links = [
      "#/workspace/simulation",
      "#/ik/simulation?tx=0.9&ty=0.8",
      "#/pid/simulation",
      "#/pid/simulation?sat=1&umax=5",
    ];
    for (const link of links) {
      await open(lab, page, link);
      await runFor(page, 700);
      const texts = await equationTexts(page);
      assert.ok(texts.length > 0, `${link}: a panel`);
      const r = await readouts(page);
      const results = await page.$$eval(".live-math .equation-result", (els) => els.map((e) => e.textContent.trim()));
      for (const result of results) {
        assert.ok(
          Object.values(r).some((value) => `= ${value}` === result),
          `${link}: the panel's ${result} is one of the readouts`,
        );
      }
      if (link.includes("sat=1")) {
        // The limit chose the other law: symbols and numbers both clamp.
        assert.match(texts[0], /^u = clamp\(Kp e \+ Ki ∫e − Kd ẏ, ±umax\) = clamp\(/);
        assert.match(await page.locator(".live-math .equation-caption").first().textContent(), /actuator limit/);
      }
      await page.locator(".live-math").scrollIntoViewIfNeeded();
      await page.locator(".live-math").screenshot({ path: `target/e2e-shots/livemath-${link.split("/")[1]}${link.includes("sat") ? "-limited" : ""}.png` });
    }
  }));
