// The SCORM 1.2 package (`cargo xtask dist --scorm`) against a real LMS-side
// runtime: scorm-again's Scorm12API as `window.API` in a stand-in LMS page
// (tests/e2e/scorm/), with the SCO launched in an iframe from the package's
// imsmanifest.xml, its `#` fragment dropped as some LMSs do. Also:
// web/scorm.js's pure parts in Node, the plain site (dist/) outside an LMS,
// where nothing changes, and README's package size against the built zip.

import { test } from "node:test";
import assert from "node:assert/strict";
import { createServer } from "node:http";
import { existsSync } from "node:fs";
import { readdir, readFile, stat } from "node:fs/promises";
import { dirname, extname, join, resolve, sep } from "node:path";
import { fileURLToPath } from "node:url";
import { launchBrowser, open, useLab, waitReady, withPage } from "./helpers.mjs";

const ROOT = resolve(dirname(fileURLToPath(import.meta.url)), "..", "..");
const PACKAGE = join(ROOT, "dist-scorm");
const MIME = {
  ".html": "text/html; charset=utf-8",
  ".js": "text/javascript; charset=utf-8",
  ".css": "text/css; charset=utf-8",
  ".json": "application/json; charset=utf-8",
  ".xml": "application/xml; charset=utf-8",
  ".wasm": "application/wasm",
  ".svg": "image/svg+xml; charset=utf-8",
  ".png": "image/png",
};

/** web/scorm.js as a module (Node 20 reads a `.js` file as CommonJS). */
async function scormModule() {
  const text = await readFile(join(ROOT, "web", "scorm.js"), "utf8");
  return import(`data:text/javascript;base64,${Buffer.from(text).toString("base64")}`);
}

// ---------------------------------------------------------------- Node only

test("scorm.js: findAPI walks up a bounded number of frames and survives cross-origin frames", async () => {
  const { findAPI, getAPI, MAX_HOPS } = await scormModule();
  const api = { LMSInitialize: () => "true" };
  const chain = (n, top) => {
    let w = top;
    for (let i = 0; i < n; i++) {
      const child = {};
      child.parent = w;
      w = child;
    }
    return w;
  };
  const top = { API: api };
  top.parent = top;
  assert.equal(findAPI(chain(3, top)), api, "three frames up");
  assert.equal(findAPI(chain(MAX_HOPS, top)), api, "at the bound");
  assert.equal(findAPI(chain(MAX_HOPS + 5, top)), null, "beyond the bound: not searched");
  const crossOrigin = {
    get API() {
      throw new Error("SecurityError");
    },
  };
  crossOrigin.parent = crossOrigin;
  assert.equal(findAPI(chain(2, crossOrigin)), null, "a cross-origin parent throws; no API, no exception");
  assert.equal(findAPI({ API: { LMSInitialize: 1 }, parent: null }), null, "not a SCORM API");
  // The opener's frames are searched when the parents have none.
  const lone = {};
  lone.parent = lone;
  lone.top = lone;
  lone.opener = chain(1, top);
  assert.equal(getAPI(lone), api);
  const none = {};
  none.parent = none;
  assert.equal(getAPI(none), null);
});

test("scorm.js: CMITimespan, mastery and status", async () => {
  const { sessionTime, masteryOf, lessonStatus, launchedExperiment } = await scormModule();
  assert.equal(sessionTime(0), "00:00:00.00");
  assert.equal(sessionTime(7250), "00:00:07.25");
  assert.equal(sessionTime(((3 * 60 + 25) * 60 + 9) * 1000 + 5), "03:25:09.01");
  assert.equal(sessionTime(-5), "00:00:00.00");
  assert.equal(sessionTime(1e12), "9999:59:59.99", "capped at HHHH");
  assert.equal(masteryOf("80"), 80);
  assert.equal(masteryOf(""), 70);
  assert.equal(masteryOf("abc"), 70);
  assert.equal(masteryOf("150"), 70);
  assert.equal(lessonStatus(70, 70), "passed");
  assert.equal(lessonStatus(69, 70), "failed");
  assert.equal(launchedExperiment("#/pid/aim"), "pid");
  assert.equal(launchedExperiment("#/"), null);
  assert.equal(launchedExperiment(""), null);
});

test("scorm.js: a SCO is named by its launch query, which survives a dropped fragment", async () => {
  const { scoOf } = await scormModule();
  assert.equal(scoOf({ search: "?sco=pid", hash: "" }), "pid", "fragment dropped");
  assert.equal(scoOf({ search: "?sco=pid", hash: "#/fk/quiz" }), "pid", "the launch query wins over where the student went");
  assert.equal(scoOf({ search: "?lms=1&sco=ik&attempts=2", hash: "" }), "ik", "among the LMS's own parameters");
  assert.equal(scoOf({ search: "", hash: "#/astar/aim" }), "astar", "an older package launched with its fragment");
  assert.equal(scoOf({ search: "?sco=%3Cx%3E", hash: "" }), null);
  assert.equal(scoOf({ search: "", hash: "" }), null);
});

