// Issue 52: every experiment's Procedure, played as a student on the built
// site from the same data as the native runner (crates/labcore/tests/
// procedures/): each step's `play` in assets/<id>.json, in order from a
// freshly opened page, on a stopped clock the test steps (never the wall
// clock), at 1280×800 and at a phone size with touch. Controls are found by
// their visible labels, readouts and the status are read as displayed;
// canvas verbs are real pointer, touch and key events on the canvas at the
// point the step names (mapped as the page maps it); the timeline is
// scrubbed with its slider; a plot's numbers are read from the CSV the page
// offers (or, for a kept run the CSV leaves out, from its text summary), a
// table's rows as shown, the scene from what the page says of it.
//
// Every verb of the native runner is played here. A claim about the scene
// is read where the page puts it into words, Describe (the button under the
// canvas, also a screen reader's): its `words` say where, `#` for the
// number.

import { test } from "node:test";
import assert from "node:assert/strict";
import { readFileSync } from "node:fs";
import { dirname, join, resolve } from "node:path";
import { fileURLToPath } from "node:url";
import { alongTheTimeline } from "./visit.mjs";
import { DESKTOP, PHONE, builtExperimentIds, open, runFor, runUntil, screenshot, settle, useLab, withPage, worldToPage } from "./helpers.mjs";
const ROOT = resolve(dirname(fileURLToPath(import.meta.url)), "..", "..");
const ART = "article.exp:not([hidden])";
const FRAME_MS = 1000 / 60;
const DT_S = 1 / 60;
/** The most page time a wait may take: Run to end's cap, ten simulated minutes. */
const MAX_MS = 10 * 60 * 1000;

/** The verbs, by the key that names an item (the native runner's VERBS, in its order). */
const VERBS = [
  "set", "press", "click", "drag", "move", "key", "wait", "until", "scrub", "scrub_back_until",
  "scrub_to_largest", "reopen", "note", "see", "watch", "status", "notice", "time", "plot",
  "table", "scene",
];
/** The keys of a claim about a number (the native runner's CLAIMS). */
const CLAIMS = ["is", "between", "above", "below", "larger_than", "smaller_than", "about", "times", "opposite_sign_to"];
const verbOf = (item) => VERBS.find((v) => v in item);

/**
 * The number Describe's `text` writes where a scene claim's `words` have
 * `#` (the words around it as written; "no" or "No" reads 0), at the first
 * place they fit: the native runner's `described_number`.
 */
export function describedNumber(text, words) {
  const at = words.indexOf("#");
  if (at < 0) return null;
  const [before, after] = [words.slice(0, at), words.slice(at + 1)];
  const t = text.replace(/\u2212/g, "-");
  for (let i = 0; i <= t.length; i++) {
    if (!t.startsWith(before, i)) continue;
    // A number starts here, not inside another one.
    if (before === "" && i > 0 && /[\d.,-]/.test(t[i - 1])) continue;
    const rest = t.slice(i + before.length);
    let n = null;
    let len = 0;
    if (rest.startsWith("no") || rest.startsWith("No")) [n, len] = [0, 2];
    else {
      const m = rest.match(/^-?[\d.,]*/)[0].replace(/[.,]+$/, "");
      const v = Number(m.replace(/,/g, ""));
      if (m !== "" && m !== "-" && Number.isFinite(v)) [n, len] = [v, m.length];
    }
    if (n !== null && rest.slice(len).startsWith(after)) return n;
  }
  return null;
}

