// The lab report (issue 17 §3): run an experiment, press "Lab report",
// catch the download and check what a student hands in: title, aim, date,
// the link that reproduces the run, every parameter, the readouts, one
// inline SVG and one data table per plot, the quiz when it was submitted.
// Then open the file offline with every request recorded (there must be
// none), print it to PDF (A4 and Letter) and screenshot it to
// target/e2e-shots/ to be looked at.

import { test } from "node:test";
import assert from "node:assert/strict";
import { mkdirSync } from "node:fs";
import { readFile, writeFile } from "node:fs/promises";
import { join } from "node:path";
import { pathToFileURL } from "node:url";
import { SHOTS, open, settle, useLab, withPage } from "./helpers.mjs";

const lab = useLab();
const ART = "article.exp:not([hidden])";

/** Sizes of the reports made in this file, printed at the end. */
const sizes = {};

function waitStatus(page, pattern, timeout = 20_000) {
  return page.waitForFunction(
    ([sel, source]) => new RegExp(source).test(document.querySelector(sel)?.textContent ?? ""),
    [`${ART} .sim-status`, pattern.source],
    { timeout },
  );
}

/** Pauses an animated run and waits until the link says so. */
async function pause(page) {
  const play = page.locator(`${ART} button[data-time=play]`);
  if ((await play.count()) && (await play.getAttribute("aria-pressed")) === "true") {
    await play.click();
    await page.waitForFunction(() => /[?&]run=0(&|$)/.test(location.hash));
  }
  await settle(page);
}

/** What the page shows, to compare the report with. */
function pageFacts(page) {
  return page.evaluate((art) => {
    const a = document.querySelector(art);
    const keys = [...new Set([...a.querySelectorAll(".sim-controls [data-param]")].map((e) => e.dataset.param))];
    return {
      title: a.querySelector("h1")?.textContent.trim() ?? document.title.split(" — ")[0],
      params: keys,
      readouts: [...a.querySelectorAll("[data-readout]")].map((e) => e.dataset.readout),
      plots: [...a.querySelectorAll("figure.plot[data-plot]")].map((e) => e.dataset.plot),
      tables: [...a.querySelectorAll(".tables [data-table]")].map((e) => e.dataset.table),
      href: location.href,
    };
  }, ART);
}

/** Presses "Lab report" and returns the downloaded file's text. */
async function downloadReport(page, id) {
  const [download] = await Promise.all([
    page.waitForEvent("download"),
    page.locator(`${ART} button[data-export=report]`).click(),
  ]);
  assert.equal(download.suggestedFilename(), `${id}-report.html`);
  return readFile(await download.path(), "utf8");
}

/**
 * Opens the report from disk in a context with the network off and every
 * request recorded; checks its contents against what the lab page showed;
 * prints it to PDF and screenshots it.
 */