test("scorm.js: per-question interactions in SCORM 1.2 formats", async () => {
  const { interaction, cmiDecimal, choiceLetter, cmiTime } = await scormModule();
  assert.deepEqual(interaction("pid", 0, [true, 2, false, 0], "10:04:05"), [
    ["id", "pid-q1"],
    ["type", "choice"],
    ["student_response", "c"],
    ["result", "wrong"],
    ["correct_responses.0.pattern", "a"],
    ["weighting", "1"],
    ["time", "10:04:05"],
  ]);
  assert.deepEqual(interaction("ik", 6, [false, 0.6, true, 0.6000000001], "00:00:00").slice(0, 5), [
    ["id", "ik-q7"],
    ["type", "numeric"],
    ["student_response", "0.6"],
    ["result", "correct"],
    ["correct_responses.0.pattern", "0.6"],
  ]);
  // Blank or unreadable: no student_response at all (CMIDecimal has no blank).
  const blank = interaction("ik", 1, [false, null, false, -12.25], "00:00:00");
  assert.ok(!blank.some(([k]) => k === "student_response"));
  assert.deepEqual(blank.find(([k]) => k === "correct_responses.0.pattern"), ["correct_responses.0.pattern", "-12.25"]);
  assert.equal(cmiDecimal(1e-9), "0");
  assert.equal(cmiDecimal(1e12), null);
  assert.equal(cmiDecimal(NaN), null);
  assert.match(cmiDecimal(-1234.5678912), /^-?[0-9]{0,10}(\.[0-9]*)?$/);
  assert.equal(choiceLetter(0), "a");
  assert.equal(choiceLetter(25), "z");
  assert.equal(choiceLetter(26), null);
  assert.equal(cmiTime(new Date(2026, 0, 2, 9, 5, 7)), "09:05:07");
});

test("scorm.js: an LMS that refuses LMSInitialize or throws never breaks the page", async () => {
  const { startSession } = await scormModule();
  const page = () => Object.assign(new EventTarget(), { location: { hash: "#/pid/aim" } });
  const refused = page();
  const calls = [];
  const refusing = { LMSInitialize: () => "false", LMSSetValue: (...a) => calls.push(a) };
  assert.equal(startSession(refused, refusing), null);
  assert.equal(refused.labLms, undefined, "no bridge when the LMS refuses");
  assert.deepEqual(calls, []);

  // An API whose every other call throws: the session still runs, quietly.
  const win = page();
  const throwing = {
    LMSInitialize: () => "true",
    LMSGetValue: () => {
      throw new Error("LMS down");
    },
    LMSSetValue: () => {
      throw new Error("LMS down");
    },
    LMSCommit: () => {
      throw new Error("LMS down");
    },
    LMSFinish: () => {
      throw new Error("LMS down");
    },
  };
  const state = startSession(win, throwing, () => 0);
  assert.equal(state.experiment, "pid");
  assert.equal(state.mastery, 70);
  win.dispatchEvent(Object.assign(new Event("lab-quiz-submitted"), { detail: { id: "pid", percent: 80, suspendData: "{}" } }));
  win.dispatchEvent(new Event("pagehide"));
  assert.equal(state.finished, true);
  // Another experiment's quiz, or an over-long suspend_data, is not kept.
  const ok = page();
  const log = [];
  const api = {
    LMSInitialize: () => "true",
    LMSGetValue: (k) => (k === "cmi.core.lesson_status" ? "not attempted" : ""),
    LMSSetValue: (k, v) => log.push([k, v]),
    LMSCommit: () => "true",
    LMSFinish: () => "true",
  };
  const s = startSession(ok, api, () => 0);
  const send = (type, detail) => ok.dispatchEvent(Object.assign(new Event(type), { detail }));
  send("lab-quiz-submitted", { id: "astar", percent: 100, suspendData: "{}" });
  send("lab-quiz-progress", { id: "pid", suspendData: "x".repeat(4097) });
  assert.deepEqual(log, [["cmi.core.lesson_status", "incomplete"]]);
  assert.equal(ok.labLms.suspendData("pid"), null);
  send("lab-quiz-progress", { id: "pid", suspendData: '{"id":"pid"}' });
  assert.equal(ok.labLms.suspendData("pid"), '{"id":"pid"}');
  assert.equal(ok.labLms.suspendData("astar"), null, "only the launched experiment");
  send("lab-quiz-submitted", { id: "pid", percent: 69, suspendData: '{"id":"pid","submitted":true}' });
  assert.deepEqual(log.slice(2, 6), [
    ["cmi.core.score.min", "0"],
    ["cmi.core.score.max", "100"],
    ["cmi.core.score.raw", "69"],
    ["cmi.core.lesson_status", "failed"],
  ]);
  assert.equal(s.suspendData, '{"id":"pid","submitted":true}');
});

