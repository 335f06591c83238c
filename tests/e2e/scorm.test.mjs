// The SCORM 1.2 package (`cargo xtask dist --scorm`) against a real LMS-side
// runtime: scorm-again's Scorm12API as `window.API` in a stand-in LMS page
// (tests/e2e/scorm/), with the SCO launched in an iframe from the package's
// imsmanifest.xml, its `#` fragment dropped as some LMSs do. Also:
// web/scorm.js's pure parts in Node, the plain site (dist/) outside an LMS,
// where nothing changes, and docs/lms.md's package size against the built zip.

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
  // Issue 51 §3: an LMS that appends its own query after a second `?`.
  assert.equal(scoOf({ search: "?sco=pid?scorm_launch=1&x=2", hash: "" }), "pid");
  assert.equal(scoOf({ search: "?sco=pid%3Fscorm_launch%3D1", hash: "" }), "pid");
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
  // A launch that names no experiment reports no score at all, only why (issue 51 §3).
  const lost = Object.assign(new EventTarget(), { location: { search: "", hash: "" } });
  const quiet = [];
  startSession(lost, { ...api, LMSSetValue: (k, v) => quiet.push([k, v]) }, () => 0);
  lost.dispatchEvent(Object.assign(new Event("lab-quiz-submitted"), { detail: { id: "fk", percent: 17, suspendData: '{"id":"fk"}' } }));
  assert.deepEqual(quiet.map(([k]) => k), ["cmi.comments"]);
  assert.equal(lost.labLms.suspendData("fk"), null);
});

test("scorm.js: a value the LMS refuses is said on the page with the LMS's reason", async () => {
  const { startSession } = await scormModule();
  // A minimal page: a body and the app, as index.html has them.
  const made = [];
  const body = { insertBefore: (el) => made.push(el) };
  const document = {
    body,
    getElementById: (id) => made.find((el) => el.id === id) ?? null,
    createElement: () => ({ textContent: "", setAttribute(k, v) { this[k] = v; } }),
  };
  const win = Object.assign(new EventTarget(), { location: { search: "?sco=pid", hash: "" }, document });
  const api = {
    LMSInitialize: () => "true",
    LMSGetValue: () => "",
    LMSSetValue: (k) => (k === "cmi.suspend_data" ? "false" : "true"),
    LMSGetLastError: () => "405",
    LMSGetErrorString: (code) => (code === "405" ? "Incorrect Data Type" : ""),
    LMSCommit: () => "true",
    LMSFinish: () => "true",
  };
  const state = startSession(win, api, () => 0);
  assert.equal(made.length, 0, "nothing to say yet");
  win.dispatchEvent(Object.assign(new Event("lab-quiz-progress"), { detail: { id: "pid", suspendData: '{"id":"pid"}' } }));
  assert.deepEqual(state.refused, ["cmi.suspend_data"]);
  assert.equal(made.length, 1);
  assert.equal(made[0].role, "alert");
  assert.equal(made[0].textContent, "Your LMS did not save cmi.suspend_data (error 405: Incorrect Data Type); tell your instructor.");
});