async function inspect(html, id, facts, { quiz = null, letter = false } = {}) {
  mkdirSync(SHOTS, { recursive: true });
  const file = join(SHOTS, `${id}-report.html`);
  await writeFile(file, html);
  sizes[id] = html.length;
  // Raw-text checks: the file carries no address but the link back.
  assert.doesNotMatch(html, /\bsrc=|<script|<link|<img|@import|@font-face/i);
  const addresses = html.match(/https?:\/\/[^\s"<]+/g) ?? [];
  const link = facts.href.replaceAll("&", "&amp;");
  assert.ok(
    addresses.every((a) => a === link),
    `only the link: ${addresses.filter((a) => a !== link).slice(0, 3)}`,
  );

  const context = await lab.browser.newContext({ viewport: { width: 900, height: 1200 }, offline: true });
  const requests = [];
  const errors = [];
  await context.route(
    (url) => url.protocol !== "file:",
    (route) => {
      requests.push(route.request().url());
      return route.abort();
    },
  );
  const page = await context.newPage();
  page.on("request", (r) => {
    if (r.url() !== pathToFileURL(file).href) requests.push(r.url());
  });
  page.on("console", (m) => m.type() === "error" && errors.push(m.text()));
  page.on("pageerror", (e) => errors.push(e.message));
  try {
    await page.goto(pathToFileURL(file).href);
    await page.waitForLoadState("load");
    const got = await page.evaluate(() => ({
      h1: document.querySelector("h1").textContent,
      aim: [...document.querySelectorAll(".aim p")].map((p) => p.textContent.trim()),
      date: document.querySelector(".date").textContent,
      link: document.querySelector(".link a").getAttribute("href"),
      params: [...document.querySelectorAll(".params tr[data-param]")].map((r) => r.dataset.param),
      units: [...document.querySelectorAll(".params tr[data-param]")].map((r) => r.children[2].textContent),
      readouts: [...document.querySelectorAll("tr[data-readout]")].map((r) => r.dataset.readout),
      tables: [...document.querySelectorAll("table[data-table]")].map((t) => t.dataset.table),
      figures: [...document.querySelectorAll("figure.plot")].map((f) => ({
        key: f.dataset.plot,
        svgs: f.querySelectorAll("svg").length,
        paths: f.querySelectorAll("svg path").length,
        width: f.querySelector("svg").getBoundingClientRect().width,
      })),
      dataTables: [...document.querySelectorAll("table[data-plot-table]")].map((t) => ({
        key: t.dataset.plotTable,
        rows: t.querySelectorAll("tbody tr").length,
      })),
      score: document.querySelector(".quiz .score")?.textContent ?? null,
      answers: document.querySelectorAll(".quiz tr.right, .quiz tr.wrong").length,
      lines: document.querySelectorAll(".observations .line").length,
      background: getComputedStyle(document.body).backgroundColor,
    }));
    assert.equal(got.h1, facts.title);
    assert.ok(got.aim.length > 0 && got.aim.every((p) => p.length > 20), "the aim");
    assert.match(got.date, /^\d{4}-\d\d-\d\d \d\d:\d\d \(UTC[+-]\d\d:\d\d\)$/);
    assert.equal(got.link, facts.href, "the link reproduces the run shown");
    for (const key of facts.params) assert.ok(got.params.includes(key), `parameter ${key}`);
    assert.ok(got.units.some((u) => u.trim() !== ""), "units are shown");
    assert.deepEqual(got.readouts, facts.readouts);
    assert.deepEqual(got.tables, facts.tables);
    assert.deepEqual(got.figures.map((f) => f.key), facts.plots, "every plot");
    for (const f of got.figures) {
      assert.equal(f.svgs, 1, `${f.key}: one inline svg`);
      assert.ok(f.width > 300, `${f.key}: the figure spans the page`);
    }
    assert.deepEqual(got.dataTables.map((t) => t.key), facts.plots, "a data table per plot");
    assert.ok(got.dataTables.every((t) => t.rows > 0 && t.rows <= 30), JSON.stringify(got.dataTables));
    assert.ok(got.figures.some((f) => f.paths > 0), "a run was plotted");
    assert.equal(got.lines, 14, "room for observations");
    assert.equal(got.background, "rgb(255, 255, 255)");
    if (quiz) {
      assert.match(got.score, new RegExp(`^Score: ${quiz.right} / ${quiz.total} \\(`));
      assert.equal(got.answers, quiz.total);
    } else {
      assert.equal(got.score, null);
    }

    const pdf = await page.pdf({ path: join(SHOTS, `${id}-report-a4.pdf`), format: "A4", printBackground: true });
    assert.equal(pdf.subarray(0, 5).toString(), "%PDF-");
    // The page tree's /Count is the number of pages.
    const counts = [...pdf.toString("latin1").matchAll(/\/Count (\d+)/g)].map((m) => Number(m[1]));
    const pages = Math.max(0, ...counts);
    assert.ok(pages >= 2 && pages <= 16, `${id}: ${pages} A4 pages`);
    if (letter) {
      const us = await page.pdf({ path: join(SHOTS, `${id}-report-letter.pdf`), format: "Letter" });
      assert.equal(us.subarray(0, 5).toString(), "%PDF-");
    }
    await page.emulateMedia({ media: "print" });
    await page.screenshot({ path: join(SHOTS, `${id}-report.png`), fullPage: true });
    // Its first page as a picture too, at A4's proportions.
    await page.setViewportSize({ width: 794, height: 1123 });
    await page.screenshot({ path: join(SHOTS, `${id}-report-page1.png`) });
    assert.deepEqual(requests, [], "the report made no request");
    assert.deepEqual(errors, [], "the report page reported no error");
  } finally {
    await context.close();
  }
}

/** Answers every question of the Self-assessment (the first option, or 1) and submits. */
async function submitQuiz(page, id) {
  await page.evaluate((id) => (location.hash = `#/${id}/quiz`), id);
  const form = page.locator(`${ART} form.quiz`);
  await form.locator(".quiz-q").first().waitFor();
  const total = await form.locator(".quiz-q").count();
  for (let i = 0; i < total; i += 1) {
    const q = form.locator(`.quiz-q[data-index="${i}"]`);
    if (await q.locator("input[type=radio]").count()) await q.locator("input[type=radio]").first().check();
    else await q.locator("input[type=text]").fill("1");
  }
  await form.locator("button[type=submit]").click();
  await form.locator(".quiz-score:not([hidden])").waitFor();
  const score = await form.locator(".quiz-score").textContent();
  const [, right] = /Score: (\d+) \//.exec(score);
  await page.evaluate((id) => (location.hash = `#/${id}/simulation`), id);
  await page.locator(`${ART} button[data-export=report]`).waitFor();
  return { right: Number(right), total };
}

test("pid: after a run and a submitted quiz, the report holds the run, every plot and the score; prints on A4 and Letter", () =>
  withPage(lab, {}, async (page) => {
    await open(lab, page, "#/pid/simulation");
    await page.waitForFunction(() => Number.parseFloat(document.querySelector("[data-readout=x]").textContent) > 0.9);
    await page.locator(`${ART} button[data-action=pin]`).click();
    await page.waitForSelector("[data-readout=pinA]");
    const quiz = await submitQuiz(page, "pid");
    await pause(page);
    const facts = await pageFacts(page);
    const html = await downloadReport(page, "pid");
    assert.match(html, /Pinned run A/);
    await inspect(html, "pid", facts, { quiz, letter: true });
  }));

test("astar: after Plan & drive the report holds the search's tables and plots", () =>
  withPage(lab, {}, async (page) => {
    await open(lab, page, "#/astar/simulation?rate=18");
    await page.click(`${ART} button[data-action=plan]`);
    await waitStatus(page, /^arrived: path cost/);
    await pause(page);
    const facts = await pageFacts(page);
    const html = await downloadReport(page, "astar");
    await inspect(html, "astar", facts);
  }));

test("ekf: after a run the report holds every plot and no quiz", () =>
  withPage(lab, {}, async (page) => {
    await open(lab, page, "#/ekf/simulation");
    await waitStatus(page, /^EKF localisation running$/);
    // Run at 4× for a while: many samples, so the tables are decimated.
    await page.selectOption(`${ART} select[data-time=speed]`, "4");
    await page.waitForFunction(() => Number(document.querySelector("canvas.sim-canvas").dataset.steps) > 4000, null, {
      timeout: 60_000,
    });
    await pause(page);
    const facts = await pageFacts(page);
    const html = await downloadReport(page, "ekf");
    assert.match(html, /evenly spaced rows of \d+ samples/);
    await inspect(html, "ekf", facts);
  }));

test("rrtstar: the report after the longest run (20,000 iterations) stays small", () =>
  withPage(lab, {}, async (page) => {
    // The largest budget: 20,000 iterations, the biggest tree and cost curve.
    await open(lab, page, "#/rrtstar/simulation?iters=20000&batch=400");
    await page.click(`${ART} button[data-action=grow]`);
    await waitStatus(page, /^done/, 90_000);
    await pause(page);
    const facts = await pageFacts(page);
    const html = await downloadReport(page, "rrtstar");
    await inspect(html, "rrtstar", facts);
    console.log(`report sizes (bytes): ${JSON.stringify(sizes)}`);
    for (const [id, n] of Object.entries(sizes)) assert.ok(n < 400_000, `${id}: ${n} bytes`);
  }));