test("scorm.js: a submission reports the counted score and journals each question after the LMS's last interaction", async () => {
  const { startSession } = await scormModule();
  const win = Object.assign(new EventTarget(), { location: { search: "?sco=ik", hash: "" } });
  const log = [];
  const api = {
    LMSInitialize: () => "true",
    LMSGetValue: (k) => ({ "cmi.core.lesson_status": "incomplete", "cmi.interactions._count": "3" })[k] ?? "",
    LMSSetValue: (k, v) => log.push([k, v]),
    LMSCommit: () => "true",
    LMSFinish: () => "true",
  };
  const state = startSession(win, api, () => Date.UTC(2026, 0, 1, 12));
  assert.equal(state.experiment, "ik");
  const send = (detail) => win.dispatchEvent(Object.assign(new Event("lab-quiz-submitted"), { detail }));
  send({ id: "ik", percent: 8, counted: 17, questions: [[false, 1.5, true, 1.5], "junk", [true, null, false, 1]], suspendData: "{}" });
  const value = (k) => log.find(([key]) => key === k)?.[1];
  assert.equal(value("cmi.core.score.raw"), "17", "the counted score, not this attempt's");
  assert.equal(value("cmi.core.lesson_status"), "failed");
  assert.equal(value("cmi.interactions.3.id"), "ik-q1", "after the LMS's three");
  assert.equal(value("cmi.interactions.3.type"), "numeric");
  assert.equal(value("cmi.interactions.3.student_response"), "1.5");
  assert.equal(value("cmi.interactions.4.id"), "ik-q3", "a malformed row is skipped");
  assert.equal(value("cmi.interactions.4.correct_responses.0.pattern"), "b");
  assert.equal(value("cmi.interactions.4.student_response"), undefined);
  const ids = log.filter(([k]) => k.startsWith("cmi.interactions.")).map(([k]) => k);
  assert.equal(ids[0], "cmi.interactions.3.id", "id first");
  // A launch that names no experiment reports nothing at all.
  const lost = Object.assign(new EventTarget(), { location: { search: "", hash: "" } });
  const quiet = [];
  startSession(lost, { ...api, LMSSetValue: (k, v) => quiet.push([k, v]) }, () => 0);
  lost.dispatchEvent(Object.assign(new Event("lab-quiz-submitted"), { detail: { id: "fk", percent: 17, suspendData: '{"id":"fk"}' } }));
  assert.deepEqual(quiet, []);
  assert.equal(lost.labLms.suspendData("fk"), null);
});

// ------------------------------------------------------------- outside an LMS

const lab = useLab();

test("outside an LMS nothing changes: no API, no labLms, the quiz keeps its attempt in local storage as before", () =>
  withPage(lab, {}, async (page) => {
    const requests = [];
    page.on("request", (r) => requests.push(new URL(r.url()).pathname));
    await open(lab, page, "#/fk/quiz?quiz=77");
    assert.ok(!requests.some((p) => p.endsWith("/scorm.js")), "outside a frame scorm.js is not even downloaded");
    assert.equal(await page.evaluate(() => typeof window.labLms), "undefined");
    const events = page.evaluate(
      () =>
        new Promise((ok) =>
          window.addEventListener("lab-quiz-submitted", (e) => ok({ ...e.detail }), { once: true }),
        ),
    );
    await page.locator("form.quiz .quiz-q input").first().check();
    const kept = JSON.parse(await page.evaluate(() => localStorage.getItem("labquiz:fk")));
    assert.deepEqual(Object.keys(kept).sort(), ["answers", "seed"], "the stored format is unchanged");
    assert.equal(kept.seed, 77);
    await submit(page);
    const detail = await events;
    assert.equal(detail.id, "fk");
    assert.ok(detail.max > 0 && detail.score >= 0 && detail.score <= detail.max);
    const after = JSON.parse(await page.evaluate(() => localStorage.getItem("labquiz:fk")));
    assert.deepEqual(Object.keys(after).sort(), ["answers", "seed"]);
  }));

// -------------------------------------------------------------- inside an LMS

