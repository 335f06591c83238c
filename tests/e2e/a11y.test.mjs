// Accessibility beyond the automated rules (issue 17 §6): every handle moves
// from the keyboard and from typed coordinates, the scene is described in a
// live region on request and at the end of a run, `?` opens the key list,
// and forced colours / more contrast still draw the scene.

import { test } from "node:test";
import assert from "node:assert/strict";
import { open, runFor, runUntil, screenshot, settle, useLab, withPage, PHONE } from "./helpers.mjs";

const lab = useLab();
const CANVAS = "article.exp:not([hidden]) canvas.sim-canvas";
const LIVE = "article.exp:not([hidden]) .sim-live";

/**
 * The link's parameters once the page has written it. The tests run on a
 * stopped clock: the link is written a frame after a key or a drag has been
 * still for 250 ms of page time (HASH_INTERVAL_MS in sim/mod.rs), so running
 * twice that reaches it however busy the machine is.
 */
async function linkParams(page) {
  await runFor(page, 500);
  return new URLSearchParams((await page.evaluate(() => location.hash)).split("?")[1] || "");
}

/** The 2 % keyboard step of the canvas's world view (`data-view` = min x, min y, max x, max y). */
async function keyboardStep(page) {
  const view = (await page.getAttribute(CANVAS, "data-view")).split(",").map(Number);
  return (view[2] - view[0]) * 0.02;
}

async function live(page) {
  return (await page.textContent(LIVE)).trim();
}

async function press(page, key) {
  await page.keyboard.press(key);
  await settle(page);
}

test("diffdrive: [ ] choose a waypoint, arrows move it, the link and the form follow", () =>
  withPage(lab, { clock: true }, async (page) => {
    await open(lab, page, "#/diffdrive/simulation?w1x=3&w1y=2&w2x=6&w2y=4&run=0");
    await page.focus(CANVAS);
    await press(page, "]");
    assert.equal(await live(page), "Chosen: Waypoint 1 at (3.00, 2.00) m.");
    const step = await keyboardStep(page);
    await press(page, "ArrowRight");
    const p = await linkParams(page);
    assert.ok(Math.abs(Number(p.get("w1x")) - (3 + step)) < 0.006, `w1x=${p.get("w1x")}, step ${step}`);
    assert.equal(Number(p.get("w1y")), 2);
    assert.match(await live(page), /^Waypoint 1 at \(3\.\d\d, 2\.00\) m\.$/);
    // The Move form shows the chosen waypoint and its new x.
    assert.equal(await page.inputValue("article.exp:not([hidden]) #move-handle"), "w1");
    assert.ok(Math.abs(Number(await page.inputValue("article.exp:not([hidden]) #move-x")) - (3 + step)) < 0.006);
    // The next one; Shift moves it a tenth of a step.
    await press(page, "]");
    assert.equal(await live(page), "Chosen: Waypoint 2 at (6.00, 4.00) m.");
    await screenshot(page, "a11y-diffdrive-focus-ring");
    await page.keyboard.press("Shift+ArrowUp");
    const q = await linkParams(page);
    assert.ok(Math.abs(Number(q.get("w2y")) - (4 + step / 10)) < 0.006, `w2y=${q.get("w2y")}`);
    assert.equal(Number(q.get("w1y")), 2, "waypoint 1 stays");
    // Escape lets go: the arrows nudge as before (no chosen point announced).
    await press(page, "Escape");
    assert.equal(await live(page), "No point chosen.");
  }));

test("astar: the start and the goal move one cell per arrow key", () =>
  withPage(lab, { clock: true }, async (page) => {
    await open(lab, page, "#/astar/simulation");
    const before = await linkParams(page);
    const sx = Number(before.get("sx") ?? 3);
    await page.focus(CANVAS);
    await press(page, "]");
    assert.match(await live(page), /^Chosen: Start at /);
    await press(page, "ArrowRight");
    const after = await linkParams(page);
    assert.equal(Number(after.get("sx")), sx + 1, `sx ${sx} → ${after.get("sx")}`);
    await press(page, "]");
    assert.match(await live(page), /^Chosen: Goal at /);
    const gy = Number(after.get("gy"));
    await press(page, "ArrowDown");
    // World y points up, rows count down: one row further down the grid.
    assert.equal(Number((await linkParams(page)).get("gy")), gy + 1);
  }));

