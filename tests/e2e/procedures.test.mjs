// Issue 52: every experiment's Procedure, played as a student on the built
// site from the same data as the native runner (crates/labcore/tests/
// procedures/): each step's `play` in assets/<id>.json, in order from a
// freshly opened page, on a stopped clock the test steps (never the wall
// clock), at 1280×800 and at a phone size with touch. Controls are found by
// their visible labels, readouts and the status are read as displayed.
//
// This runner knows the verbs a student uses through the panel and the time
// bar (set, press, wait, until, note, see, status, time); the canvas verbs
// (click, drag, key, move, scrub) and the plot, scene and table claims are
// the native runner's only, for now: on each page the Procedure is played up
// to the first step that needs one of those, and the test says how far it got.

import { test } from "node:test";
import assert from "node:assert/strict";
import { readFileSync } from "node:fs";
import { dirname, join, resolve } from "node:path";
import { fileURLToPath } from "node:url";
import { DESKTOP, PHONE, builtExperimentIds, open, runFor, runUntil, settle, useLab, withPage } from "./helpers.mjs";

const lab = useLab();
const ROOT = resolve(dirname(fileURLToPath(import.meta.url)), "..", "..");
const ART = "article.exp:not([hidden])";
const FRAME_MS = 1000 / 60;
/** The most page time a wait may take: Run to end's cap, ten simulated minutes. */
const MAX_MS = 10 * 60 * 1000;

/** The verbs this runner plays, by the key that names an item (as the native runner's VERBS). */
const VERBS = ["set", "press", "wait", "until", "note", "see", "status", "time"];
const ALL_VERBS = [
  "set", "press", "click", "drag", "move", "key", "wait", "until", "scrub", "scrub_back_until",
  "scrub_to_largest", "reopen", "note", "see", "watch", "status", "notice", "time", "plot",
  "table", "scene",
];
const verbOf = (item) => ALL_VERBS.find((v) => v in item);

/** The steps of experiment `id`'s Procedure that this runner can play, in order from the first. */
function playable(id) {
  const steps = JSON.parse(readFileSync(join(ROOT, "assets", `${id}.json`), "utf8")).procedure;
  const reach = steps.findIndex((s) => !s.play.every((item) => VERBS.includes(verbOf(item))));
  return { steps, reach: reach === -1 ? steps.length : reach };
}

/** The number a readout's text shows, as the native runner reads it (`2.2 × 10⁻⁸ m` → 2.2e-8). */
function shownNumber(text) {
  const t = text.trim().replace(/\u2212/g, "-");
  const m = t.match(/^-?\d+(\.\d+)?/);
  if (!m) return null;
  const sup = { "⁻": "-", "⁰": "0", "¹": "1", "²": "2", "³": "3", "⁴": "4", "⁵": "5", "⁶": "6", "⁷": "7", "⁸": "8", "⁹": "9" };
  const e = t.slice(m[0].length).match(/^ × 10([⁻⁰¹²³⁴⁵⁶⁷⁸⁹]+)/);
  const exponent = e ? Number([...e[1]].map((c) => sup[c]).join("")) : 0;
  return Number(m[0]) * 10 ** exponent;
}

/** What the page shows for `label`: a readout's text, else a control's value as its box shows it. */
function shown(page, label) {
  return page.evaluate(
    ([art, label]) => {
      for (const ro of document.querySelectorAll(`${art} .readout`)) {
        if (ro.querySelector("dt")?.textContent.trim() === label) return ro.querySelector("dd").textContent.trim();
      }
      for (const ctl of document.querySelectorAll(`${art} [data-ctl]`)) {
        const name = ctl.querySelector(":scope > label, :scope > legend")?.textContent.trim();
        if (name !== label) continue;
        const checked = ctl.querySelector("input[type=radio]:checked");
        if (checked) return checked.parentElement.textContent.trim();
        const select = ctl.querySelector("select");
        if (select) return select.selectedOptions[0]?.textContent.trim() ?? "";
        const box = ctl.querySelector("input[type=text]");
        const unit = ctl.querySelector(".unit")?.textContent ?? "";
        return `${box.value} ${unit}`.trim();
      }
      return null;
    },
    [ART, label],
  );
}

const statusText = (page) => page.locator(`${ART} .sim-status`).first().textContent().then((t) => t.trim());

/** One student at one page: the values they noted down. */
class Student {
  constructor(page, touch) {
    this.page = page;
    this.notes = new Map();
    // On a touch screen the page words a status for a finger ("click"
    // becomes "tap", labcore's `for_touch`): so does the claim.
    this.words = (text) => (touch ? text.replaceAll("click", "tap") : text);
  }

  async reference(r) {
    if (typeof r === "number") return [r, `against ${r}`];
    if (this.notes.has(r)) return [this.notes.get(r), `noted as ${r}`];
    const text = await shown(this.page, r);
    if (text === null) throw new Error(`no readout or control “${r}”`);
    return [shownNumber(text), `${r} = ${text}`];
  }

  /** The claim of `o` about `n` (shown as `said`), as the native runner's `compare`. */
  async compare(o, n, said) {
    const within = (o.within ?? 1e-9 * Math.abs(n)) + 1e-9;
    if ("times" in o) {
      const [base, how] = await this.reference(o.times);
      assert.ok(Math.abs(n / base - o.is) <= within, `${said} (${how}; ratio ${n / base})`);
      return;
    }
    if ("is" in o) return assert.ok(Math.abs(n - o.is) <= within, said);
    if ("between" in o) return assert.ok(o.between[0] <= n && n <= o.between[1], said);
    for (const [key, larger] of [["above", true], ["larger_than", true], ["below", false], ["smaller_than", false]]) {
      if (key in o) {
        const [base, how] = await this.reference(o[key]);
        return assert.ok(larger ? n > base : n < base, `${said} (${how})`);
      }
    }
    if ("about" in o) {
      const [base, how] = await this.reference(o.about);
      return assert.ok(Math.abs(n - base) <= within, `${said} (${how})`);
    }
    if ("opposite_sign_to" in o) {
      const [base, how] = await this.reference(o.opposite_sign_to);
      return assert.ok(n * base < 0, `${said} (${how})`);
    }
    throw new Error(`no claim in ${JSON.stringify(o)}`);
  }

