// Issue 53 §4, keys, buttons and help where the student is: the time keys
// work anywhere in the Simulation tab (not in a text field), so the canvas
// needs no click to take keys and a click on it acts, `?` lists every key, the
// phone's time bar buttons are named and 44 px tall, the slider is named and a
// mark goes back to its moment, Shift+Tab never hides a control under the
// header, and cartpole's Nudge pole sits by its Control switch. Every
// moment is reached on a stopped page clock.

import { test } from "node:test";
import assert from "node:assert/strict";
import { DESKTOP, open, runFor, runUntil, screenshot, settle, useLab, withPage } from "./helpers.mjs";

const lab = useLab();
const PHONE_TALL = { width: 390, height: 844 };
const ART = "article.exp:not([hidden])";
const CANVAS = `${ART} canvas.sim-canvas`;
const steps = (page) => page.$eval(CANVAS, (c) => Number(c.dataset.steps));

test("the time keys work after the slider and after Back, not in a text field; End after Plan & drive runs to the end", () =>
  withPage(lab, { clock: true }, async (page) => {
    await open(lab, page, "#/pid/simulation?run=0");
    await page.locator(`${ART} button[data-time=step]`).click();
    await page.locator(`${ART} button[data-time=step]`).click();
    await settle(page);
    const two = await steps(page);
    assert.ok(two > 0);
    // Focus on the Back button: `,` steps back, `.` steps on.
    await page.locator(`${ART} button[data-time=back]`).click();
    await settle(page);
    const one = await steps(page);
    assert.ok(one < two, "Back stepped back");
    await page.keyboard.press(",");
    await settle(page);
    assert.ok((await steps(page)) < one, "`,` after Back steps back");
    await page.keyboard.press(".");
    await settle(page);
    assert.equal(await steps(page), one, "`.` after Back steps on");
    // Focus on the timeline slider: `.` and M are the tab's; its arrows are its own.
    await page.focus(`${ART} .tb-scrub`);
    await page.keyboard.press(".");
    await settle(page);
    assert.equal(await steps(page), two, "`.` on the slider steps on");
    await page.keyboard.press("m");
    await settle(page);
    assert.equal(await page.locator(`${ART} .tb-mark`).count(), 1, "M on the slider marks");
    await page.keyboard.press("ArrowLeft");
    await settle(page);
    assert.equal(await steps(page), one, "the slider's own arrow");
    // In a text field the keys are typing.
    const box = `${ART} .sim-controls input[type=text]`;
    await page.focus(box);
    await page.keyboard.press(".");
    await page.keyboard.press("End");
    await settle(page);
    assert.equal(await steps(page), one, "`.` and End in a text field are typing");
    assert.notEqual(await page.$eval(`${ART} .timebar`, (b) => b.dataset.clock), "ended");

    // astar: End right after Plan & drive (focus on that button).
    await open(lab, page, "#/astar/simulation");
    await page.locator(`${ART} button[data-action=plan]`).click();
    await settle(page);
    const y = await page.evaluate(() => scrollY);
    await page.keyboard.press("End");
    await runUntil(page, () => document.querySelector("article.exp:not([hidden]) .timebar").dataset.clock === "ended", undefined, {
      what: "the run's end",
    });
    assert.equal(await page.evaluate(() => scrollY), y, "End did not scroll the page");
  }));

