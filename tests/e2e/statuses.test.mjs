// Issue 23 §3: statuses, hints and labels that say what is happening, in
// the words of the input in use; one system for one point; the quiz's
// button after a submit.

import { test } from "node:test";
import assert from "node:assert/strict";
import { experimentIds, open, settle, until, useLab, withPage } from "./helpers.mjs";

const lab = useLab();
const SIM = 'article.exp:not([hidden]) [data-panel="simulation"]';
const PHONE_TALL = { width: 390, height: 844 };

/** Words a phone has no use for: keys, clicks and modifiers. */
const KEY_WORDS = [/click/i, /\bshift\b/i, /\bctrl\b/i, /arrow key/i, /[←→↑↓]/, /\[\s*\]/, /\bkeyboard\b/i, /canvas has focus/i];

/** Touches the caption (no effect on the experiment) so the page words everything for touch. */
async function useTouch(page) {
  const caption = page.locator(`${SIM} .sim-caption`);
  await caption.scrollIntoViewIfNeeded();
  const box = await caption.boundingBox();
  await page.touchscreen.tap(box.x + 4, box.y + box.height / 2);
  await until(page, 
    (sel) => document.querySelector(`${sel} .sim-caption`).dataset.input === "touch",
    SIM,
  );
}

/** Every text the Simulation tab shows now, as a reader sees it. */
const shownText = (page) => page.locator(SIM).innerText();

function assertNoKeyWords(text, where) {
  for (const word of KEY_WORDS) {
    const hit = text.split("\n").find((line) => word.test(line));
    assert.equal(hit, undefined, `${where}: a phone shows “${hit}” (${word})`);
  }
}

test("phone hints: on a touch screen no text of the Simulation tab names a key, a click or a modifier, before or after each action", async (t) => {
  for (const id of await experimentIds(lab)) {
    await t.test(`experiment ${id}`, () =>
      withPage(lab, { hasTouch: true, viewport: PHONE_TALL, clock: true }, async (page) => {
        await open(lab, page, `#/${id}/simulation`);
        await useTouch(page);
        assertNoKeyWords(await shownText(page), `${id} at load`);
        const actions = page.locator(`${SIM} button[data-action]`);
        const n = await actions.count();
        for (let i = 0; i < n; i++) {
          const button = actions.nth(i);
          const key = await button.getAttribute("data-action");
          // A button with nothing to act on is hidden ("Hide basin map"
          // without a map): no finger reaches it.
          if (!(await button.isVisible())) continue;
          // A tap on the button itself (Playwright checks that the finger
          // lands on it, not on the sticky header above a scrolled page).
          await button.tap();
          await settle(page);
          assertNoKeyWords(await shownText(page), `${id} after ${key}`);
        }
      }),
    );
  }
});

test("diffdrive: on a phone the badge says tap to drop a goal, not click", () =>
  withPage(lab, { hasTouch: true, viewport: PHONE_TALL, clock: true }, async (page) => {
    await open(lab, page, "#/diffdrive/simulation");
    await useTouch(page);
    await until(page, (sel) => /^idle: tap to drop a goal$/.test(document.querySelector(`${sel} .sim-status`).textContent), SIM);
  }));

test("diffdrive: the Waypoints heading counts waypoints, not input fields", () =>
  withPage(lab, { clock: true }, async (page) => {
    await open(lab, page, "#/diffdrive/simulation?w1x=2&w1y=2&w2x=6&w2y=4");
    const heading = page.locator(`${SIM} details.ctl-group summary`);
    await until(page, (sel) => /^Waypoints \(2\)$/.test(document.querySelector(`${sel} details.ctl-group summary`).textContent.trim()), SIM);
    await page.locator(`${SIM} button[data-action=clear]`).click();
    await until(page, (sel) => /^Waypoints \(0\)$/.test(document.querySelector(`${sel} details.ctl-group summary`).textContent.trim()), SIM);
    assert.match((await heading.innerText()).trim(), /^Waypoints \(0\)$/);
  }));

/** The Move a point form's labels and values. */
const moveForm = (page) =>
  page.evaluate((sel) => {
    const form = document.querySelector(`${sel} .sim-move`);
    const label = (axis) => form.querySelector(`label[for=move-${axis}]`).textContent.trim();
    const value = (axis) => form.querySelector(`input[data-move=${axis}]`).value;
    return { point: form.querySelector("select").value, labels: [label("x"), label("y")], values: [value("x"), value("y")] };
  }, SIM);

test("astar: the start is one point in one system: Move a point shows and takes its column and row, as the controls do", () =>
  withPage(lab, { clock: true }, async (page) => {
    await open(lab, page, "#/astar/simulation");
    const control = (key) => page.locator(`${SIM} input[data-param=${key}]`).inputValue();
    const shown = await moveForm(page);
    assert.equal(shown.point, "start");
    assert.deepEqual(shown.labels, ["column", "row"]);
    assert.deepEqual(shown.values, [await control("sx"), await control("sy")]);
    assert.deepEqual(shown.values, ["3", "12"]);
    await page.fill(`${SIM} input[data-move=x]`, "5");
    await page.fill(`${SIM} input[data-move=y]`, "10");
    await page.click(`${SIM} .sim-move button[type=submit]`);
    await until(page, (sel) => document.querySelector(`${sel} input[data-param=sx]`).value === "5", SIM);
    assert.equal(await control("sy"), "10");
    assert.deepEqual((await moveForm(page)).values, ["5", "10"]);
    assert.equal(await page.locator(`${SIM} .sim-message`).innerText(), "");
  }));

test("astar: a Move a point refused because the point is locked says that it is locked", () =>
  withPage(lab, { clock: true }, async (page) => {
    await open(lab, page, "#/astar/simulation?lock=sx,sy");
    await page.fill(`${SIM} input[data-move=x]`, "5");
    await page.fill(`${SIM} input[data-move=y]`, "10");
    await page.click(`${SIM} .sim-move button[type=submit]`);
    await until(page, (sel) => /locked/.test(document.querySelector(`${sel} .sim-message`).textContent), SIM);
    const message = await page.locator(`${SIM} .sim-message`).innerText();
    assert.match(message, /^Start .*is locked by your instructor/);
    assert.doesNotMatch(message, /could not go/);
    assert.equal(await page.locator(`${SIM} input[data-param=sx]`).inputValue(), "3");
  }));

test("quiz: “Submit anyway” goes once the quiz is submitted", () =>
  withPage(lab, { clock: true }, async (page) => {
    await open(lab, page, "#/fk/quiz");
    const submit = page.locator("form.quiz button[type=submit]");
    await submit.click();
    await page.locator("form.quiz .quiz-confirm").waitFor({ state: "visible" });
    assert.equal((await submit.innerText()).trim(), "Submit anyway");
    await submit.click();
    await page.locator("form.quiz .quiz-score").waitFor({ state: "visible" });
    await settle(page);
    assert.equal((await submit.innerText()).trim(), "Submitted");
    assert.ok(await submit.isDisabled());
  }));