test("ik: the target moves by keyboard and by typed coordinates", () =>
  withPage(lab, { clock: true }, async (page) => {
    await open(lab, page, "#/ik/simulation?tx=1.1&ty=0.9");
    await page.focus(CANVAS);
    await press(page, "]");
    assert.equal(await live(page), "Chosen: Target at (1.10, 0.90) m.");
    const step = await keyboardStep(page);
    await press(page, "ArrowLeft");
    const p = await linkParams(page);
    assert.ok(Math.abs(Number(p.get("tx")) - (1.1 - step)) < 0.006, `tx=${p.get("tx")}`);
    // Typed: pick the point, type x and y, Move.
    await page.selectOption("article.exp:not([hidden]) #move-handle", "target");
    await page.fill("article.exp:not([hidden]) #move-x", "1.2");
    await page.fill("article.exp:not([hidden]) #move-y", "0.5 m");
    await page.click("article.exp:not([hidden]) .sim-move button[type=submit]");
    const q = await linkParams(page);
    assert.equal(Number(q.get("tx")), 1.2);
    assert.equal(Number(q.get("ty")), 0.5);
    // Something unreadable: a message, the target stays.
    await page.fill("article.exp:not([hidden]) #move-x", "abc");
    await page.click("article.exp:not([hidden]) .sim-move button[type=submit]");
    assert.match(await page.textContent("article.exp:not([hidden]) .sim-message"), /Could not read that/);
    assert.equal(Number((await linkParams(page)).get("tx")), 1.2);
  }));

// Issue 23 §3: "Move a point" offered "Setpoint y" in a one-dimensional
// experiment. The setpoint moves along the track only: no y box, no y in what
// is said, and ↑ ↓ leave it where it is.
test("pid: the setpoint moves along x only, the Move form offers no y", () =>
  withPage(lab, { clock: true }, async (page) => {
    await open(lab, page, "#/pid/simulation?r=0.5");
    const form = "article.exp:not([hidden]) .sim-move";
    assert.equal(await page.inputValue(`${form} #move-handle`), "setpoint");
    assert.equal(await page.isVisible(`${form} #move-x`), true);
    assert.equal(await page.isVisible(`${form} #move-y`), false);
    await page.focus(CANVAS);
    await press(page, "]");
    assert.equal(await live(page), "Chosen: Setpoint at x = 0.50 m.");
    await press(page, "ArrowUp");
    assert.equal(Number((await linkParams(page)).get("r")), 0.5);
    await page.fill(`${form} #move-x`, "1.2");
    await page.click(`${form} button[type=submit]`);
    assert.equal(Number((await linkParams(page)).get("r")), 1.2);
    assert.equal(await live(page), "Setpoint at x = 1.20 m.");
    assert.equal((await page.textContent("article.exp:not([hidden]) .sim-message") || "").trim(), "");
  }));

test("potential: an obstacle moves by keyboard", () =>
  withPage(lab, { clock: true }, async (page) => {
    await open(lab, page, "#/potential/simulation");
    const before = await linkParams(page);
    await page.focus(CANVAS);
    await press(page, "]");
    assert.match(await live(page), /^Chosen: Start at /);
    await press(page, "]");
    const m = (await live(page)).match(/^Chosen: Obstacle 1 at \(([\d.]+), ([\d.]+)\) m\.$/);
    assert.ok(m, await live(page));
    const step = await keyboardStep(page);
    await press(page, "ArrowUp");
    const p = await linkParams(page);
    assert.ok(
      Math.abs(Number(p.get("o1y")) - (Number(m[2]) + step)) < 0.006,
      `o1y ${m[2]} → ${p.get("o1y")} (step ${step}; before ${before.get("o1y")})`,
    );
    assert.ok(Math.abs(Number(p.get("o1x")) - Number(m[1])) < 0.006);
  }));