// A student never needs to click the canvas to give its keys focus: the time
// keys are the whole tab's. So a click on the canvas is what it looks like,
// an action (a wall painted at the first click, as a first tap does), and
// Tab gives the canvas focus without acting.
test("the time keys need no click on the canvas; a click on it acts at once, a tap too, and Tab focuses it without acting", async () => {
  const spot = async (page) => {
    const box = await page.locator(CANVAS).boundingBox();
    // Column 10, row 4 of the default 40 × 24 maze area: no handle there.
    return { x: box.x + box.width * 0.27, y: box.y + box.height * 0.2 };
  };
  const hash = (page) => page.evaluate(() => location.hash);
  const steps = (page) => page.locator(CANVAS).getAttribute("data-steps").then(Number);
  await withPage(lab, { clock: true }, async (page) => {
    await open(lab, page, "#/pid/simulation");
    // Focus on the Step button, never on the canvas: `.` steps, `,` goes back.
    await page.locator(`${ART} button[data-time=step]`).focus();
    await page.keyboard.press(".");
    await settle(page);
    const one = await steps(page);
    await page.keyboard.press(".");
    await settle(page);
    assert.equal(await steps(page), one + 1, "`.` steps with the canvas never focused");
  });
  await withPage(lab, { clock: true }, async (page) => {
    await open(lab, page, "#/astar/simulation");
    // Tab onto the canvas: it has focus and nothing on the grid changed.
    const before = await hash(page);
    await page.locator(CANVAS).focus();
    await runFor(page, 1000);
    assert.equal(await hash(page), before, "focusing the canvas changed nothing");
    await page.locator(`${ART} button[data-time=step]`).focus();
    const { x, y } = await spot(page);
    await page.mouse.click(x, y);
    await runUntil(page, (h) => location.hash !== h, before, { maxMs: 2000, what: "the first click to paint" });
    // The canvas's own keys work once it has focus: D describes.
    await page.keyboard.press("d");
    await settle(page);
    assert.ok((await page.locator(`${ART} .sim-description`).textContent()).length > 10);
  });
  await withPage(lab, { viewport: PHONE_TALL, hasTouch: true, isMobile: true, clock: true }, async (page) => {
    await open(lab, page, "#/astar/simulation");
    await page.locator(CANVAS).scrollIntoViewIfNeeded();
    const before = await hash(page);
    const { x, y } = await spot(page);
    await page.touchscreen.tap(x, y);
    await runUntil(page, (h) => location.hash !== h, before, { maxMs: 2000, what: "a first tap to paint" });
  });
});

test("? lists every key: the time keys, the slider's and the plots', the canvas's", () =>
  withPage(lab, { clock: true }, async (page) => {
    await open(lab, page, "#/pid/simulation");
    await page.locator(`${ART} button[data-time=step]`).focus();
    await page.keyboard.press("?");
    const dialog = page.locator("dialog#kbd-help[open]");
    await dialog.waitFor();
    const keys = await dialog.locator("kbd").allTextContents();
    for (const k of ["Space", ".", ",", "End", "M", "←", "→", "Page Up", "Page Down", "Home", "[", "]", "Escape", "D", "?"]) {
      assert.ok(keys.includes(k), `the help lists ${k}: ${keys.join(" ")}`);
    }
    assert.match(await dialog.textContent(), /not in a text field/);
    await screenshot(page, "keys-help-desktop");
  }));

// The words are read out, not shown, on a phone (style.css says why): the
// buttons are 44 px tall and on the screen; shown words, 44 px widths and a
// row that Pause turning into Play does not move are issue 53 §4's open
// phone bullet.
test("a phone's time bar: buttons named with the Procedure's words, 44 px tall, on the screen", () =>
  withPage(lab, { viewport: PHONE_TALL, hasTouch: true, isMobile: true, clock: true }, async (page) => {
    await open(lab, page, "#/pid/simulation");
    const bar = page.locator(`${ART} .timebar`);
    await bar.scrollIntoViewIfNeeded();
    const boxes = () =>
      page.$$eval(`${ART} .timebar [data-time]:not([data-time=speed]):not([data-time=scrub])`, (els) =>
        els.map((b) => {
          const r = b.getBoundingClientRect();
          return { what: b.dataset.time, text: b.innerText.trim(), x: r.x, y: r.y, w: r.width, h: r.height };
        }),
      );
    const first = await boxes();
    const words = { play: "Pause", step: "Step", back: "Back", end: "Run to end", mark: "Mark", reset: "Reset" };
    for (const b of first) {
      assert.equal(b.text, words[b.what], `${b.what} says ${words[b.what]}`);
      assert.ok(b.h >= 44, `${b.what}: ${b.w} × ${b.h} px`);
      assert.ok(b.x >= 0 && b.x + b.w <= PHONE_TALL.width, `${b.what} on the screen`);
    }
    await screenshot(page, "keys-timebar-phone");
    await page.keyboard.press("?");
    await page.locator("dialog#kbd-help[open]").waitFor();
    await screenshot(page, "keys-help-phone");
  }));