test("scorm.js: what the page says for review, browse and no-credit launches", async () => {
  const { modeNotice } = await scormModule();
  assert.match(modeNotice("review", "credit"), /^Review: .*read-only/);
  assert.match(modeNotice("browse", "credit"), /^Browse mode: your LMS records no score/);
  assert.match(modeNotice("normal", "no-credit"), /^No credit: your LMS records no score/);
  assert.equal(modeNotice("normal", "credit"), "");
  assert.equal(modeNotice("", ""), "", "an LMS that says nothing: a normal launch");
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
  // The runtime's commits (LMSCommit and LMSFinish post the cmi here).
  const commits = [];
  const waiting = [];
  const cmiIn = (body) => {
    try {
      return JSON.parse(body);
    } catch {
      return {};
    }
  };
  /**
   * The first commit posted (already or later) whose parsed cmi satisfies
   * `wanted`; fails after 15 s, naming what did arrive, rather than hang.
   */
  const commitWhere = (wanted, what) =>
    new Promise((ok, fail) => {
      const seen = commits.find((b) => wanted(cmiIn(b)));
      if (seen) return ok(cmiIn(seen));
      const w = { wanted, ok: (body) => (clearTimeout(w.timer), ok(cmiIn(body))) };
      w.timer = setTimeout(() => {
        waiting.splice(waiting.indexOf(w), 1);
        fail(new Error(`no commit ${what} reached the LMS server in 15 s; it got ${commits.length}: ${commits.map((b) => b.slice(0, 160)).join(" | ")}`));
      }, 15_000);
      waiting.push(w);
    });
  const server = createServer(async (req, res) => {
    const path = decodeURIComponent(new URL(req.url, "http://x").pathname);
    if (req.method === "POST" && path === "/lms/commit") {
      let body = "";
      for await (const chunk of req) body += chunk;
      commits.push(body);
      for (const w of [...waiting]) {
        if (w.wanted(cmiIn(body))) {
          waiting.splice(waiting.indexOf(w), 1);
          w.ok(body);
        }
      }
      res.writeHead(200, { "Content-Type": "application/json" }).end('{"result":true,"errorCode":0}');
      return;
    }
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
  return { port, commits, commitWhere, url: `http://127.0.0.1:${port}/lms/`, close: () => new Promise((ok) => server.close(ok)) };
}

/** A browser profile (context) for the test LMS. */
async function profile(browser) {
  const context = await browser.newContext({ viewport: { width: 1280, height: 860 } });
  context.setDefaultTimeout(15_000);
  return context;
}

/**
 * Opens the test LMS (`query` e.g. `?sco=pid`), optionally with an earlier
 * session's cmi, in a new profile or in `shared` (one browser profile, as a
 * lab PC has); returns the page and the SCO's frame once `ready` holds in it
 * (by default: the page's module has started).
 */
async function launch(browser, lms, query = "", savedCmi = null, shared = null, ready = () => document.body?.dataset.ready === "1") {
  const context = shared ?? (await profile(browser));
  const problems = [];
  if (savedCmi) await context.addInitScript(`window.SAVED_CMI = ${JSON.stringify(savedCmi)};`);
  const page = await context.newPage();
  page.on("console", (m) => m.type() === "error" && problems.push(`console error: ${m.text()}`));
  page.on("pageerror", (e) => problems.push(`uncaught exception: ${e.message}`));
  page.on("response", (r) => r.status() >= 400 && problems.push(`HTTP ${r.status()} for ${r.url()}`));
  await page.goto(lms.url + "index.html" + query);
  await page.waitForFunction(() => document.getElementById("lms-status").textContent.startsWith("launched"));
  const frame = await (await page.$("#sco")).contentFrame();
  await frame.waitForFunction(ready);
  return { context, page, frame, problems };
}

const lmsLog = (page) => page.evaluate(() => window.lmsLog.map((entry) => [...entry]));
/** Seconds in a SCORM 1.2 CMITimespan (HHHH:MM:SS.SS), to 1/100 s. */
const timespanSeconds = (span) => {
  const m = /^(\d{2,4}):(\d{2}):(\d{2})(\.\d{1,2})?$/.exec(span);
  assert.ok(m, `a CMITimespan: ${span}`);
  return Math.round((Number(m[1]) * 3600 + Number(m[2]) * 60 + Number(m[3]) + Number(m[4] ?? 0)) * 100) / 100;
};
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

// ------------------------------- issue 51: one attempt per person per LMS record

/** Runs `body` with the test LMS's server and a browser, closing both after. */
async function withLms(body) {
  const lms = await startLms();
  const browser = await launchBrowser();
  try {
    await body(lms, browser);
  } finally {
    await browser.close();
    await lms.close();
  }
}

/** Leaves the SCO as an LMS does (the frame is emptied) and waits for LMSFinish. */
async function leave(page) {
  await page.evaluate(() => {
    document.getElementById("sco").src = "about:blank";
  });
  await page.waitForFunction(() => window.lmsLog.some((e) => e[0] === "LMSFinish"));
}

/** The quiz as shown: its seed, the answers in it, whether it is graded. */
const quizShown = (target) =>
  target.locator("article.exp:not([hidden]) form.quiz").evaluate((form) => ({
    seed: form.querySelector(".quiz-seed")?.textContent,
    checked: form.querySelectorAll("input[type=radio]:checked").length,
    typed: [...form.querySelectorAll("input[type=text]")].map((i) => i.value).filter(Boolean),
    graded: !form.querySelector(".quiz-score").hidden,
  }));

/** pid's quiz with question 1 ticked and question 7 answered right (not submitted). */
async function answerPid(frame) {
  const content = JSON.parse(await readFile(join(ROOT, "assets", "pid.json"), "utf8"));
  const form = frame.locator("form.quiz");
  await form.locator('.quiz-q[data-index="0"] input[type=radio]').first().check();
  await form.locator('.quiz-q[data-index="6"] input').fill(String(content.quiz[6].answer));
}

/** Watches a page opened outside the test's own helpers for console errors. */
function watch(page, problems) {
  page.on("console", (m) => m.type() === "error" && problems.push(`console error: ${m.text()}`));
  page.on("pageerror", (e) => problems.push(`uncaught exception: ${e.message}`));
}

test("LMS attempt, second tab: a tab opened from the SCO's brand link shows neither the LMS attempt's seed nor its answers, and reports nothing", () =>
  withLms(async (lms, browser) => {
    const { context, page, frame, problems } = await launch(browser, lms, `?sco=pid&launch-query=${encodeURIComponent("attempts=1")}`);
    await openQuiz(frame);
    await answerPid(frame);
    const inLms = await quizShown(frame);
    assert.equal(inLms.checked, 1);
    // A middle-click on the lab's own brand link: a new tab, not connected to any LMS.
    const [tab] = await Promise.all([context.waitForEvent("page"), frame.locator("a.brand").click({ button: "middle" })]);
    watch(tab, problems);
    await tab.waitForFunction(() => document.body?.dataset.ready === "1");
    assert.equal(await tab.evaluate(() => typeof window.labLms), "undefined", "the tab is not connected to the LMS");
    await tab.evaluate(() => {
      location.hash = "#/pid/quiz";
    });
    await tab.locator('article.exp[data-experiment="pid"]:not([hidden]) form.quiz .quiz-q').first().waitFor();
    const outside = await quizShown(tab);
    assert.notEqual(outside.seed, inLms.seed, "not the LMS attempt's seed");
    assert.deepEqual([outside.checked, outside.typed, outside.graded], [0, [], false], "none of its answers");
    // Graded there, it reaches nothing, and the LMS attempt is untouched.
    await submit(tab.locator("article.exp:not([hidden])"));
    assert.deepEqual(sets(await lmsLog(page), "cmi.core.score.raw"), []);
    const kept = JSON.parse((await cmiOf(page)).suspend_data);
    assert.equal(String(kept.seed), inLms.seed);
    assert.equal(kept.submitted, false);
    assert.deepEqual(
      await frame.evaluate(() => Object.keys(localStorage).filter((k) => k.startsWith("labquiz:"))),
      [],
      "nothing of the attempt in local storage",
    );
    assert.deepEqual(problems, []);
    await context.close();
  }));

test("LMS attempt, two learners in one browser profile: B starts fresh and never sees A's seed, answers, score or report fields", () =>
  withLms(async (lms, browser) => {
    const context = await profile(browser);
    const a = await launch(browser, lms, "?sco=pid&student=s-A", null, context);
    await openQuiz(a.frame);
    await answerPid(a.frame);
    await submit(a.frame);
    const seenByA = await quizShown(a.frame);
    await a.frame.locator("article.exp:not([hidden]) [role=tab][data-tab=simulation]").click();
    const fields = a.frame.locator("article.exp:not([hidden]) details.report-fields");
    await fields.locator("summary").click();
    await fields.locator("[data-report-field=name]").fill("Ada Student-A");
    await fields.locator("[data-report-field=group]").fill("G1");
    await fields.locator("[data-report-field=group]").press("Tab");
    await leave(a.page);
    assert.deepEqual(a.problems, []);
    await a.page.close();

    // Student B, another LMS user with an empty record, on the same PC.
    const b = await launch(browser, lms, "?sco=pid&student=s-B", null, context);
    await openQuiz(b.frame);
    const seenByB = await quizShown(b.frame);
    assert.notEqual(seenByB.seed, seenByA.seed, "a new seed");
    assert.deepEqual([seenByB.checked, seenByB.typed, seenByB.graded], [0, [], false], "none of A's answers, no score");
    await submit(b.frame);
    assert.deepEqual(sets(await lmsLog(b.page), "cmi.core.score.raw"), ["0"], "B's own blank attempt, not A's score");
    await b.frame.locator("article.exp:not([hidden]) [role=tab][data-tab=simulation]").click();
    const names = b.frame.locator("article.exp:not([hidden]) details.report-fields input");
    assert.deepEqual(await names.evaluateAll((inputs) => inputs.map((i) => i.value)), ["", ""], "not A's name or group");
    assert.deepEqual(b.problems, []);
    await leave(b.page);
    await b.page.close();

    // A again, another day, same PC: A's own fields are back (kept under A's id).
    const again = await launch(browser, lms, "?sco=pid&student=s-A", null, context);
    await again.frame.locator("article.exp:not([hidden]) [role=tab][data-tab=simulation]").click();
    const back = again.frame.locator("article.exp:not([hidden]) details.report-fields input");
    assert.deepEqual(await back.evaluateAll((inputs) => inputs.map((i) => i.value)), ["Ada Student-A", "G1"]);
    assert.deepEqual(again.problems, []);
    await context.close();
  }));

test("LMS attempt, a new LMS attempt with an empty cmi starts a fresh attempt with a new seed", () =>
  withLms(async (lms, browser) => {
    const context = await profile(browser);
    const first = await launch(browser, lms, "?sco=pid", null, context);
    await openQuiz(first.frame);
    await answerPid(first.frame);
    await submit(first.frame);
    const before = await quizShown(first.frame);
    await leave(first.page);
    await first.page.close();
    // The LMS starts a new attempt: its record is empty, the browser is the same.
    const second = await launch(browser, lms, "?sco=pid", null, context);
    await openQuiz(second.frame);
    const after = await quizShown(second.frame);
    assert.notEqual(after.seed, before.seed);
    assert.deepEqual([after.checked, after.typed, after.graded], [0, [], false]);
    assert.ok(await second.frame.locator("form.quiz button[type=submit]").isEnabled());
    assert.deepEqual([...first.problems, ...second.problems], []);
    await context.close();
  }));

test("Inside a SCO the package decides: quiz= and key= in the link never replace the LMS's seed or show its key", () =>
  withLms(async (lms, browser) => {
    const { context, page, frame, problems } = await launch(browser, lms, "?sco=pid");
    await openQuiz(frame);
    await answerPid(frame);
    const { seed } = await quizShown(frame);
    const route = (hash) =>
      frame.evaluate(
        (h) =>
          new Promise((ok) => {
            addEventListener("hashchange", () => requestAnimationFrame(() => ok()), { once: true });
            location.hash = h;
          }),
        hash,
      );
    await route("#/pid/quiz?quiz=123&key=always");
    const shown = await quizShown(frame);
    assert.equal(shown.seed, seed, "the LMS's seed stays");
    assert.equal(shown.checked, 1, "with its answers");
    assert.equal(String(JSON.parse((await cmiOf(page)).suspend_data).seed), seed);
    // key=always in the Simulation tab's link: a report made before submitting lists no answers.
    await route("#/pid/simulation?key=always&quiz=123");
    const [download] = await Promise.all([
      page.waitForEvent("download"),
      frame.locator("article.exp:not([hidden]) button[data-export=report]").click(),
    ]);
    const html = await readFile(await download.path(), "utf8");
    assert.equal((html.match(/<td class="expected">/g) ?? []).length, 0, "no expected answers in the report");
    await route("#/pid/quiz");
    assert.equal((await quizShown(frame)).seed, seed);
    assert.deepEqual(problems, []);
    await context.close();
  }));

test("answer key, one rule: with a class quiz seed the Self-assessment tab shows no expected answers after submitting, as the report; key=submitted shows them in both", () =>
  withPage(lab, {}, async (page) => {
    await open(lab, page, "#/pid/simulation?quiz=4242");
    await page.locator("article.exp:not([hidden]) [role=tab][data-tab=quiz]").click();
    await page.locator("form.quiz .quiz-q").first().waitFor();
    await submit(page);
    const lines = await page.locator("form.quiz .quiz-feedback").allInnerTexts();
    assert.ok(lines.length > 0 && lines.every((t) => !t.includes("Expected")), lines.join(" | "));
    assert.equal(await page.locator("form.quiz .quiz-explanation:not([hidden])").count(), 0);
    await open(lab, page, "#/fk/simulation?quiz=4242&key=submitted");
    await page.locator("article.exp:not([hidden]) [role=tab][data-tab=quiz]").click();
    await page.locator("form.quiz .quiz-q").first().waitFor();
    await submit(page.locator("article.exp:not([hidden])"));
    const shown = await page.locator("article.exp:not([hidden]) form.quiz .quiz-feedback").allInnerTexts();
    assert.ok(shown.some((t) => t.includes("Expected")), shown.join(" | "));
  }));

test("SCORM launch query mangled by the LMS (?sco=pid?scorm_launch=1&…): the SCO opens pid, keeps its rules and reports its score", () =>
  withLms(async (lms, browser) => {
    const query = `?sco=pid&launch-query=${encodeURIComponent("attempts=1")}&lms-query=${encodeURIComponent("scorm_launch=1&lms_attempt=7")}`;
    const { context, page, frame, problems } = await launch(browser, lms, query);
    assert.match(await page.evaluate(() => window.lmsLaunched), /\?sco=pid&attempts=1\?scorm_launch=1/);
    await frame.locator('article.exp[data-experiment="pid"]:not([hidden])').waitFor();
    await openQuiz(frame);
    assert.equal(await submitPid(frame, 1), 8);
    assert.match(await frame.locator("form.quiz .quiz-score").innerText(), /1 of 1 attempts graded/);
    assert.deepEqual(sets(await lmsLog(page), "cmi.core.score.raw"), ["8"]);
    assert.equal(await frame.locator("#lms-notice").count(), 0, "connected: nothing to say");
    assert.deepEqual(problems, []);
    await context.close();
  }));

test("SCORM launch query lost (index.html alone): the page says it is not connected and tells the LMS in cmi.comments", () =>
  withLms(async (lms, browser) => {
    // The home page starts no module: wait for the page's line about the LMS.
    const { context, page, frame, problems } = await launch(browser, lms, "?sco=pid&bare=1", null, null, () => document.getElementById("lms-notice"));
    assert.equal(await page.evaluate(() => window.lmsLaunched), "index.html");
    const notice = frame.locator("#lms-notice");
    await notice.waitFor();
    assert.match(await notice.innerText(), /not connected to your LMS: scores will not be recorded/);
    assert.equal(await notice.getAttribute("role"), "alert");
    const [comment] = sets(await lmsLog(page), "cmi.comments");
    assert.match(comment, /launched without its \?sco= query/);
    await page.screenshot({ path: join(ROOT, "target", "e2e-shots", "scorm-not-connected.png") }).catch(() => {});
    assert.deepEqual(problems, []);
    await context.close();
  }));

test("SCORM lesson_mode review: the kept attempt is shown read-only, with no New attempt and no new score", () =>
  withLms(async (lms, browser) => {
    const first = await launch(browser, lms, "?sco=pid");
    await openQuiz(first.frame);
    await answerPid(first.frame);
    const before = await quizShown(first.frame);
    await leave(first.page);
    const saved = await cmiOf(first.page);
    await first.context.close();

    const review = await launch(browser, lms, "?sco=pid&mode=review", saved);
    await openQuiz(review.frame);
    const shown = await quizShown(review.frame);
    assert.deepEqual([shown.seed, shown.checked, shown.typed.length], [before.seed, 1, 1], "the kept attempt");
    const form = review.frame.locator("form.quiz");
    assert.equal(await form.locator("input:not([disabled]), button:not([disabled])").count(), 0, "read-only: no answer, Submit or New attempt");
    assert.match(await review.frame.locator("#lms-notice").innerText(), /^Review: /);
    await leave(review.page);
    const log = await lmsLog(review.page);
    for (const element of ["cmi.core.score.raw", "cmi.core.lesson_status", "cmi.suspend_data"]) {
      assert.deepEqual(sets(log, element), [], `${element} is not written in review`);
    }
    assert.deepEqual(review.problems, []);
    await review.context.close();
  }));

test("SCORM lesson_mode browse and credit no-credit: the quiz is graded on the page and no score is written", () =>
  withLms(async (lms, browser) => {
    for (const [query, notice] of [
      ["?sco=pid&mode=browse", /^Browse mode: your LMS records no score/],
      ["?sco=pid&credit=no-credit", /^No credit: your LMS records no score/],
    ]) {
      const { context, page, frame, problems } = await launch(browser, lms, query);
      await openQuiz(frame);
      assert.equal(await submitPid(frame, 1), 8);
      const log = await lmsLog(page);
      assert.deepEqual(sets(log, "cmi.core.score.raw"), [], query);
      assert.ok(!sets(log, "cmi.core.lesson_status").some((s) => s === "passed" || s === "failed"), query);
      assert.equal(log.filter((e) => e[1]?.startsWith?.("cmi.interactions.")).length, 0, query);
      assert.match(await frame.locator("#lms-notice").innerText(), notice);
      assert.deepEqual(problems, []);
      await context.close();
    }
  }));

test("SCORM suspend_data counted in the same units: 2,100 × 𝑥 pasted into an answer are capped and the attempt is still kept", () =>
  withLms(async (lms, browser) => {
    const { context, page, frame, problems } = await launch(browser, lms, `?sco=pid&launch-query=${encodeURIComponent("attempts=1")}`);
    await openQuiz(frame);
    const field = frame.locator('form.quiz .quiz-q[data-index="6"] input');
    assert.equal(await field.getAttribute("maxlength"), "40", "the page caps a typed answer");
    // Pasted past the cap (a script can set any value): the attempt is still kept.
    await field.evaluate((input) => {
      input.value = "𝑥".repeat(2100);
      input.dispatchEvent(new Event("input", { bubbles: true }));
    });
    await frame.locator('form.quiz .quiz-q[data-index="0"] input[type=radio]').first().check();
    const calls = await page.evaluate(() => window.lmsCalls.filter((c) => c[0] === "LMSSetValue" && c[1] === "cmi.suspend_data"));
    assert.ok(calls.length >= 2);
    for (const [, , value, result] of calls) {
      assert.equal(result, "true", "the LMS took every suspend_data");
      assert.ok(/^[\x20-\x7e]*$/.test(value) && value.length <= 4096, "ASCII, within 4,096 units");
    }
    const kept = JSON.parse((await cmiOf(page)).suspend_data);
    assert.equal(kept.answers[6].Text, "𝑥".repeat(20), "the answer, cut to 40 UTF-16 units");
    assert.equal(kept.answers[0].Choice !== null, true, "the latest answer is kept");
    assert.equal(await frame.locator("#lms-notice").count(), 0);
    assert.deepEqual(problems, []);
    await context.close();
  }));

test("SCORM final LMSCommit on pagehide succeeds in the runtime", () =>
  withLms(async (lms, browser) => {
    const { context, page, frame, problems } = await launch(browser, lms, "?sco=pid");
    await openQuiz(frame);
    await answerPid(frame);
    await leave(page);
    // The runtime posts commits to the LMS server with a synchronous request,
    // which a browser refuses while a page goes away: an LMSCommit in
    // pagehide returned "false". The last data goes with LMSFinish (a beacon).
    const calls = await page.evaluate(() => window.lmsCalls.map((c) => [...c]));
    const commits = calls.filter((c) => c[0] === "LMSCommit");
    assert.ok(commits.length >= 1);
    assert.deepEqual(commits.filter((c) => c.at(-1) !== "true"), [], "every LMSCommit succeeds");
    const [time] = sets(await lmsLog(page), "cmi.core.session_time");
    assert.deepEqual(calls.at(-1), ["LMSFinish", "", "true"]);
    // The last commit the server gets carries the session time and the exit.
    // The runtime writes the timespan in its own form ("00:00:00.50" is
    // posted as "00:00:00.5"), so the two are compared as durations.
    const last = await lms.commitWhere((body) => body.cmi?.core?.exit === "suspend", 'with cmi.core.exit "suspend"');
    assert.equal(timespanSeconds(last.cmi.core.session_time), timespanSeconds(time), `posted ${last.cmi.core.session_time}, set ${time}`);
    assert.equal(last.cmi.core.exit, "suspend");
    assert.equal(JSON.parse(last.cmi.suspend_data).id, "pid");
    assert.deepEqual(problems, []);
    await context.close();
  }));

// ------------------------------------------------ docs/lms.md's package figures

/** Bytes in a docs/lms.md size like `1.80 MiB` or `537 KiB`. */
const readmeBytes = (n, unit) => Number(n) * (unit === "MiB" ? 1024 * 1024 : 1024);

test("docs/lms.md's SCORM package size is the built zip's, within 5 %", async () => {
  const doc = await readFile(join(ROOT, "docs", "lms.md"), "utf8");
  const m = doc.match(/upload \(([\d.]+) (KiB|MiB); ([\d.]+) (KiB|MiB) unzipped/);
  assert.ok(m, "docs/lms.md states the zip's size and the unzipped size");
  const zip = (await stat(join(ROOT, "dist-scorm.zip"))).size;
  let unzipped = 0;
  for (const entry of await readdir(PACKAGE, { recursive: true, withFileTypes: true })) {
    if (entry.isFile()) unzipped += (await stat(join(entry.parentPath ?? entry.path, entry.name))).size;
  }
  const near = (stated, actual, what) =>
    assert.ok(Math.abs(stated - actual) <= 0.05 * actual, `docs/lms.md says ${what} is ${(stated / 1048576).toFixed(2)} MiB; the build has ${(actual / 1048576).toFixed(2)} MiB`);
  near(readmeBytes(m[1], m[2]), zip, "dist-scorm.zip");
  near(readmeBytes(m[3], m[4]), unzipped, "dist-scorm/");
});