/** Serves the test LMS at /lms/, scorm-again at /lms/scorm-again/ and the package at /lms/content/1/. */
async function startLms() {
  if (!existsSync(join(PACKAGE, "imsmanifest.xml"))) {
    throw new Error("dist-scorm/ is missing: run `cargo xtask dist --scorm` first");
  }
  const mounts = [
    ["/lms/content/1/", PACKAGE],
    ["/lms/scorm-again/", join(ROOT, "node_modules", "scorm-again", "dist")],
    ["/lms/", join(ROOT, "tests", "e2e", "scorm")],
  ];
  const server = createServer(async (req, res) => {
    const path = decodeURIComponent(new URL(req.url, "http://x").pathname);
    const mount = mounts.find(([prefix]) => path.startsWith(prefix));
    let file = mount && resolve(mount[1], "." + sep + path.slice(mount[0].length));
    if (!mount || (file !== mount[1] && !file.startsWith(mount[1] + sep))) {
      res.writeHead(404).end();
      return;
    }
    if ((await stat(file).catch(() => null))?.isDirectory()) file = join(file, "index.html");
    const body = await readFile(file).catch(() => null);
    if (!body) {
      res.writeHead(404).end();
      return;
    }
    res.writeHead(200, { "Content-Type": MIME[extname(file)] || "application/octet-stream", "Cache-Control": "no-cache" });
    res.end(body);
  });
  await new Promise((ok) => server.listen(0, "127.0.0.1", ok));
  const port = server.address().port;
  return { port, url: `http://127.0.0.1:${port}/lms/`, close: () => new Promise((ok) => server.close(ok)) };
}

/** Opens the test LMS (`query` e.g. `?sco=pid`), optionally with an earlier session's cmi; returns the page and the SCO's frame. */
async function launch(browser, lms, query = "", savedCmi = null) {
  const context = await browser.newContext({ viewport: { width: 1280, height: 860 } });
  context.setDefaultTimeout(15_000);
  const problems = [];
  if (savedCmi) await context.addInitScript(`window.SAVED_CMI = ${JSON.stringify(savedCmi)};`);
  const page = await context.newPage();
  page.on("console", (m) => m.type() === "error" && problems.push(`console error: ${m.text()}`));
  page.on("pageerror", (e) => problems.push(`uncaught exception: ${e.message}`));
  page.on("response", (r) => r.status() >= 400 && problems.push(`HTTP ${r.status()} for ${r.url()}`));
  await page.goto(lms.url + "index.html" + query);
  await page.waitForFunction(() => document.getElementById("lms-status").textContent.startsWith("launched"));
  const frame = await (await page.$("#sco")).contentFrame();
  await frame.waitForFunction(() => document.body?.dataset.ready === "1");
  return { context, page, frame, problems };
}

const lmsLog = (page) => page.evaluate(() => window.lmsLog.map((entry) => [...entry]));
const sets = (log, element) => log.filter((e) => e[0] === "LMSSetValue" && e[1] === element).map((e) => e[2]);

async function submit(target) {
  const button = target.locator("form.quiz button[type=submit]");
  await button.click();
  // With unanswered questions the first press asks to confirm.
  if (await target.locator("form.quiz .quiz-score").isHidden()) await button.click();
  await target.locator("form.quiz .quiz-score:not([hidden])").waitFor();
}

async function openQuiz(frame) {
  await frame.locator("article.exp:not([hidden]) [role=tab][data-tab=quiz]").click();
  await frame.locator("form.quiz .quiz-q").first().waitFor();
}

test("SCORM: inside an LMS, the package launches from its manifest, initialises and marks the lesson incomplete", async () => {
  const lms = await startLms();
  const browser = await launchBrowser();
  try {
    const { context, page, frame, problems } = await launch(browser, lms);
    const launchHref = await page.evaluate(() => window.lmsLaunch);
    assert.match(launchHref, /^index\.html\?sco=[a-z0-9_-]+$/, "a SCO per experiment, named in the launch's query");
    const log = await lmsLog(page);
    assert.deepEqual(log[0], ["LMSInitialize"]);
    assert.deepEqual(sets(log, "cmi.core.lesson_status"), ["incomplete"]);
    assert.ok(log.some((e) => e[0] === "LMSCommit"));
    assert.equal(await page.evaluate(() => window.API.cmi.core.lesson_status), "incomplete");
    assert.equal(await frame.evaluate(() => typeof window.labLms?.suspendData), "function");
    await page.screenshot({ path: join(ROOT, "target", "e2e-shots", "scorm-lms.png") }).catch(() => {});
    assert.deepEqual(problems, []);
    await context.close();
  } finally {
    await browser.close();
    await lms.close();
  }
});

