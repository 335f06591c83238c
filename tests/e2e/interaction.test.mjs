// Direct manipulation on the canvas (mouse and touch) and the quiz.

import { test } from "node:test";
import assert from "node:assert/strict";
import { experimentIds, open, readouts, runUntil, settle, until, useLab, waitReady, withPage } from "./helpers.mjs";

const lab = useLab();

/** Canvas box and two points inside it to drag between. */
async function dragPath(page) {
  const canvas = page.locator('article.exp:not([hidden]) [data-panel="simulation"] canvas.sim-canvas');
  await canvas.scrollIntoViewIfNeeded();
  const box = await canvas.boundingBox();
  assert.ok(box && box.width > 50 && box.height > 50, "the canvas has a usable size");
  return {
    from: { x: box.x + box.width * 0.75, y: box.y + box.height * 0.4 },
    to: { x: box.x + box.width * 0.3, y: box.y + box.height * 0.25 },
  };
}

/**
 * Runs page time until the tip's readouts leave `before` (a drag is a stream:
 * its text follows at the pace of a run, 250 ms of page time), then checks.
 */
async function assertTipMovesFrom(page, before) {
  await runUntil(
    page,
    (b) => ["x", "y"].some((k) => document.querySelector(`article.exp:not([hidden]) [data-readout="${k}"]`).textContent.trim() !== b[k]),
    before,
    { maxMs: 2000, what: "the tip's readouts to change" },
  ).catch(() => {});
  assertTipMoved(before, await readouts(page));
}

function assertTipMoved(before, after) {
  assert.ok(
    before.x !== after.x || before.y !== after.y,
    `tip readouts changed: ${JSON.stringify(before)} -> ${JSON.stringify(after)}`,
  );
}

/** Records the pointerType of every pointerdown the page sees. */
const recordPointerTypes = (page) =>
  page.evaluate(() => {
    window.__pointerTypes = [];
    addEventListener("pointerdown", (e) => window.__pointerTypes.push(e.pointerType), true);
  });

test("dragging on the fk canvas with a mouse moves the arm's tip", () =>
  withPage(lab, { clock: true }, async (page) => {
    await open(lab, page, "#/fk/simulation");
    await recordPointerTypes(page);
    const { from, to } = await dragPath(page);
    const before = await readouts(page);
    await page.mouse.move(from.x, from.y);
    await page.mouse.down();
    for (let i = 1; i <= 8; i++) {
      await page.mouse.move(from.x + ((to.x - from.x) * i) / 8, from.y + ((to.y - from.y) * i) / 8);
    }
    await page.mouse.up();
    await assertTipMovesFrom(page, before);
    assert.deepEqual(await page.evaluate(() => window.__pointerTypes), ["mouse"]);
  }));

test("dragging on the fk canvas with a finger (touch) moves the arm's tip", () =>
  withPage(lab, { hasTouch: true, viewport: { width: 412, height: 900 }, clock: true }, async (page, context) => {
    await open(lab, page, "#/fk/simulation");
    await recordPointerTypes(page);
    const { from, to } = await dragPath(page);
    const before = await readouts(page);
    // Real touch input through the DevTools protocol: the browser turns it
    // into pointer events with pointerType "touch" (and applies touch-action).
    const cdp = await context.newCDPSession(page);
    const touch = (type, p) =>
      cdp.send("Input.dispatchTouchEvent", {
        type,
        touchPoints: p ? [{ x: Math.round(p.x), y: Math.round(p.y), id: 1 }] : [],
      });
    await touch("touchStart", from);
    for (let i = 1; i <= 8; i++) {
      await touch("touchMove", {
        x: from.x + ((to.x - from.x) * i) / 8,
        y: from.y + ((to.y - from.y) * i) / 8,
      });
    }
    await touch("touchEnd");
    await assertTipMovesFrom(page, before);
    assert.deepEqual(await page.evaluate(() => window.__pointerTypes), ["touch"]);
  }));