/** The steps of experiment `id`'s Procedure. */
function procedure(id) {
  return JSON.parse(readFileSync(join(ROOT, "assets", `${id}.json`), "utf8")).procedure;
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

/** Splits one CSV row (RFC 4180 quoting). */
function csvCells(row) {
  const out = [];
  let cell = "";
  let quoted = false;
  for (let i = 0; i < row.length; i++) {
    const c = row[i];
    if (quoted) {
      if (c === '"' && row[i + 1] === '"') (cell += '"'), i++;
      else if (c === '"') quoted = false;
      else cell += c;
    } else if (c === '"') quoted = true;
    else if (c === ",") out.push(cell), (cell = "");
    else cell += c;
  }
  out.push(cell);
  return out;
}

/**
 * The series of a plot's CSV by label: `{ x, y }` arrays (the x column it
 * shares, or its own), as labcore's `Plot::to_csv` writes them.
 */
function csvSeries(text) {
  const lines = text.split("\r\n").filter((l) => l !== "");
  const head = csvCells(lines[0]);
  const rows = lines.slice(1).map(csvCells);
  const name = (h) => h.replace(/ \([^()]*\)$/, "");
  const col = (i) => rows.map((r) => r[i]).filter((v) => v !== "" && v !== undefined).map(Number);
  const series = [];
  // Each series with its own x has two columns, "<label> <x label>" then "<label>".
  const paired = head.length % 2 === 0 && head.every((h, i) => i % 2 === 1 || name(h).startsWith(`${name(head[i + 1])} `));
  if (paired) {
    for (let i = 0; i < head.length; i += 2) series.push({ label: name(head[i + 1]), x: col(i), y: col(i + 1) });
  } else {
    const x = col(0);
    for (let i = 1; i < head.length; i++) series.push({ label: name(head[i]), x, y: col(i) });
  }
  return series;
}

/** How much wider each swing about `level` is than the one before (the native runner's). */
function swingGrowth(y, level) {
  const halves = [];
  let current = 0;
  let side = 0;
  for (const v of y) {
    const d = v - level;
    if (d === 0) continue;
    if (side !== 0 && Math.sign(d) !== side) {
      halves.push(current);
      current = 0;
    }
    side = Math.sign(d);
    current = Math.max(current, Math.abs(d));
  }
  if (halves.length < 3) return null;
  const ratios = [];
  for (let i = 2; i < halves.length; i++) ratios.push(halves[i] / halves[i - 1]);
  ratios.sort((a, b) => a - b);
  return ratios[Math.floor(ratios.length / 2)];
}

/**
 * The whole CSS pixel nearest to a page point: the page reads a pointer's
 * place in whole pixels (`MouseEvent.clientX`), so that is where it lands.
 */
const px = (p) => ({ x: Math.round(p.x), y: Math.round(p.y) });

const share = (flags) => (flags.length ? (100 * flags.filter(Boolean).length) / flags.length : null);

/** One student at one page: the values they noted down. */
class Student {
  constructor(lab, page, touch, id) {
    this.lab = lab;
    this.page = page;
    this.touch = touch;
    this.id = id;
    this.notes = new Map();
    /** The slider's step at the student's last input: where the run shown began. */
    this.lastInput = 0;
    /** A pointer still pressed at the end of a drag (`hold`), released at the next input. */
    this.held = null;
    // On a touch screen the page words a status for a finger ("click"
    // becomes "tap", labcore's `for_touch`): so does the claim.
    this.words = (text) => (touch ? text.replaceAll("click", "tap") : text);
  }

  async reference(r) {
    if (typeof r === "number") return [r, `against ${r}`];
    if (this.notes.has(r)) {
      const [n, said] = this.notes.get(r);
      return [n, `noted as ${r}: ${said}`];
    }
    const text = await shown(this.page, r);
    if (text === null) throw new Error(`no readout or control “${r}”`);
    return [shownNumber(text), `${r} = ${text}`];
  }

  /** The claim of `o` about `n` (shown as `said`), as the native runner's `compare`. */
  async compare(o, n, said, precision = 0) {
    const within = (o.within ?? precision) + 1e-9;
    if ("times" in o) {
      const [base, how] = await this.reference(o.times);
      assert.ok(Math.abs(n / base - o.is) <= within, `${said} (${how}; ratio ${(n / base).toFixed(3)})`);
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

  /** A plot's, the scene's or a watched number: checked if the item claims something, noted with `as`. */
  async notedOrCompared(o, n, said) {
    if (CLAIMS.some((k) => k in o)) await this.compare(o, n, said, 0);
    if (o.as) this.notes.set(o.as, [n, said]);
  }

  /** The timeline slider's step now (0 on a page without time). */
  async sliderStep() {
    const v = await this.page.locator(`${ART} .tb-scrub`).evaluateAll((s) => (s[0] ? Number(s[0].value) : 0));
    return v;
  }

  /** Before a change by the student: the run shown begins here, and a held pointer lets go. */
  async input() {
    await this.release();
    this.lastInput = await this.sliderStep();
  }

  async set(label, to) {
    const { page } = this;
    await this.input();
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
      await this.input();
      await action.filter({ hasText: label }).first().click();
    } else {
      assert.ok(label in times, `no button labelled “${label}”`);
      const clock = await page.locator(`${ART} .timebar`).getAttribute("data-clock");
      // Pause and Play are one button: press it only when it offers the
      // other (an ended run offers Replay, never Pause: nothing to pause).
      if ((label === "Pause" && ["paused", "ended"].includes(clock)) || (label === "Play" && !["paused", "ended"].includes(clock))) return;
      if (label === "Reset") this.lastInput = 0;
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

  // ---- the canvas: a mouse at 1280×800, a finger on the phone ----

  async cdp() {
    this.session ??= await this.page.context().newCDPSession(this.page);
    return this.session;
  }

  /** A touch (CDP, as a finger: start, move, end) with Shift/Ctrl held on an attached keyboard. */
  async finger(type, p, mods = {}) {
    const cdp = await this.cdp();
    const modifiers = (mods.shift ? 8 : 0) | (mods.ctrl ? 2 : 0);
    await cdp.send("Input.dispatchTouchEvent", { type, modifiers, touchPoints: p ? [{ x: p.x, y: p.y, id: 1 }] : [] });
  }

  async pointerDown(p, mods = {}) {
    p = px(p);
    if (this.touch) return this.finger("touchStart", p, mods);
    const { mouse, keyboard } = this.page;
    await mouse.move(p.x, p.y);
    this.mouseAt = p;
    if (mods.shift) await keyboard.down("Shift");
    if (mods.ctrl) await keyboard.down("Control");
    await mouse.down();
  }

  async pointerMove(p) {
    p = px(p);
    if (this.touch) return this.finger("touchMove", p);
    await this.page.mouse.move(p.x, p.y);
    this.mouseAt = p;
  }

  async pointerUp(p, mods = {}) {
    p = px(p);
    if (this.touch) return this.finger("touchEnd", null, mods);
    const { mouse, keyboard } = this.page;
    // A click is a press and a release where it pressed: no move between
    // (a move with the button down is a drag, to the page as to the model).
    if (this.mouseAt?.x !== p.x || this.mouseAt?.y !== p.y) await mouse.move(p.x, p.y);
    this.mouseAt = p;
    await mouse.up();
    if (mods.ctrl) await keyboard.up("Control");
    if (mods.shift) await keyboard.up("Shift");
  }

  async release() {
    if (!this.held) return;
    const p = this.held;
    this.held = null;
    await this.pointerUp(p);
    await settle(this.page);
  }

  /**
   * After a stream of input (a drag, held keys) the page writes its text
   * at its pace, once the stream has been still for TEXT_INTERVAL_MS (250
   * ms, labweb's sim/mod.rs): the student reads it then.
   */
  async streamRead() {
    await runFor(this.page, 250 + 2 * FRAME_MS);
  }

  /** Where the handle labelled `label` is, in world coordinates: as the Move form shows it. */
  async handle(label) {
    const { page } = this;
    const form = page.locator(`${ART} form.sim-move`);
    const options = await form.locator("select[data-move=handle] option").allTextContents();
    assert.ok(options.includes(label), `no handle “${label}” (the handles: ${options.join(", ")})`);
    await form.locator("select[data-move=handle]").selectOption({ label });
    await settle(page);
    const names = await form.locator(".ctl-number label").allTextContents();
    const x = Number(await form.locator("input[data-move=x]").inputValue());
    const y = Number(await form.locator("input[data-move=y]").inputValue());
    // Choosing a point in the form chooses it for the arrow keys too: let go
    // on the canvas (Escape), as the form's help says.
    await page.locator(`${ART} canvas.sim-canvas`).focus();
    await page.keyboard.press("Escape");
    if (names[0] === "column") {
      // A grid cell's column and row (row 0 at the top): its centre.
      const rows = Number((await shown(page, "Grid")).match(/× (\d+)/)[1]);
      return [x + 0.5, rows - y - 0.5];
    }
    return [x, y];
  }

  async click([x, y], withKey) {
    await this.input();
    const mods = { shift: withKey === "shift", ctrl: withKey === "ctrl" };
    assert.ok(!withKey || mods.shift || mods.ctrl, `no key “${withKey}”`);
    const p = await worldToPage(this.page, x, y);
    await this.pointerDown(p, mods);
    await this.pointerUp(p, mods);
    await settle(this.page);
  }

  async drag(o) {
    await this.input();
    const from = typeof o.drag === "string" ? await this.handle(o.drag) : o.drag;
    const path = o.to ? [o.to] : o.through;
    assert.ok(path, "a drag goes `to` a point or `through` points");
    const start = await worldToPage(this.page, ...from);
    await this.pointerDown(start);
    let last = from;
    let end = start;
    for (const pos of path) {
      // The pointer moves in small steps, as a hand does (the native runner's 5 cm).
      const n = Math.max(1, Math.ceil(Math.hypot(pos[0] - last[0], pos[1] - last[1]) / 0.05));
      for (let k = 1; k <= n; k++) {
        end = await worldToPage(this.page, last[0] + ((pos[0] - last[0]) * k) / n, last[1] + ((pos[1] - last[1]) * k) / n);
        await this.pointerMove(end);
      }
      last = pos;
    }
    if (o.hold) this.held = end;
    else await this.pointerUp(end);
    await this.streamRead();
  }

  async key(o) {
    await this.input();
    await this.page.locator(`${ART} canvas.sim-canvas`).focus();
    for (let k = 0; k < (o.times ?? 1); k++) {
      await this.page.keyboard.press(o.shift ? `Shift+${o.key}` : o.key);
    }
    await this.streamRead();
  }

  /** The Move form: the point chosen by its label, x and y typed, Move. */
  async move(label, [x, y]) {
    const { page } = this;
    await this.input();
    const form = page.locator(`${ART} form.sim-move`);
    await form.locator("select[data-move=handle]").selectOption({ label });
    await form.locator("input[data-move=x]").fill(String(x));
    await form.locator("input[data-move=y]").fill(String(y));
    await form.locator("button[type=submit]").click();
    await settle(page);
  }

  // ---- the timeline slider ----

  slider() {
    return this.page.locator(`${ART} .tb-scrub`);
  }

  /** The slider put at step `n` (as a pointer drags its thumb there): a scrub pauses the page. */
  async scrubToStep(n) {
    const { page } = this;
    await this.slider().fill(String(n));
    // The page writes its text once the slider has rested (scrub.rs's
    // SCRUB_REST_MS, 150 ms): read it then, as a student does. Paused,
    // page time moves nothing else.
    await runFor(page, 150 + 2 * FRAME_MS);
  }

  async scrub(t) {
    const slider = this.slider();
    const [min, max] = [Number(await slider.getAttribute("min")), Number(await slider.getAttribute("max"))];
    const to = Math.round(t / DT_S);
    assert.ok(min <= to && to <= max, `the timeline runs from ${(min * DT_S).toFixed(2)} s to ${(max * DT_S).toFixed(2)} s`);
    await this.scrubToStep(to);
    // The slider says its moment first ("t = 6.00 s, Pole angle θ = 31.2°").
    const text = await slider.getAttribute("aria-valuetext");
    assert.ok(text.split(",")[0] === `t = ${t.toFixed(2)} s`, `the slider shows the moment scrubbed to: ${text}`);
  }

  async scrubBackUntil(text) {
    const slider = this.slider();
    const min = Number(await slider.getAttribute("min"));
    for (let at = Number(await slider.inputValue()); ; ) {
      const status = await statusText(this.page);
      if (status.includes(text)) return;
      assert.ok(at > min, `the start of the timeline, and the status never showed “${text}”`);
      at -= 1;
      await this.scrubToStep(at);
    }
  }

  /**
   * The slider left where the readout `label` is largest along the run
   * shown, as a student finds it: where a plot draws the same quantity (a
   * series of that name), its peak read off the plot, the slider dragged
   * there and then moved a step either way while the readout grows (Back
   * and Step); else every step of the run looked at in turn.
   */
  async scrubToLargest(label) {
    const slider = this.slider();
    const first = Math.max(this.lastInput, Number(await slider.getAttribute("min")));
    const end = Number(await slider.getAttribute("max"));
    const valueAt = async (step) => {
      await this.scrubToStep(step);
      const text = await shown(this.page, label);
      return text === null ? null : shownNumber(text);
    };
    const peak = await this.plotPeak(label);
    if (peak !== null) {
      // A plot's time is the run's own (from the input that began it, for
      // a run that starts again at each change) or the time bar's: the
      // moment of the two on the run shown where the readout is larger.
      const candidates = [first + Math.round(peak / DT_S), Math.round(peak / DT_S)].filter((s) => first <= s && s <= end);
      assert.ok(candidates.length > 0, `the plot's peak at ${peak} s is not on the run shown`);
      let [at, v] = [null, null];
      for (const s of candidates) {
        const w = await valueAt(s);
        if (w !== null && (v === null || w > v)) [at, v] = [s, w];
      }
      assert.ok(v !== null, `${label} shows no number at the plot's peak`);
      for (const dir of [-1, 1]) {
        for (;;) {
          const next = at + dir;
          if (next < first || next > end) break;
          const w = await valueAt(next);
          // Ties go to the earlier moment, as the scan below takes the first.
          if (w === null || w < v || (w === v && dir > 0)) break;
          [at, v] = [next, w];
        }
      }
      await this.scrubToStep(at);
      return;
    }
    let best = null;
    for (let step = first; step <= end; step++) {
      const v = await valueAt(step);
      if (v !== null && (best === null || v > best[1])) best = [step, v];
    }
    assert.ok(best, "the value shows no number on the timeline");
    await this.scrubToStep(best[0]);
  }

  /** The time (x) of the largest sample of a plotted series named as readout `label` (case aside), or null. */
  async plotPeak(label) {
    const titles = (await this.page.locator(`${ART} figure.plot .plot-title`).allTextContents()).map((t) => t.trim());
    for (const title of titles) {
      const { series } = await this.plotCsv(title);
      const s = series.find((c) => c.label.toLowerCase() === label.toLowerCase());
      if (s && s.y.length) return s.x[s.y.reduce((b, v, i) => (v > s.y[b] ? i : b), 0)];
    }
    return null;
  }

  /** The page opened anew from its own link, as a classmate would open it. */
  async reopen() {
    await this.release();
    // The address bar follows the page every HASH_INTERVAL_MS (250 ms,
    // labweb's sim/mod.rs): the link is copied once it has caught up.
    await runFor(this.page, 250 + 2 * FRAME_MS);
    const hash = await this.page.evaluate(() => location.hash);
    await this.page.goto("about:blank");
    await open(this.lab, this.page, hash);
    this.lastInput = 0;
    this.session = null;
  }

  /**
   * Readouts watched while the clock runs for `for` seconds: each frame's
   * shown text, sampled in the page after every animation frame (by the
   * init script WATCH), with the time the time bar shows.
   */
  async watch(o) {
    const { page } = this;
    const watched = [o, ...(o.also ?? [])];
    const labels = watched.map((w) => w.watch);
    await page.evaluate(([art, labels]) => window.__procedureWatch.start(art, labels), [ART, labels]);
    const frames = Math.round(o.for / DT_S);
    await runFor(page, frames * FRAME_MS);
    const samples = await page.evaluate(() => window.__procedureWatch.stop());
    const t0 = samples[0].t;
    for (const [i, w] of watched.entries()) {
      let largest = 0;
      let lastAbove = 0;
      for (const s of samples) {
        const v = Math.abs(s.values[i] ?? 0);
        largest = Math.max(largest, v);
        if (w.level !== undefined && v > w.level) lastAbove = s.t - t0;
      }
      let value;
      if (w.of === "max_abs") value = largest;
      else if (w.of === "last_above" && w.level !== undefined) value = lastAbove;
      else throw new Error(`no watch property “${w.of}” (max_abs, last_above with a level)`);
      await this.notedOrCompared(w, value, `${w.of} of ${w.watch} over ${o.for} s = ${value.toFixed(4)} (${samples.length} frames seen)`);
    }
  }

  /** The figure of plot `title` (its title exactly). */
  async figure(title) {
    const { page } = this;
    const figure = page.locator(`${ART} figure.plot`).filter({ has: page.locator(".plot-title", { hasText: title }) });
    const titles = await page.locator(`${ART} figure.plot .plot-title`).allTextContents();
    const exact = [];
    for (let i = 0; i < (await figure.count()); i++) {
      if ((await figure.nth(i).locator(".plot-title").textContent()).trim() === title) exact.push(figure.nth(i));
    }
    assert.ok(exact.length === 1, `no plot “${title}” (the plots: ${titles.join(", ")})`);
    return exact[0];
  }

  /** The series of plot `title`, from the CSV the page offers (the plot as drawn: the whole run). */
  async plotCsv(title) {
    const { page } = this;
    const fig = await this.figure(title);
    const [download] = await Promise.all([page.waitForEvent("download"), fig.locator("button[data-plot-csv]").click()]);
    const text = readFileSync(await download.path(), "utf8");
    const summary = (await fig.locator(".plot-summary").textContent()) ?? "";
    return { series: csvSeries(text), summary };
  }

  async plot(o) {
    if (o.of === "cursor") {
      // The moment the slider went back to, as the plot's cursor marks it.
      const x = await (await this.figure(o.plot)).locator("canvas").first().getAttribute("data-cursor");
      assert.ok(x !== null, `“${o.plot}” shows no cursor: the page shows the run's end`);
      return this.notedOrCompared(o, Number(x), `the cursor of “${o.plot}” at ${x}`);
    }
    const { series, summary } = await this.plotCsv(o.plot);
    const title = o.plot;
    let s = o.series === undefined ? series[0] : series.find((c) => c.label === o.series);
    let value;
    if (!s) {
      // A run kept by a change in the past is drawn and summarised, not in
      // the CSV (the model's own plots): its summary's latest and range.
      const at = summary.indexOf(`${o.series}: `);
      assert.ok(at >= 0, `“${title}” has the series ${series.map((c) => c.label).join(", ")} (summary: ${summary})`);
      const m = summary.slice(at + o.series.length + 2).match(/^\d+ samples?, latest (.+?), range (.+?) to (.+?)\.(\s|$)/);
      assert.ok(m, `the summary of “${o.series}”: ${summary}`);
      const [latest, lo, hi] = [m[1], m[2], m[3]].map(shownNumber);
      value = { max: hi, min: lo, max_abs: Math.max(Math.abs(lo), Math.abs(hi)), final: latest }[o.of];
      assert.ok(value !== undefined, `“${o.series}” is kept, not in the CSV: its summary gives max, min, max_abs, final, not ${o.of}`);
      return this.notedOrCompared(o, value, `${o.of} of “${o.series}” on “${title}” = ${value} (its summary: ${m[0]})`);
    }
    const { x, y } = s;
    assert.ok(y.length > 0, `“${s.label}” of plot “${title}” has no samples`);
    const atMax = () => y.reduce((b, v, i) => (v > y[b] ? i : b), 0);
    switch (o.of) {
      case "max": value = Math.max(...y); break;
      case "min": value = Math.min(...y); break;
      case "max_abs": value = Math.max(...y.map(Math.abs)); break;
      case "final": value = y[y.length - 1]; break;
      case "mean": value = y.reduce((a, b) => a + b, 0) / y.length; break;
      case "x_end": value = x[x.length - 1]; break;
      case "x_at_max": value = x[atMax()]; break;
      case "first_x_above": {
        const i = y.findIndex((v) => v > o.level);
        value = i >= 0 ? x[i] : null;
        break;
      }
      case "swing_growth": value = swingGrowth(y, o.level); break;
      case "share_in_band": {
        const [lo, hi] = await this.band(title);
        value = share(y.map((v) => lo <= v && v <= hi));
        break;
      }
      case "share_within": {
        const b = series.find((c) => c.label === o.bound);
        assert.ok(b, `“${title}” has no series “${o.bound}”`);
        value = share(y.map((v, i) => Math.abs(v) <= Math.abs(b.y[i])));
        break;
      }
      default:
        throw new Error(`no plot property “${o.of}”`);
    }
    assert.ok(value !== null && value !== undefined, `“${s.label}” of plot “${title}”: no ${o.of}`);
    return this.notedOrCompared(o, value, `${o.of} of “${s.label}” on “${title}” = ${value.toFixed(4)} (CSV, ${y.length} samples)`);
  }

  /**
   * The bounds of a plot's shaded band, as the page states them: the
   * band's legend names it, the Theory tab gives its numbers ("between
   * 0.216 and 9.35").
   */
  async band(title) {
    const { page } = this;
    const fig = page.locator(`${ART} figure.plot`).filter({ has: page.locator(".plot-title", { hasText: title }) });
    const legend = (await fig.locator("[data-legend=band]").allTextContents()).map((t) => t.trim());
    assert.ok(legend.length > 0, `“${title}” has no band`);
    const theory = await page.locator(`${ART} [data-panel="theory"]`).textContent();
    const m = theory.match(/lies between (\d+(?:\.\d+)?) and (\d+(?:\.\d+)?)/);
    assert.ok(m, `the band “${legend[0]}”: the Theory tab gives no numbers for it`);
    return [Number(m[1]), Number(m[2])];
  }

  async table(o) {
    const rows = await this.page.evaluate(
      ([art, caption]) => {
        const t = [...document.querySelectorAll(`${art} .live-table table`)].find((t) => t.caption?.textContent.includes(caption));
        if (!t) return null;
        return [...t.tBodies[0].rows].map((r) => [...r.cells].map((c) => c.textContent.trim()).join(" | "));
      },
      [ART, o.table],
    );
    assert.ok(rows, `no table “${o.table}”`);
    const line = rows[o.row - 1];
    assert.ok(line !== undefined, `“${o.table}” has ${rows.length} rows`);
    assert.ok(line.includes(o.says), `row ${o.row} of “${o.table}”: ${line} (its rows: ${rows.join("; ")})`);
  }

  /**
   * What Describe (the button under the canvas) says of the scene. The page
   * writes it at the press: no page time passes, as natively (a running
   * experiment is read at the moment the step reads it).
   */
  async describe() {
    const { page } = this;
    // A finger's tap on a phone: a mouse click would turn the page's words
    // to the mouse's ("click a target" for "tap a target").
    const button = page.locator(`${ART} [data-a11y=describe]`);
    await (this.touch ? button.tap() : button.click());
    return (await page.locator(`${ART} .sim-description`).textContent()).trim();
  }

  /** A claim about the scene, read where Describe puts it into words (`words`, `#` for the number). */
  async scene(o) {
    assert.ok(typeof o.words === "string" && o.words.includes("#"), `the scene claim ${JSON.stringify(o)} gives no words to read it by`);
    const text = await this.describe();
    const n = describedNumber(text, o.words);
    assert.ok(n !== null, `Describe does not say “${o.words}”: “${text}”`);
    return this.notedOrCompared(o, n, `${o.words} = ${n} in Describe: “${text}”`);
  }

  async item(o) {
    const { page } = this;
    // On a touch screen, the way the step gives for a finger (`touch`: an
    // item or a list) where the mouse's way needs Shift or Ctrl.
    if (this.touch && o.touch) {
      for (const t of [o.touch].flat()) await this.item(t);
      return;
    }
    const verb = verbOf(o);
    switch (verb) {
      case "set":
        return this.set(o.set, o.to);
      case "press":
        for (let k = 0; k < (o.times ?? 1); k++) await this.press(o.press);
        return;
      case "click":
        return this.click(o.click, o.with);
      case "drag":
        return this.drag(o);
      case "key":
        return this.key(o);
      case "move":
        return this.move(o.move, o.to);
      case "wait":
        if (o.wait === "rest") return this.rest();
        return runFor(page, Math.round(o.wait / DT_S) * FRAME_MS);
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
      case "scrub":
        return this.scrub(o.scrub);
      case "scrub_back_until":
        return this.scrubBackUntil(this.words(o.scrub_back_until));
      case "scrub_to_largest":
        return this.scrubToLargest(o.scrub_to_largest);
      case "reopen":
        return this.reopen();
      case "note": {
        const text = await shown(page, o.note);
        assert.ok(text !== null, `no readout “${o.note}”`);
        const n = shownNumber(text);
        assert.ok(n !== null, `${o.note} = “${text}” has no number`);
        this.notes.set(o.as ?? o.note, [n, `${o.note} = ${text}`]);
        return;
      }
      case "see": {
        const text = await shown(page, o.see);
        assert.ok(text !== null, `no readout or control “${o.see}”`);
        if ("says" in o) return assert.ok(text.includes(o.says), `${o.see} = ${text}`);
        const n = shownNumber(text);
        assert.ok(n !== null, `${o.see} = ${text}: no number`);
        // As displayed: without `within`, the claim's number is the one the page shows.
        return this.compare(o, n, `${o.see} = ${text}`, 1e-9 * Math.abs(n));
      }
      case "watch":
        return this.watch(o);
      case "status": {
        const text = await statusText(page);
        assert.equal(text.includes(this.words(o.status)), !o.not, `the status “${text}”`);
        return;
      }
      case "notice": {
        const text = (await page.locator(`${ART} .sim-notice`).first().textContent()).trim();
        assert.ok(text.includes(o.notice), `the notice “${text}”`);
        return;
      }
      case "time": {
        const text = await page.locator(`${ART} .tb-time`).textContent();
        return this.notedOrCompared(o, shownNumber(text.replace(/^t = /, "")), text);
      }
      case "plot":
        return this.plot(o);
      case "table":
        return this.table(o);
      case "scene":
        return this.scene(o);
      default:
        throw new Error(`no verb in ${JSON.stringify(o)}`);
    }
  }
}

/**
 * In the page, before it loads: after every animation frame, while a
 * watch is on, the watched readouts' shown numbers and the time of the
 * step they are of.
 */
function WATCH() {
  const number = (text) => {
    const t = text.trim().replace(/\u2212/g, "-");
    const m = t.match(/^-?\d+(\.\d+)?/);
    if (!m) return null;
    const sup = { "⁻": "-", "⁰": "0", "¹": "1", "²": "2", "³": "3", "⁴": "4", "⁵": "5", "⁶": "6", "⁷": "7", "⁸": "8", "⁹": "9" };
    const e = t.slice(m[0].length).match(/^ × 10([⁻⁰¹²³⁴⁵⁶⁷⁸⁹]+)/);
    return Number(m[0]) * 10 ** (e ? Number([...e[1]].map((c) => sup[c]).join("")) : 0);
  };
  let on = null;
  const sample = (art, labels) => {
    const values = labels.map((label) => {
      const ro = [...document.querySelectorAll(`${art} .readout`)].find((r) => r.querySelector("dt")?.textContent.trim() === label);
      return ro ? number(ro.querySelector("dd").textContent) : null;
    });
    // The time of the step the readouts shown are of (their data-step):
    // while "The math" is in view a running page writes them at idle time,
    // a frame or more after the time bar, and a busy machine puts that off
    // further. Paired with the bar's time, a value would be dated late.
    const step = document.querySelector(`${art} dl.readouts`)?.dataset.step;
    const t = step !== undefined ? Number(step) / 60 : number(document.querySelector(`${art} .tb-time`).textContent.replace(/^t = /, ""));
    return { t, values };
  };
  window.__procedureWatch = {
    sample,
    start(art, labels) {
      on = { art, labels, samples: [sample(art, labels)] };
    },
    stop() {
      const samples = on.samples;
      on = null;
      return samples;
    },
  };
  const request = window.requestAnimationFrame.bind(window);
  window.requestAnimationFrame = (callback) =>
    request((t) => {
      callback(t);
      if (on) on.samples.push(sample(on.art, on.labels));
    });
}

/**
 * How long experiment `id`'s Procedure keeps a page busy, roughly: the
 * simulated seconds it names (watches, waits) and a little for each item.
 */
function weight(id) {
  const items = procedure(id).flatMap((s) => s.play);
  return items.reduce((w, o) => w + 2 + (o.for ?? 0) + (typeof o.wait === "number" ? o.wait : 0), 0);
}

/**
 * The experiments of part `k` (from 0) of `n`: the built experiments
 * shared out by weight, heaviest first, each to the lightest part so far,
 * so that the files of the parts (run side by side) take alike.
 */
export function partOf(k, n) {
  const parts = Array.from({ length: n }, () => ({ ids: [], w: 0 }));
  const ids = builtExperimentIds().map((id) => [id, weight(id)]);
  ids.sort((a, b) => b[1] - a[1] || (a[0] < b[0] ? -1 : 1));
  for (const [id, w] of ids) {
    const lightest = parts.reduce((l, p) => (p.w < l.w ? p : l));
    lightest.ids.push(id);
    lightest.w += w;
  }
  return parts[k].ids;
}

/** The tests of part `k` of `n` (`procedures-<k+1>.test.mjs`): each experiment at both sizes. */
export function playPart(k, n) {
  const lab = useLab();
  for (const id of partOf(k, n)) playProcedure(lab, id);
  if (k === 0) {
    test("the parts share out every built experiment once", () => {
      const all = Array.from({ length: n }, (_, j) => partOf(j, n)).flat();
      assert.deepEqual([...all].sort(), [...builtExperimentIds()].sort());
    });
    test("a scene claim's number is read where its words put it in Describe (as natively)", () => {
      const text =
        "Tip at (0.76, 1.27) m. 2 dashed circles bound the reach: outer radius 1.700 m, inner radius 0.300 m. No ghost arm: the branches merge. Basin map: 1,050 starts reach the goal, \u22123 trapped.";
      assert.equal(describedNumber(text, "# dashed circle"), 2);
      assert.equal(describedNumber(text, "outer radius # m"), 1.7);
      assert.equal(describedNumber(text, "inner radius # m"), 0.3);
      assert.equal(describedNumber(text, "# ghost arm"), 0);
      assert.equal(describedNumber(text, "# starts reach"), 1050);
      assert.equal(describedNumber(text, "# trapped"), -3);
      assert.equal(describedNumber(text, "#) m"), 1.27);
      assert.equal(describedNumber(text, "# collided"), null);
      assert.equal(describedNumber(text, "no number here"), null);
    });
  }
}

function playProcedure(lab, id) {
  const steps = procedure(id);
  for (const [name, options] of [
    ["1280×800", { viewport: DESKTOP }],
    ["phone, touch", { viewport: PHONE, hasTouch: true, isMobile: true }],
  ]) {
    test(`${id}: the Procedure played as a student at ${name}, all ${steps.length} steps, then along the timeline`, () =>
      withPage(lab, { ...options, clock: true, initScript: WATCH }, async (page) => {
        await open(lab, page, `#/${id}/simulation`);
        const student = new Student(lab, page, Boolean(options.hasTouch), id);
        // LAB_PLAY_ON=1 plays on past a claim that does not hold and lists
        // them all at the end, for whoever writes a Procedure.
        const failures = [];
        for (const [k, step] of steps.entries()) {
          for (const item of step.play) {
            try {
              await student.item(item);
              // LAB_PLAY_TRACE=<id>: what the page shows after each item (as the native runner's).
              if (process.env.LAB_PLAY_TRACE === id) {
                const shownNow = await page.evaluate((art) => [...document.querySelectorAll(`${art} .readout`)].map((r) => r.textContent.trim()).join(" | "), ART);
                console.log(`[${k + 1}] ${JSON.stringify(item)}\n    ${await page.locator(`${ART} .tb-time`).textContent()}, status “${await statusText(page)}”\n    ${shownNow}`);
              }
            } catch (e) {
              const failure = `${id} step ${k + 1}: “${step.text}”\n    claim: ${JSON.stringify(item)}\n    the page showed: ${e.message}`;
              if (!process.env.LAB_PLAY_ON) throw new Error(failure);
              failures.push(failure);
            }
          }
          // LAB_PLAY_SHOTS=pid:9,astar:8: the page after those steps, as
          // target/e2e-shots/procedure-<id>-step<k>-<size>.png, to look at
          // (the phone's at 390 × 844, the size issue 53 asks to look at).
          if ((process.env.LAB_PLAY_SHOTS ?? "").split(",").includes(`${id}:${k + 1}`)) {
            const size = page.viewportSize();
            if (options.hasTouch) await page.setViewportSize({ width: 390, height: 844 });
            await runFor(page, 300);
            await screenshot(page, `procedure-${id}-step${k + 1}-${options.hasTouch ? "390" : "1280"}`);
            await page.setViewportSize(size);
            await runFor(page, 300);
          }
        }
        assert.deepEqual(failures, [], `\n${failures.join("\n\n")}`);
        // Issue 53: the timeline along the whole visit, at its end.
        await student.release();
        await alongTheTimeline(lab, page, id);
      }));
  }
}
