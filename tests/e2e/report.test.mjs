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
import { SHOTS, open, runUntil, screenshot, settle, until, useLab, waitReady, withPage } from "./helpers.mjs";

const lab = useLab();
const ART = "article.exp:not([hidden])";

/** Sizes of the reports made in this file, printed at the end. */
const sizes = {};

function waitStatus(page, pattern, timeout = 20_000) {
  return until(
    page,
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
    await until(page, () => /[?&]run=0(&|$)/.test(location.hash));
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
  // Raw-text checks: the file carries no address but the link back, and
  // its one script element is the JSON record (a type no browser runs).
  assert.doesNotMatch(html, /\bsrc=|<link|<img|@import|@font-face/i);
  assert.equal(html.match(/<script/gi).length, 1);
  assert.match(html, /<script type="application\/json" id="lab-report-data">\{"report":1,/);
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
    // Every plot (the page puts the plots a Procedure watches first: issue 53 §5; the report keeps the experiment's order).
    assert.deepEqual(got.figures.map((f) => f.key).sort(), [...facts.plots].sort(), "every plot");
    for (const f of got.figures) {
      assert.equal(f.svgs, 1, `${f.key}: one inline svg`);
      assert.ok(f.width > 300, `${f.key}: the figure spans the page`);
    }
    assert.deepEqual(got.dataTables.map((t) => t.key), got.figures.map((f) => f.key), "a data table per plot, in the figures' order");
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
  withPage(lab, { clock: true }, async (page) => {
    await open(lab, page, "#/pid/simulation");
    await runUntil(page, () => Number.parseFloat(document.querySelector("[data-readout=x]").textContent) > 0.9);
    await page.locator(`${ART} button[data-action=pin]`).click();
    await until(page, () => Boolean(document.querySelector("[data-readout=pinA]")));
    const quiz = await submitQuiz(page, "pid");
    await pause(page);
    const facts = await pageFacts(page);
    const html = await downloadReport(page, "pid");
    assert.match(html, /Pinned run A/);
    // No class-wide seed in the link: the expected answers once submitted.
    assert.equal(expectedCells(html), quiz.total, "the student's own seed is not a class seed");
    await inspect(html, "pid", facts, { quiz, letter: true });
  }));

test("astar: after Plan & drive the report holds the search's tables and plots", () =>
  withPage(lab, { clock: true }, async (page) => {
    await open(lab, page, "#/astar/simulation?rate=18");
    await page.click(`${ART} button[data-action=plan]`);
    await waitStatus(page, /^arrived: path cost/);
    await pause(page);
    const facts = await pageFacts(page);
    const html = await downloadReport(page, "astar");
    await inspect(html, "astar", facts);
  }));

test("ekf: after a run the report holds every plot and no quiz", () =>
  withPage(lab, { clock: true }, async (page) => {
    await open(lab, page, "#/ekf/simulation");
    await waitStatus(page, /^EKF localisation, known map$/);
    // Run at 4× for a while: many samples, so the tables are decimated.
    await page.selectOption(`${ART} select[data-time=speed]`, "4");
    await runUntil(page, () => Number(document.querySelector("canvas.sim-canvas").dataset.steps) > 4000, null, {
      timeout: 60_000,
    });
    await pause(page);
    const facts = await pageFacts(page);
    const html = await downloadReport(page, "ekf");
    assert.match(html, /evenly spaced rows of \d+ samples/);
    await inspect(html, "ekf", facts);
  }));

test("rrtstar: the report after the longest run (20,000 iterations) draws the whole tree the screen shows and stays small", () =>
  withPage(lab, { clock: true }, async (page) => {
    // The largest budget: 20,000 iterations, the biggest tree and cost curve,
    // reached by stepping (one step is one batch of 400 iterations).
    await open(lab, page, "#/rrtstar/simulation?iters=20000&batch=400");
    await page.click(`${ART} button[data-action=grow]`);
    await pause(page);
    const step = page.locator(`${ART} button[data-time=step]`);
    for (let i = 0; i < 60; i += 1) {
      if (/^done/.test(await page.locator(`${ART} .sim-status`).textContent())) break;
      await step.click();
    }
    await waitStatus(page, /^done/);
    // The address bar's link follows at its pace (a paused run's link names
    // the moment shown, `at=`, which each step moves).
    await page.clock.runFor(300);
    const nodes = Number((await page.locator(`${ART} [data-readout=nodes]`).textContent()).replace(/[^\d]/g, ""));
    assert.ok(nodes > 10_000, `${nodes} nodes on screen`);
    const facts = await pageFacts(page);
    const html = await downloadReport(page, "rrtstar");
    // The tree is the scene's path in the Visited colour: one move per edge.
    const scene = html.slice(html.indexOf('<svg class="scene"'), html.indexOf("</svg>"));
    const tree = [...scene.matchAll(/<path d="([^"]*)"[^>]*stroke="#56B4E9"/g)].map((m) => m[1]);
    assert.equal(tree.length, 1, "the tree is drawn");
    assert.equal(tree[0].split("M").length - 1, nodes - 1, "every edge of the tree on screen");
    await inspect(html, "rrtstar", facts);
    console.log(`report sizes (bytes): ${JSON.stringify(sizes)}`);
    for (const [id, n] of Object.entries(sizes)) assert.ok(n < 400_000, `${id}: ${n} bytes`);
  }));


/** The text of a saved report file as the browser shows it in print. */
async function printedText(html, name, edit = null) {
  mkdirSync(SHOTS, { recursive: true });
  const file = join(SHOTS, name);
  await writeFile(file, html);
  const context = await lab.browser.newContext({ viewport: { width: 900, height: 1200 }, offline: true });
  try {
    const page = await context.newPage();
    await page.goto(pathToFileURL(file).href);
    if (edit) await edit(page);
    await page.emulateMedia({ media: "print" });
    const pdf = await page.pdf({ format: "A4" });
    assert.equal(pdf.subarray(0, 5).toString(), "%PDF-");
    return await page.evaluate(() => ({
      name: document.querySelector("[data-field=name]").innerText,
      group: document.querySelector("[data-field=group]").innerText,
      observations: document.querySelector("[data-field=observations]").innerText,
      visible: ["name", "group", "observations"].every((f) => {
        const r = document.querySelector(`[data-field=${f}]`).getBoundingClientRect();
        return r.width > 0 && r.height > 0;
      }),
    }));
  } finally {
    await context.close();
  }
}

test("report fields: Name, Group and Observations typed on the page are kept after a reload, printed in the report, and editable in the file", () =>
  withPage(lab, {}, async (page) => {
    await open(lab, page, "#/fk/simulation");
    const fields = page.locator(`${ART} details.report-fields`);
    await fields.locator("summary").click();
    await fields.locator("[data-report-field=name]").fill("Ada Lovelace");
    await fields.locator("[data-report-field=group]").fill("B2 <lab>");
    await fields.locator("[data-report-field=observations]").fill("The reach is l1 + l2.\nThe tip follows θ1.");
    await fields.locator("[data-report-field=observations]").blur();
    await page.reload();
    await waitReady(page);
    await page.locator(`${ART} button[data-export=report]`).waitFor();
    await page.locator(`${ART} details.report-fields summary`).click();
    assert.equal(await page.locator(`${ART} [data-report-field=name]`).inputValue(), "Ada Lovelace", "kept after a reload");
    assert.equal(await page.locator(`${ART} [data-report-field=group]`).inputValue(), "B2 <lab>");
    const html = await downloadReport(page, "fk");
    const shown = await printedText(html, "fk-fields-report.html");
    assert.equal(shown.name, "Ada Lovelace");
    assert.equal(shown.group, "B2 <lab>");
    assert.equal(shown.observations, "The reach is l1 + l2.\nThe tip follows θ1.");
    assert.ok(shown.visible, "the fields are printed");
    // Typed into the saved file before printing: the print shows it.
    const edited = await printedText(html, "fk-fields-report.html", async (p) => {
      await p.locator("[data-field=name]").click();
      await p.keyboard.press("End");
      await p.keyboard.type(" (edited)");
    });
    assert.equal(edited.name, "Ada Lovelace (edited)");
  }));

/** The expected-answer cells of a report. */
const expectedCells = (html) => (html.match(/<td class="expected">/g) ?? []).length;

test("answer key: a class quiz seed hides the expected answers by default", () =>
  withPage(lab, {}, async (page) => {
    await open(lab, page, "#/fk/simulation?quiz=123");
    const quiz = await submitQuiz(page, "fk");
    const html = await downloadReport(page, "fk");
    assert.match(html, new RegExp(`Score: ${quiz.right} / ${quiz.total}`));
    assert.match(html, /attempt seed <code>123<\/code>/);
    assert.equal(expectedCells(html), 0, "no key with a class-wide seed");
    assert.match(html, /Expected answers are not shown/);
  }));

test("answer key: key=submitted shows the expected answers once submitted, key=never never", () =>
  withPage(lab, {}, async (page) => {
    await open(lab, page, "#/fk/simulation?quiz=123&key=submitted");
    assert.equal(expectedCells(await downloadReport(page, "fk")), 0, "nothing before submission");
    const quiz = await submitQuiz(page, "fk");
    assert.equal(expectedCells(await downloadReport(page, "fk")), quiz.total);
  }).then(() =>
    withPage(lab, {}, async (page) => {
      await open(lab, page, "#/fk/simulation?key=never");
      await submitQuiz(page, "fk");
      const html = await downloadReport(page, "fk");
      assert.match(html, /Score: \d+ \/ \d+/);
      assert.equal(expectedCells(html), 0);
    }),
  ));

test("answer key: key=always shows them before submission; the Instructor panel offers the choice", () =>
  withPage(lab, {}, async (page) => {
    await open(lab, page, "#/ik/simulation?key=always");
    const always = await downloadReport(page, "ik");
    assert.doesNotMatch(always, /Score:/, "not submitted");
    assert.ok(expectedCells(always) > 0, "key=always shows the questions' expected answers");
    // The Instructor panel writes the choice into its link.
    await page.locator(`${ART} details.instructor-panel summary`).click();
    assert.equal(await page.locator(`${ART} select.instructor-key`).inputValue(), "always", "from the link");
    await page.selectOption(`${ART} select.instructor-key`, "never");
    await page.waitForFunction(
      (art) => /[?&]key=never(&|$)/.test(document.querySelector(`${art} .instructor-link`).value),
      ART,
    );
  }));

/** check.html's verdict on the report `text` (the page is open): good or bad, and its text. */
async function checkVerdict(page, text, name) {
  await page.evaluate(() => document.getElementById("check-result").replaceChildren());
  await page.setInputFiles("#check-file", { name, mimeType: "text/html", buffer: Buffer.from(text) });
  await page.waitForFunction(() => ["good", "bad"].includes(document.getElementById("check-result").dataset.verdict)
    && !/Checking/.test(document.getElementById("check-result").textContent));
  return page.evaluate(() => {
    const r = document.getElementById("check-result");
    return { verdict: r.dataset.verdict, text: r.textContent };
  });
}

test("check a report: the check page passes an untampered report and catches an edited score", () =>
  withPage(lab, {}, async (page) => {
    await open(lab, page, "#/pid/simulation");
    const quiz = await submitQuiz(page, "pid");
    await pause(page);
    const html = await downloadReport(page, "pid");
    const requests = [];
    page.on("request", (r) => requests.push(new URL(r.url()).pathname));
    await page.goto(`${lab.server.base}check.html`);
    const verdict = (text, name) => checkVerdict(page, text, name);
    const good = await verdict(html, "pid-report.html");
    assert.equal(good.verdict, "good", good.text);
    assert.match(good.text, new RegExp(`✓ The printed score, ${quiz.right} / ${quiz.total}, matches`));
    await screenshot(page, "check-page-pass");

    // The printed score raised by hand: caught.
    const raised = quiz.right === quiz.total ? quiz.right - 1 : quiz.total;
    const tampered = html.replace(/Score: \d+ \/ (\d+) \(\d+%\)/, `Score: ${raised} / $1 (100%)`);
    assert.notEqual(tampered, html);
    const bad = await verdict(tampered, "pid-report.html");
    assert.equal(bad.verdict, "bad", bad.text);
    assert.match(bad.text, new RegExp(`does not match: the answers in the file score ${quiz.right} / ${quiz.total}`));
    await screenshot(page, "check-page-caught");
    // Score edited in both places but not the answers: caught too.
    const both = tampered.replace(/"score":\[\d+,/, `"score":[${raised},`);
    assert.equal((await verdict(both, "pid-report.html")).verdict, "bad");

    // The page loaded only pid's module, no other experiment's.
    const wasm = requests.filter((p) => p.endsWith(".wasm"));
    assert.equal(wasm.length, 1, JSON.stringify(wasm));
  }));

test("the report's module is downloaded only when a report is made, once; a failed download says so and the next press works", () =>
  withPage(lab, { clock: true }, async (page) => {
    const fetched = [];
    page.on("request", (req) => {
      const name = new URL(req.url()).pathname.split("/").pop();
      if (/^report\.[0-9a-f]{8}\.(js|wasm)$/.test(name)) fetched.push(name);
    });
    await open(lab, page, "#/fk/simulation");
    await page.waitForLoadState("networkidle");
    assert.deepEqual(fetched, [], "a visit does not download the report's module");

    // A host that serves something broken in its place: the page says so,
    // the button is not left busy, and the lab goes on.
    await page.route(/\/pkg\/report\.[0-9a-f]{8}\.js$/, (route) =>
      route.fulfill({ status: 200, contentType: "text/javascript", body: 'throw new Error("a broken copy");' }),
    );
    await page.locator(`${ART} button[data-export=report]`).click();
    const notice = page.locator("#notice:not([hidden]) .notice-text");
    await notice.waitFor();
    assert.match(await notice.textContent(), /^The lab report could not be made \(a broken copy\)\./);
    assert.equal(await page.locator(`${ART} button[data-export=report]`).getAttribute("aria-busy"), null);
    await page.unroute(/\/pkg\/report\.[0-9a-f]{8}\.js$/);

    // The next press loads the real module and makes the file; a second
    // report reuses it.
    fetched.length = 0;
    const first = await downloadReport(page, "fk");
    assert.match(first, /<h1>Robot arm forward kinematics<\/h1>/);
    assert.deepEqual(fetched.filter((n) => n.endsWith(".wasm")).length, 1, `the module was fetched once: ${fetched}`);
    const second = await downloadReport(page, "fk");
    assert.match(second, /lab-report-data/);
    assert.equal(fetched.filter((n) => n.endsWith(".wasm")).length, 1, `and not again: ${fetched}`);
  }));

test("what a report check proves: a classmate's report with the name changed passes, so do answers and score edited together from a printed key; docs/instructors.md and the check page say so", () =>
  withPage(lab, {}, async (page) => {
    await open(lab, page, "#/fk/simulation?quiz=123&key=submitted");
    const fields = page.locator(`${ART} details.report-fields`);
    await fields.locator("summary").click();
    await fields.locator("[data-report-field=name]").fill("Ada Lovelace");
    await fields.locator("[data-report-field=name]").blur();
    const quiz = await submitQuiz(page, "fk");
    const html = await downloadReport(page, "fk");
    assert.ok((html.match(/<td class="expected">/g) ?? []).length > 0, "the report printed its answer key");
    await page.goto(`${lab.server.base}check.html`);
    // A classmate's report, the name changed: it passes, under the new name.
    const copied = html.replaceAll("Ada Lovelace", "Bob Classmate");
    assert.notEqual(copied, html);
    const classmate = await checkVerdict(page, copied, "fk-report.html");
    assert.equal(classmate.verdict, "good", classmate.text);
    assert.match(classmate.text, /Bob Classmate/);
    // Answers and score edited together (here: every answer blanked, 0 points): it passes.
    const edited = html
      .replace(/"answers":\[[^\]]*\]/, `"answers":[${Array(quiz.total).fill("null").join(",")}]`)
      .replace(/"score":\[\d+,/, '"score":[0,')
      .replace(/Score: \d+ \/ (\d+) \(\d+%\)/, "Score: 0 / $1 (0%)");
    assert.notEqual(edited, html);
    const together = await checkVerdict(page, edited, "fk-report.html");
    assert.equal(together.verdict, "good", together.text);
    assert.match(together.text, /a classmate's report with the name changed passes/);
    // Said plainly, next to what it catches.
    const doc = await readFile(new URL("../../docs/instructors.md", import.meta.url), "utf8");
    const section = doc.match(/\*\*Checking a report\.\*\*([^]*?)(?:\n## |$)/)?.[1] ?? "";
    assert.match(section, /What it catches: a score edited on its own/);
    assert.match(section, /A\s+classmate's report with the name changed passes\./);
    assert.match(section, /A report that printed its answer key/);
    const intro = await page.locator("main.check-page").innerText();
    assert.match(intro, /a classmate's report with the name changed passes/);
    assert.match(intro, /a report that printed its answer key/);
  }));