test("quiz: submitting with no answers scores 0 / N, and a new attempt draws new questions", async (t) => {
  for (const id of await experimentIds(lab)) {
    await t.test(`experiment ${id}`, () =>
      withPage(lab, { clock: true }, async (page) => {
        await open(lab, page, `#/${id}/quiz`);
        const questions = page.locator("form.quiz .quiz-q");
        const n = await questions.count();
        assert.ok(n > 0, "the quiz has questions");
        const prompts = await questions.evaluateAll((qs) => qs.map((q) => q.innerText));
        // No worked answer is in the page before submission.
        assert.equal(await page.locator("form.quiz .quiz-explanation:not(:empty)").count(), 0);

        // Unanswered questions ask for confirmation first.
        await page.click("form.quiz button[type=submit]");
        const confirm = page.locator("form.quiz .quiz-confirm");
        await confirm.waitFor({ state: "visible" });
        assert.match(await confirm.innerText(), new RegExp(`${n} questions have no answer`));
        assert.ok(await page.locator(".quiz-score").isHidden(), "not graded yet");
        await page.click("form.quiz button[type=submit]");
        const score = page.locator(".quiz-score");
        await score.waitFor({ state: "visible" });
        assert.match(await score.innerText(), new RegExp(`\\b0\\s*/\\s*${n}\\b`));
        for (let i = 0; i < n; i++) {
          const q = questions.nth(i);
          const cls = (await q.getAttribute("class")).split(/\s+/);
          assert.ok(cls.includes("wrong") && !cls.includes("right"), `question ${i + 1} marked wrong`);
          assert.ok(await q.locator(".quiz-explanation").isVisible(), `question ${i + 1} explained`);
        }

        // The score sits at the top of the form, above the questions.
        const [scoreTop, firstTop] = await page.evaluate(() => [
          document.querySelector("form.quiz .quiz-score").getBoundingClientRect().top,
          document.querySelector("form.quiz .quiz-q").getBoundingClientRect().top,
        ]);
        assert.ok(scoreTop < firstTop, "score above the questions");
        const seed = await page.locator("form.quiz .quiz-seed").innerText();
        assert.match(await page.evaluate(() => location.hash), new RegExp(`quiz=${seed}`), "the link names the attempt");

        await page.click("form.quiz button.quiz-new");
        await settle(page);
        const fresh = await page
          .locator("form.quiz .quiz-q")
          .evaluateAll((qs) => qs.map((q) => q.innerText));
        assert.notDeepEqual(fresh, prompts, "a new attempt changes at least one question");
      }),
    );
  }
});

test("quiz: an instructor's link fixes the attempt, and answers survive a reload", () =>
  withPage(lab, { clock: true }, async (page) => {
    await open(lab, page, "#/ik/quiz?quiz=123");
    assert.equal(await page.locator("form.quiz .quiz-seed").innerText(), "123");
    const prompts = await page.locator("form.quiz .quiz-q").evaluateAll((qs) => qs.map((q) => q.innerText));
    // Answer the first numeric question, then reload the page.
    const field = page.locator("form.quiz .quiz-numeric input").first();
    await field.fill("0.5");
    await field.dispatchEvent("input");
    await page.reload();
    await waitReady(page);
    assert.equal(await page.locator("form.quiz .quiz-seed").innerText(), "123");
    assert.equal(await page.locator("form.quiz .quiz-numeric input").first().inputValue(), "0.5");
    const again = await page.locator("form.quiz .quiz-q").evaluateAll((qs) => qs.map((q) => q.innerText));
    assert.deepEqual(again, prompts, "the same numbers for the whole class");
  }));

test("a number field says what it read: '1,5' is refused with a reason, '0.5 rad' converts to degrees", () =>
  withPage(lab, { clock: true }, async (page) => {
    await open(lab, page, "#/fk/simulation?t1=35");
    const box = page.locator("article.exp:not([hidden]) input[type=text][data-param=t1]");
    await box.fill("1,5");
    await box.press("Enter");
    const message = page.locator("article.exp:not([hidden]) .sim-message");
    await message.waitFor({ state: "visible" });
    assert.match(await message.innerText(), /comma only separates thousands/);
    assert.equal(await page.locator("article.exp:not([hidden]) input[type=range][data-param=t1]").inputValue(), "35", "kept");
    await box.fill("0.5 rad");
    await box.press("Enter");
    await until(page, () => /Read “0\.5 rad” as 28\.6/.test(document.querySelector("article.exp:not([hidden]) .sim-message").textContent));
    // The link keeps the value exactly as read (0.5 rad = 28.64788975654116°).
    await until(page, () => /t1=28\.647889756541/.test(location.hash));
  }));

test("the caption follows the input in use: a touch on the canvas shows the touch hint", () =>
  withPage(lab, { hasTouch: true, viewport: { width: 390, height: 844 }, clock: true }, async (page) => {
    await open(lab, page, "#/astar/simulation");
    const caption = page.locator("article.exp:not([hidden]) .sim-caption");
    const canvas = page.locator("article.exp:not([hidden]) canvas.sim-canvas");
    const box = await canvas.boundingBox();
    await page.touchscreen.tap(box.x + box.width * 0.5, box.y + box.height * 0.5);
    await until(page, () => document.querySelector("article.exp:not([hidden]) .sim-caption").dataset.input === "touch");
    assert.ok((await caption.innerText()).trim().length > 0);
    await page.mouse.click(box.x + box.width * 0.5, box.y + box.height * 0.5);
    await until(page, () => document.querySelector("article.exp:not([hidden]) .sim-caption").dataset.input === "mouse");
  }));