test("SCORM: a submitted quiz sets score and status and commits; a relaunch with the kept cmi resumes the graded attempt", async () => {
  const lms = await startLms();
  const browser = await launchBrowser();
  try {
    // First session: answer one question, submit.
    const first = await launch(browser, lms, "?sco=pid");
    const { page, frame } = first;
    await openQuiz(frame);
    const seed = await frame.locator("form.quiz .quiz-seed").innerText();
    await frame.locator("form.quiz .quiz-q input[type=radio]").first().check();
    const progress = JSON.parse(await page.evaluate(() => window.API.cmi.suspend_data));
    assert.equal(progress.id, "pid");
    assert.equal(String(progress.seed), seed);
    assert.equal(progress.submitted, false, "an answer in progress is kept, not submitted");
    assert.equal(sets(await lmsLog(page), "cmi.core.score.raw").length, 0, "no score before submission");

    await submit(frame);
    const scoreText = await frame.locator("form.quiz .quiz-score").innerText();
    const [, right, total, percent] = scoreText.match(/Score: (\d+) \/ (\d+) \((\d+)%\)/).map(Number);
    assert.ok(total > 0 && right <= total);
    const log = await lmsLog(page);
    assert.deepEqual(sets(log, "cmi.core.score.raw"), [String(percent)]);
    assert.deepEqual(sets(log, "cmi.core.score.min"), ["0"]);
    assert.deepEqual(sets(log, "cmi.core.score.max"), ["100"]);
    const status = percent >= 70 ? "passed" : "failed";
    assert.deepEqual(sets(log, "cmi.core.lesson_status"), ["incomplete", status]);
    const rawAt = log.findIndex((e) => e[1] === "cmi.core.score.raw");
    assert.ok(log.slice(rawAt).some((e) => e[0] === "LMSCommit"), "committed after the score");
    const cmi = await page.evaluate(() => ({
      raw: window.API.cmi.core.score.raw,
      status: window.API.cmi.core.lesson_status,
      suspend: window.API.cmi.suspend_data,
    }));
    assert.equal(cmi.raw, String(percent));
    assert.equal(cmi.status, status);
    assert.ok(cmi.suspend.length <= 4096);
    const kept = JSON.parse(cmi.suspend);
    assert.equal(kept.submitted, true);
    assert.equal(String(kept.seed), seed);

    // Leaving the SCO: session time, suspend, commit, finish.
    await page.evaluate(() => {
      document.getElementById("sco").src = "about:blank";
    });
    await page.waitForFunction(() => window.lmsLog.some((e) => e[0] === "LMSFinish"));
    const end = await lmsLog(page);
    const [time] = sets(end, "cmi.core.session_time");
    assert.match(time, /^\d{2,4}:\d{2}:\d{2}\.\d{2}$/, "CMITimespan");
    assert.deepEqual(sets(end, "cmi.core.exit"), ["suspend"]);
    const saved = await page.evaluate(() => JSON.parse(JSON.stringify(window.API.cmi)));
    assert.deepEqual(first.problems, []);
    await first.context.close();

    // Relaunch with what the LMS kept: the graded attempt is back.
    const second = await launch(browser, lms, "?sco=pid", saved);
    const log2 = await lmsLog(second.page);
    assert.deepEqual(log2[0], ["LMSInitialize"]);
    assert.deepEqual(sets(log2, "cmi.core.lesson_status"), [], "a graded lesson is not set back to incomplete");
    await openQuiz(second.frame);
    assert.equal(await second.frame.locator("form.quiz .quiz-seed").innerText(), seed);
    assert.equal(await second.frame.locator("form.quiz .quiz-score").innerText(), scoreText);
    const radio = second.frame.locator("form.quiz .quiz-q input[type=radio]").first();
    assert.ok(await radio.isChecked(), "the saved answer is back");
    assert.ok(await radio.isDisabled(), "the attempt is locked, as after grading");
    assert.equal(
      await second.frame.locator("form.quiz .quiz-explanation:not([hidden])").count(),
      total,
      "every worked answer is shown again",
    );
    await second.page.screenshot({ path: join(ROOT, "target", "e2e-shots", "scorm-resumed.png") }).catch(() => {});
    assert.deepEqual(second.problems, []);
    await second.context.close();
  } finally {
    await browser.close();
    await lms.close();
  }
});

test("SCORM: an attempt in progress resumes unsubmitted, with its answers, on another computer", async () => {
  const lms = await startLms();
  const browser = await launchBrowser();
  try {
    const first = await launch(browser, lms, "?sco=ik");
    await openQuiz(first.frame);
    const seed = await first.frame.locator("form.quiz .quiz-seed").innerText();
    const field = first.frame.locator("form.quiz .quiz-numeric input").first();
    await field.fill("0.5");
    await first.page.evaluate(() => {
      document.getElementById("sco").src = "about:blank";
    });
    await first.page.waitForFunction(() => window.lmsLog.some((e) => e[0] === "LMSFinish"));
    const saved = await first.page.evaluate(() => JSON.parse(JSON.stringify(window.API.cmi)));
    assert.equal(saved.core.lesson_status, "incomplete");
    assert.deepEqual(first.problems, []);
    await first.context.close();

    // A fresh context: no local storage, only what the LMS kept.
    const second = await launch(browser, lms, "?sco=ik", saved);
    await openQuiz(second.frame);
    assert.equal(await second.frame.locator("form.quiz .quiz-seed").innerText(), seed);
    const again = second.frame.locator("form.quiz .quiz-numeric input").first();
    assert.equal(await again.inputValue(), "0.5");
    assert.ok(await again.isEnabled(), "not submitted: still open");
    assert.ok(await second.frame.locator("form.quiz .quiz-score").isHidden());
    assert.deepEqual(second.problems, []);
    await second.context.close();
  } finally {
    await browser.close();
    await lms.close();
  }
});