  async set(label, to) {
    const { page } = this;
    const key = await page.evaluate(
      ([art, label]) =>
        [...document.querySelectorAll(`${art} [data-ctl]`)].find(
          (c) => c.querySelector(":scope > label, :scope > legend")?.textContent.trim() === label,
        )?.dataset.ctl ?? null,
      [ART, label],
    );
    assert.ok(key, `no control labelled “${label}”`);
    const ctl = page.locator(`${ART} [data-ctl="${key}"]`);
    // A control in a collapsed group opens with its group.
    const group = ctl.locator("xpath=ancestor::details[not(@open)]");
    if (await group.count()) await group.first().locator("summary").click();
    if (typeof to === "string") {
      if (await ctl.locator("select").count()) await ctl.locator("select").selectOption({ label: to });
      else await ctl.locator("label", { hasText: to }).first().click();
    } else {
      const box = ctl.locator("input[type=text]");
      await box.fill(String(to));
      await box.press("Enter");
    }
    await settle(page);
  }

  async press(label) {
    const { page } = this;
    const times = { Pause: "play", Play: "play", Step: "step", Back: "back", "Run to end": "end", Reset: "reset", Mark: "mark" };
    const action = page.locator(`${ART} button[data-action]`, { hasText: label });
    const matches = await action.evaluateAll((bs, l) => bs.filter((b) => b.textContent.trim() === l).length, label);
    if (matches > 0) {
      await action.filter({ hasText: label }).first().click();
    } else {
      assert.ok(label in times, `no button labelled “${label}”`);
      const clock = await page.locator(`${ART} .timebar`).getAttribute("data-clock");
      // Pause and Play are one button: press it only when it offers the other.
      if ((label === "Pause" && clock === "paused") || (label === "Play" && clock !== "paused")) return;
      await page.locator(`${ART} button[data-time=${times[label]}]`).click();
    }
    await settle(page);
  }

  /** Runs page time until nothing moves or the run has ended (or a page without time). */
  async rest() {
    await runUntil(
      this.page,
      (art) => {
        const bar = document.querySelector(`${art} .timebar`);
        return !bar || ["held", "ended"].includes(bar.dataset.clock);
      },
      ART,
      { sliceMs: 100, maxMs: MAX_MS, what: "rest" },
    );
  }

  async item(o) {
    const { page } = this;
    const verb = verbOf(o);
    switch (verb) {
      case "set":
        return this.set(o.set, o.to);
      case "press":
        for (let k = 0; k < (o.times ?? 1); k++) await this.press(o.press);
        return;
      case "wait":
        if (o.wait === "rest") return this.rest();
        return runFor(page, Math.round(o.wait / (1 / 60)) * FRAME_MS);
      case "until":
        return runUntil(
          page,
          ([art, text, label]) => {
            if (!label) return document.querySelector(`${art} .sim-status`)?.textContent.includes(text);
            const ro = [...document.querySelectorAll(`${art} .readout`)].find((r) => r.querySelector("dt")?.textContent.trim() === label);
            return ro?.querySelector("dd").textContent.includes(text);
          },
          [ART, o.readout ? o.until : this.words(o.until), o.readout ?? null],
          { sliceMs: FRAME_MS, maxMs: MAX_MS, what: `“${o.until}”` },
        );
      case "note": {
        const text = await shown(page, o.note);
        assert.ok(text !== null, `no readout “${o.note}”`);
        this.notes.set(o.as ?? o.note, shownNumber(text));
        return;
      }
      case "see": {
        const text = await shown(page, o.see);
        assert.ok(text !== null, `no readout or control “${o.see}”`);
        if ("says" in o) return assert.ok(text.includes(o.says), `${o.see} = ${text}`);
        return this.compare(o, shownNumber(text), `${o.see} = ${text}`);
      }
      case "status": {
        const text = await statusText(page);
        assert.equal(text.includes(this.words(o.status)), !o.not, `the status “${text}”`);
        return;
      }
      case "time": {
        const text = await page.locator(`${ART} .tb-time`).textContent();
        return this.compare(o, shownNumber(text.replace(/^t = /, "")), text);
      }
      default:
        throw new Error(`the browser runner does not play “${verb}”`);
    }
  }
}

for (const id of builtExperimentIds()) {
  const { steps, reach } = playable(id);
  for (const [name, options] of [
    ["1280×800", { viewport: DESKTOP }],
    ["phone, touch", { viewport: PHONE, hasTouch: true, isMobile: true }],
  ]) {
    test(`${id}: the Procedure played as a student at ${name}, steps 1–${reach} of ${steps.length}`, { skip: reach === 0 && "its first step needs a canvas verb" }, () =>
      withPage(lab, { ...options, clock: true }, async (page) => {
        await open(lab, page, `#/${id}/simulation`);
        const student = new Student(page, Boolean(options.hasTouch));
        for (const [k, step] of steps.slice(0, reach).entries()) {
          for (const item of step.play) {
            try {
              await student.item(item);
            } catch (e) {
              throw new Error(`${id} step ${k + 1}: “${step.text}”\n    claim: ${JSON.stringify(item)}\n    the page showed: ${e.message}`);
            }
          }
        }
      }));
  }
}
