// The SCORM 1.2 package (`cargo xtask dist --scorm`) against a real LMS-side
// runtime: scorm-again's Scorm12API as `window.API` in a stand-in LMS page
// (tests/e2e/scorm/), with the SCO launched in an iframe from the package's
// imsmanifest.xml. Also: web/scorm.js's pure parts in Node, and the plain
// site (dist/) outside an LMS, where nothing changes.

import { test } from "node:test";
import assert from "node:assert/strict";
import { createServer } from "node:http";
import { existsSync } from "node:fs";
import { readFile, stat } from "node:fs/promises";
import { dirname, extname, join, resolve, sep } from "node:path";
import { fileURLToPath } from "node:url";
import { launchBrowser, open, useLab, withPage } from "./helpers.mjs";

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

// ------------------------------------------------------------- outside an LMS

const lab = useLab();

test("outside an LMS nothing changes: no API, no labLms, the quiz keeps its attempt in local storage as before", () =>
  withPage(lab, {}, async (page) => {
    await open(lab, page, "#/fk/quiz?quiz=77");
    assert.equal(await page.locator('script[src^="scorm.js"]').count(), 1, "scorm.js is loaded");
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
    assert.match(launchHref, /^index\.html#\/[a-z0-9_-]+\/aim$/, "a SCO per experiment, launched on its Aim tab");
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