test("SCORM: a SCO on another origin than the LMS cannot reach its API and runs as a plain page", async () => {
  const lms = await startLms();
  const browser = await launchBrowser();
  try {
    const { context, page, frame, problems } = await launch(browser, lms, `?origin=http://localhost:${lms.port}`);
    assert.equal(new URL(frame.url()).hostname, "localhost");
    assert.equal(await frame.evaluate(() => typeof window.labLms), "undefined");
    assert.deepEqual(await lmsLog(page), [], "no call reached the LMS");
    assert.deepEqual(problems, []);
    await context.close();
  } finally {
    await browser.close();
    await lms.close();
  }
});

// ------------------------------------------------ what real LMSs do (issue 24)

/** The cmi as the LMS keeps it (scorm-again's JSON export reads write-only elements). */
const cmiOf = (page) => page.evaluate(() => JSON.parse(JSON.stringify(window.API.cmi)));
const interactionsOf = (cmi) => Object.values(cmi.interactions ?? {});
const visibleExperiment = (frame) =>
  frame.evaluate(() => document.querySelector("article.exp:not([hidden])")?.dataset.experiment ?? "home");

test("SCORM launch without #: the SCO opens its experiment and reports only its own quiz wherever the student goes", async () => {
  const lms = await startLms();
  const browser = await launchBrowser();
  try {
    const { context, page, frame, problems } = await launch(browser, lms, "?sco=pid");
    const launched = await page.evaluate(() => window.lmsLaunched);
    assert.ok(!launched.includes("#"), `the LMS dropped the fragment: ${launched}`);
    await frame.locator('article.exp[data-experiment="pid"]:not([hidden])').waitFor();
    assert.equal(await visibleExperiment(frame), "pid", "the SCO shows its experiment, not the home page");
    assert.match(new URL(frame.url()).hash, /^#\/pid\/aim/);

    // fk's quiz inside the pid SCO: graded on the page, never reported.
    await frame.evaluate(() => {
      location.hash = "#/fk/quiz";
    });
    await frame.locator('article.exp[data-experiment="fk"]:not([hidden]) form.quiz .quiz-q').first().waitFor();
    await frame.locator("article.exp:not([hidden]) form.quiz .quiz-q input").first().check();
    await submit(frame.locator("article.exp:not([hidden])"));
    let cmi = await cmiOf(page);
    assert.equal(cmi.core.score.raw, "", "fk's score is not pid's");
    assert.equal(cmi.core.lesson_status, "incomplete");
    assert.ok(!cmi.suspend_data.includes('"id":"fk"'), cmi.suspend_data);
    assert.equal(interactionsOf(cmi).length, 0);

    // Back to pid: its quiz reports into its SCO.
    await frame.evaluate(() => {
      location.hash = "#/pid/quiz";
    });
    const pidForm = frame.locator('article.exp[data-experiment="pid"]:not([hidden])');
    await pidForm.locator("form.quiz .quiz-q").first().waitFor();
    await submit(pidForm);
    const scoreText = await pidForm.locator("form.quiz .quiz-score").innerText();
    const percent = Number(scoreText.match(/\((\d+)%\)/)[1]);
    cmi = await cmiOf(page);
    assert.equal(cmi.core.score.raw, String(percent));
    assert.equal(JSON.parse(cmi.suspend_data).id, "pid");
    assert.deepEqual(problems, []);
    await context.close();
  } finally {
    await browser.close();
    await lms.close();
  }
});

test("SCORM per-question results: each question reaches the runtime as cmi.interactions.n", async () => {
  const lms = await startLms();
  const browser = await launchBrowser();
  const content = JSON.parse(await readFile(join(ROOT, "assets", "pid.json"), "utf8"));
  try {
    const { context, page, frame, problems } = await launch(browser, lms, "?sco=pid");
    await openQuiz(frame);
    const form = frame.locator("form.quiz");
    const total = await form.locator(".quiz-q").count();
    // A choice answered (the first option shown), question 7 right, question 8 unreadable.
    await form.locator('.quiz-q[data-index="0"] input[type=radio]').first().check();
    await form.locator('.quiz-q[data-index="6"] input').fill(String(content.quiz[6].answer));
    await form.locator('.quiz-q[data-index="7"] input').fill("about half");
    await submit(frame);
    const kinds = await form.locator(".quiz-q").evaluateAll((qs) =>
      qs.map((q) => ({
        choice: q.querySelector("input[type=radio]") !== null,
        right: q.classList.contains("right"),
        expected: q.querySelector(".quiz-feedback").textContent,
      })),
    );
    const cmi = await cmiOf(page);
    const rows = interactionsOf(cmi);
    assert.equal(rows.length, total, "one interaction per question");
    rows.forEach((row, i) => {
      assert.equal(row.id, `pid-q${i + 1}`);
      assert.equal(row.type, kinds[i].choice ? "choice" : "numeric");
      assert.equal(row.result, kinds[i].right ? "correct" : "wrong", `question ${i + 1}`);
      assert.equal(row.weighting, "1");
      assert.match(row.time, /^\d{2}:\d{2}:\d{2}$/);
      const pattern = row.correct_responses["0"]?.pattern;
      if (kinds[i].choice) {
        // Letters in the content's order: the same for every student, whatever the shuffle.
        assert.equal(pattern, String.fromCharCode(97 + content.quiz[i].answer), `question ${i + 1}`);
      } else if (kinds[i].right) {
        assert.equal(Number(pattern), Number(row.student_response), `question ${i + 1}`);
      } else {
        // The answer the page showed, rounded for display.
        const shown = Number(kinds[i].expected.match(/Expected (-?\d+(?:\.\d+)?)/)[1]);
        assert.ok(Math.abs(Number(pattern) - shown) <= 1e-3 * Math.max(1, Math.abs(shown)), `question ${i + 1}: ${pattern} vs ${shown}`);
      }
    });
    assert.match(rows[0].student_response, /^[a-z]$/, "a choice answer is a letter");
    const picked = await form.locator('.quiz-q[data-index="0"] input[type=radio]').first().evaluate((r) => r.closest("label").querySelector("span").innerHTML);
    assert.equal(rows[0].student_response, String.fromCharCode(97 + content.quiz[0].options.indexOf(picked.trim())));
    assert.equal(rows[6].student_response, String(content.quiz[6].answer));
    assert.equal(rows[6].result, "correct");
    assert.equal(rows[7].student_response, "", "an unreadable number is not sent as a response");
    assert.equal(rows[7].result, "wrong");
    assert.equal(rows[1].student_response, "", "a blank choice has no response");
    assert.deepEqual(problems, []);
    await context.close();
  } finally {
    await browser.close();
    await lms.close();
  }
});

/** pid's quiz with `right` of its 12 questions answered right (its two fixed numeric ones), the rest blank. */
async function submitPid(frame, right) {
  const content = JSON.parse(await readFile(join(ROOT, "assets", "pid.json"), "utf8"));
  const form = frame.locator("form.quiz");
  for (const [k, index] of [6, 7].entries()) {
    await form.locator(`.quiz-q[data-index="${index}"] input`).fill(k < right ? String(content.quiz[index].answer) : "");
  }
  await submit(frame);
  return Number((await form.locator(".quiz-score").innerText()).match(/\((\d+)%\)/)[1]);
}

async function newAttempt(frame) {
  await frame.locator("form.quiz button.quiz-new").click();
  await frame.locator("form.quiz .quiz-score").waitFor({ state: "hidden" });
}

test("SCORM attempts: with attempts=2 a third submission is refused with a clear message, also after a relaunch", async () => {
  const lms = await startLms();
  const browser = await launchBrowser();
  try {
    const query = `?sco=pid&launch-query=${encodeURIComponent("attempts=2")}`;
    const first = await launch(browser, lms, query);
    const { page, frame } = first;
    await openQuiz(frame);
    assert.equal(await submitPid(frame, 1), 8);
    assert.match(await frame.locator("form.quiz .quiz-score").innerText(), /1 of 2 attempts graded\. The best score counts: 8%\. Press New attempt/);
    await newAttempt(frame);
    assert.equal(JSON.parse((await cmiOf(page)).suspend_data).submitted, false, "a new attempt is not kept as graded");
    assert.equal(await submitPid(frame, 2), 17);
    assert.match(await frame.locator("form.quiz .quiz-score").innerText(), /2 of 2 attempts graded\. The best score counts: 17%\. No attempts left\./);
    await newAttempt(frame);
    await frame.locator('form.quiz .quiz-q[data-index="6"] input').fill("0.01");
    await frame.locator("form.quiz button[type=submit]").click();
    const refusal = frame.locator("form.quiz .quiz-confirm");
    await refusal.waitFor();
    assert.equal(await refusal.innerText(), "No attempts left: 2 of 2 attempts graded. The best score counts: 17%.");
    assert.ok(await frame.locator("form.quiz .quiz-score").isHidden(), "not graded");
    const cmi = await cmiOf(page);
    assert.equal(cmi.core.score.raw, "17");
    assert.equal(interactionsOf(cmi).length, 24, "two graded attempts of 12 questions");
    assert.deepEqual(sets(await lmsLog(page), "cmi.core.score.raw"), ["8", "17"]);
    await page.evaluate(() => {
      document.getElementById("sco").src = "about:blank";
    });
    await page.waitForFunction(() => window.lmsLog.some((e) => e[0] === "LMSFinish"));
    const saved = await cmiOf(page);
    assert.deepEqual(first.problems, []);
    await first.context.close();

    // Another launch, another computer: the LMS's count holds.
    const second = await launch(browser, lms, query, saved);
    await openQuiz(second.frame);
    await newAttempt(second.frame);
    await second.frame.locator("form.quiz button[type=submit]").click();
    await second.frame.locator("form.quiz .quiz-confirm").waitFor();
    assert.match(await second.frame.locator("form.quiz .quiz-confirm").innerText(), /^No attempts left: 2 of 2 attempts graded/);
    assert.deepEqual(sets(await lmsLog(second.page), "cmi.core.score.raw"), []);
    assert.deepEqual(second.problems, []);
    await second.context.close();
  } finally {
    await browser.close();
    await lms.close();
  }
});

test("SCORM score rule: best keeps the higher of 8 → 17 → 8 (the default), last and first do as named", async () => {
  const lms = await startLms();
  const browser = await launchBrowser();
  try {
    for (const [rule, expected] of [
      ["", ["8", "17", "17"]],
      ["score=best", ["8", "17", "17"]],
      ["score=last", ["8", "17", "8"]],
      ["score=first", ["8", "8", "8"]],
    ]) {
      const query = rule ? `?sco=pid&launch-query=${encodeURIComponent(rule)}` : "?sco=pid";
      const { context, page, frame, problems } = await launch(browser, lms, query);
      await openQuiz(frame);
      const raws = [];
      for (const [k, right] of [1, 2, 1].entries()) {
        if (k > 0) await newAttempt(frame);
        await submitPid(frame, right);
        raws.push((await cmiOf(page)).core.score.raw);
      }
      assert.deepEqual(raws, expected, rule || "default");
      const cmi = await cmiOf(page);
      assert.equal(cmi.core.lesson_status, "failed");
      assert.equal(interactionsOf(cmi).length, 36, "every graded attempt's questions are journalled");
      assert.equal(JSON.parse(cmi.suspend_data).graded, 3);
      assert.deepEqual(problems, []);
      await context.close();
    }
  } finally {
    await browser.close();
    await lms.close();
  }
});

test("attempts in an instructor's link: attempts=1&score=last outside an LMS refuses a second submission; the quiz link keeps the rules", () =>
  withPage(lab, {}, async (page) => {
    await open(lab, page, "#/pid/quiz?attempts=1&score=last");
    await page.locator("form.quiz .quiz-q").first().waitFor();
    assert.equal(await submitPid(page, 2), 17);
    assert.match(await page.locator("form.quiz .quiz-score").innerText(), /1 of 1 attempts graded\. The last score counts: 17%\. No attempts left\./);
    await newAttempt(page);
    await page.locator("form.quiz button[type=submit]").click();
    await page.locator("form.quiz .quiz-confirm").waitFor();
    assert.equal(await page.locator("form.quiz .quiz-confirm").innerText(), "No attempts left: 1 of 1 attempts graded. The last score counts: 17%.");
    // The quiz's link keeps the rules, so a reload or a shared link has them
    // (outside an LMS the count starts with the page: a teaching aid).
    assert.match(await page.evaluate(() => location.hash), /^#\/pid\/quiz\?attempts=1&score=last&quiz=\d+$/);
    await page.reload();
    await waitReady(page);
    await page.locator("form.quiz .quiz-q").first().waitFor();
    assert.equal(await submitPid(page, 1), 8);
    assert.match(await page.locator("form.quiz .quiz-score").innerText(), /1 of 1 attempts graded\. The last score counts: 8%\. No attempts left\./);
  }));

// --------------------------------------------------- README's package figures

/** Bytes in a README size like `1.80 MiB` or `537 KiB`. */
const readmeBytes = (n, unit) => Number(n) * (unit === "MiB" ? 1024 * 1024 : 1024);

test("README's SCORM package size is the built zip's, within 5 %", async () => {
  const readme = await readFile(join(ROOT, "README.md"), "utf8");
  const m = readme.match(/upload \(([\d.]+) (KiB|MiB); ([\d.]+) (KiB|MiB) unzipped/);
  assert.ok(m, "README states the zip's size and the unzipped size");
  const zip = (await stat(join(ROOT, "dist-scorm.zip"))).size;
  let unzipped = 0;
  for (const entry of await readdir(PACKAGE, { recursive: true, withFileTypes: true })) {
    if (entry.isFile()) unzipped += (await stat(join(entry.parentPath ?? entry.path, entry.name))).size;
  }
  const near = (stated, actual, what) =>
    assert.ok(Math.abs(stated - actual) <= 0.05 * actual, `README says ${what} is ${(stated / 1048576).toFixed(2)} MiB; the build has ${(actual / 1048576).toFixed(2)} MiB`);
  near(readmeBytes(m[1], m[2]), zip, "dist-scorm.zip");
  near(readmeBytes(m[3], m[4]), unzipped, "dist-scorm/");
});