test("the slider is named Timeline with a tooltip; a mark's time goes back to its moment", () =>
  withPage(lab, { clock: true }, async (page) => {
    await open(lab, page, "#/pid/simulation?run=0");
    const slider = page.locator(`${ART} .tb-scrub`);
    const named = await slider.evaluate((s) => ({ label: s.labels[0]?.innerText.trim(), title: s.title }));
    assert.equal(named.label, "Timeline");
    assert.ok(named.title.length > 10, "a tooltip");
    for (let i = 0; i < 3; i++) await page.locator(`${ART} button[data-time=step]`).click();
    await settle(page);
    const marked = await steps(page);
    await page.locator(`${ART} button[data-time=mark]`).click();
    for (let i = 0; i < 3; i++) await page.locator(`${ART} button[data-time=step]`).click();
    await settle(page);
    assert.ok((await steps(page)) > marked);
    await page.locator(`${ART} .tb-mark button[data-goto]`).click();
    await settle(page);
    assert.equal(await steps(page), marked, "the mark's time shows its moment");
    await screenshot(page, "keys-timebar-desktop");
  }));

test("Shift+Tab never leaves the focused control under the sticky header", () =>
  withPage(lab, { viewport: DESKTOP }, async (page) => {
    await open(lab, page, "#/pid/simulation");
    await page.evaluate(() => scrollTo(0, document.documentElement.scrollHeight));
    // From the page's last control, back up through the tab.
    await page.evaluate(() => {
      const all = [...document.querySelectorAll("article.exp:not([hidden]) [data-panel=simulation] button, article.exp:not([hidden]) [data-panel=simulation] input")];
      all.filter((e) => e.offsetParent).at(-1).focus();
    });
    const hidden = [];
    for (let i = 0; i < 60; i++) {
      await page.keyboard.press("Shift+Tab");
      const where = await page.evaluate(() => {
        const el = document.activeElement;
        const top = document.querySelector(".top");
        if (!el || top.contains(el) || !el.closest("[data-panel=simulation]")) return null;
        const r = el.getBoundingClientRect();
        return { el: el.outerHTML.slice(0, 60), top: r.top, header: top.getBoundingClientRect().bottom };
      });
      if (!where) break;
      if (where.top < where.header - 1) hidden.push(where);
    }
    assert.deepEqual(hidden, [], "controls under the header");
  }));

test("cartpole on a phone: Nudge pole and the Control switch sit together", () =>
  withPage(lab, { viewport: PHONE_TALL, hasTouch: true, isMobile: true, clock: true }, async (page) => {
    await open(lab, page, "#/cartpole/simulation");
    const nudge = await page.locator(`${ART} button[data-action=nudge]`).boundingBox();
    const ctl = await page.locator(`${ART} [data-ctl=ctl]`).boundingBox();
    const apart = Math.abs(ctl.y - nudge.y);
    // One thumb's reach, on one screen (it was 2,241 px).
    assert.ok(apart < 300, `the Control switch is ${apart} px from Nudge pole`);
    // And it still switches the control.
    await page.locator(`${ART} [data-ctl=ctl] input[value="0"]`).check();
    await runUntil(page, () => location.hash.includes("ctl=0"), undefined, { maxMs: 2000, what: "the link to say ctl=0" });
  }));