test("Describe: the button and D announce the scene; the end of a run does too", () =>
  withPage(lab, { clock: true }, async (page) => {
    await open(lab, page, "#/diffdrive/simulation");
    await page.click("article.exp:not([hidden]) [data-a11y=describe]");
    assert.equal(
      await live(page),
      "Robot at (4.00, 3.00) m heading 0.0°, no waypoints yet; idle: click to drop a goal.",
    );
    assert.equal(await page.getAttribute(LIVE, "aria-live"), "polite");
    await page.focus(CANVAS);
    await press(page, "d");
    assert.match(await live(page), /^Robot at \(4\.00, 3\.00\) m heading 0\.0°/);
    // The IK arm moving to a linked target: once it arrives the run has
    // ended and the description is read.
    await open(lab, page, "#/ik/simulation?tx=1.1&ty=0.9");
    await runUntil(
      page,
      (sel) => document.querySelector(sel)?.textContent.startsWith("Target at (1.10, 0.90) m: in reach. Arm at"),
      LIVE,
    );
    // Arrived: the tip on the target, the other branch's ghost and the reach circles.
    assert.match(await live(page), /tip at \(1\.10, 0\.90\) m\. 1 ghost arm shows the other branch, .* inner radius 0\.300 m\.$/);
  }));

test("? opens the keyboard help; Escape closes it and focus goes back; not while typing", () =>
  withPage(lab, { clock: true }, async (page) => {
    await open(lab, page, "#/pid/simulation");
    // Typing a question mark into a number box is just typing.
    const box = "article.exp:not([hidden]) .sim-controls input[type=text]";
    await page.focus(box);
    await page.keyboard.press("?");
    assert.equal(await page.$("dialog#kbd-help[open]"), null);
    await page.focus(CANVAS);
    await page.keyboard.press("?");
    const dialog = page.locator("dialog#kbd-help[open]");
    await dialog.waitFor();
    const text = await dialog.textContent();
    assert.match(text, /Keyboard shortcuts/);
    assert.match(text, /Play or pause/, "pid is animated: the time keys are listed");
    assert.match(text, /Choose the previous or next point/);
    assert.match(text, /This experiment:/);
    await screenshot(page, "a11y-help-desktop");
    await page.keyboard.press("Escape");
    await page.waitForSelector("dialog#kbd-help[open]", { state: "detached" });
    assert.ok(await page.evaluate(() => document.activeElement?.classList.contains("sim-canvas")));
  }));

test("the help fits a phone", () =>
  withPage(lab, { viewport: PHONE, colorScheme: "dark", clock: true }, async (page) => {
    await open(lab, page, "#/astar/simulation");
    await page.focus(CANVAS);
    await page.keyboard.press("?");
    await page.waitForSelector("dialog#kbd-help[open]");
    const box = await page.locator("dialog#kbd-help").boundingBox();
    assert.ok(box.width <= PHONE.width, `dialog ${box.width} px wide`);
    await screenshot(page, "a11y-help-phone-dark");
  }));

/** How many canvas pixels differ from its background colour (the top-left pixel). */
function inkedPixels(page) {
  return page.evaluate((sel) => {
    const c = document.querySelector(sel);
    const d = c.getContext("2d").getImageData(0, 0, c.width, c.height).data;
    const [r, g, b] = d;
    let n = 0;
    for (let i = 0; i < d.length; i += 4) {
      if (Math.abs(d[i] - r) + Math.abs(d[i + 1] - g) + Math.abs(d[i + 2] - b) > 60) n++;
    }
    return { n, total: d.length / 4, bg: [r, g, b] };
  }, CANVAS);
}

for (const [name, media, scheme] of [
  ["forced colours, light", { forcedColors: "active" }, "light"],
  ["forced colours, dark", { forcedColors: "active" }, "dark"],
  ["more contrast, light", { contrast: "more" }, "light"],
  ["more contrast, dark", { contrast: "more" }, "dark"],
]) {
  test(`${name}: the scene is drawn, not blank`, () =>
    withPage(lab, { colorScheme: scheme, clock: true }, async (page) => {
      await page.emulateMedia({ ...media, colorScheme: scheme });
      for (const [id, hash] of [
        ["diffdrive", "#/diffdrive/simulation?w1x=3&w1y=2&w2x=6&w2y=4&run=0"],
        ["astar", "#/astar/simulation"],
      ]) {
        await open(lab, page, hash);
        await page.focus(CANVAS);
        await press(page, "]");
        await settle(page);
        const ink = await inkedPixels(page);
        assert.ok(ink.n > ink.total * 0.005, `${id}: ${ink.n} of ${ink.total} pixels drawn on ${ink.bg}`);
        await screenshot(page, `a11y-${id}-${name.replace(/[ ,]+/g, "-")}`);
      }
    }));
}
