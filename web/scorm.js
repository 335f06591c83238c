// SCORM 1.2 run-time glue. `main.js` loads it only inside a frame or a
// window opened by another (how an LMS launches a SCO); even there, without
// an `API` object it does nothing at all.
//
// Inside an LMS (the lab uploaded as dist-scorm.zip, see docs/lms.md), it
// finds the LMS's `API` object in a parent frame or the opener,
// calls LMSInitialize, and reports what the quiz of the experiment this SCO
// was launched for does (crates/labweb/src/lms.rs sends the events). The SCO
// is named by the launch's query (`index.html?sco=pid`), which an LMS keeps
// where some drop the `#` fragment; the quizzes of other experiments opened
// inside it are never reported.
//   cmi.core.lesson_status   incomplete on the first launch; passed or failed
//                            on a submission (mastery: the LMS's
//                            cmi.student_data.mastery_score, else 70 %)
//   cmi.core.score.raw/min/max  the percentage that counts (best, last or
//                            first graded attempt, see docs/lms.md), 0 and 100
//   cmi.interactions.n.*     each question of each graded attempt: id
//                            (`pid-q3`), type (choice or numeric),
//                            student_response, result (correct or wrong),
//                            correct_responses.0.pattern, weighting, time
//   cmi.suspend_data         the attempt (seed, answers, submitted, attempts
//                            graded), at most 4,096 characters, so a
//                            relaunch resumes it
//   cmi.core.session_time    on leaving (CMITimespan HHHH:MM:SS.SS)
//   cmi.comments             only when the launch names no SCO
// with an LMSCommit after each change, and LMSFinish (which commits the
// session time) when the page goes away. A review launch writes nothing;
// browse and no-credit write no score (cmi.core.lesson_mode, credit).
// Reference: ADL, SCORM Version 1.2 Run-Time Environment (2001), §3.3 (API,
// FindAPI) and §3.4 (data model).

export const SUSPEND_DATA_MAX = 4096;
export const DEFAULT_MASTERY = 70;
/** How many frames up findAPI looks (ADL's sample uses 7). */
export const MAX_HOPS = 10;

/** True when `win` holds a SCORM 1.2 API object (false across origins). */
function hasApi(win) {
  try {
    return Boolean(win.API) && typeof win.API.LMSInitialize === "function";
  } catch {
    return false; // a cross-origin frame: not ours to read
  }
}

/** The API object in `win` or one of its parents, at most MAX_HOPS up. */
export function findAPI(win) {
  for (let hops = 0; win && hops <= MAX_HOPS; hops++) {
    if (hasApi(win)) return win.API;
    let parent = null;
    try {
      parent = win.parent;
    } catch {
      return null;
    }
    if (!parent || parent === win) return null;
    win = parent;
  }
  return null;
}

/** ADL's GetAPI: the frames above `win`, then those above its opener. */
export function getAPI(win) {
  const found = findAPI(win);
  if (found) return found;
  for (const opener of [() => win.top?.opener, () => win.opener]) {
    try {
      const o = opener();
      const api = o && findAPI(o);
      if (api) return api;
    } catch {
      // the opener is on another origin
    }
  }
  return null;
}

/** Milliseconds as a SCORM 1.2 CMITimespan, `HH:MM:SS.SS` (hours up to 9999). */
export function sessionTime(ms) {
  const centis = Math.max(0, Math.min(Math.round(ms / 10), 9999 * 360000 + 359999));
  const hours = Math.floor(centis / 360000);
  const minutes = Math.floor((centis % 360000) / 6000);
  const seconds = (centis % 6000) / 100;
  const two = (n) => String(n).padStart(2, "0");
  return `${two(hours)}:${two(minutes)}:${seconds.toFixed(2).padStart(5, "0")}`;
}

/** passed or failed for a percentage against a mastery percentage. */
export function lessonStatus(percent, mastery) {
  return percent >= mastery ? "passed" : "failed";
}

/** The mastery percentage the LMS passes on, else DEFAULT_MASTERY. */
export function masteryOf(text) {
  const m = text === "" || text == null ? NaN : Number(text);
  return Number.isFinite(m) && m >= 0 && m <= 100 ? m : DEFAULT_MASTERY;
}

/** The experiment a launch URL's hash names (`#/pid/aim` → `pid`), or null. */
export function launchedExperiment(hash) {
  const m = /^#\/([A-Za-z0-9_-]+)/.exec(hash || "");
  return m ? m[1] : null;
}

/**
 * The experiment a SCO was launched for: the leading id of its launch
 * query's `sco` (`index.html?sco=pid`; an LMS that appends its own query
 * with a second `?`, `?sco=pid?scorm_launch=1&…`, is read as if it had used
 * `&`), else (a package from before the query) the hash it was launched
 * with; null when neither names one. labcore::lms::launch reads it the same
 * way for the wasm.
 */
export function scoOf(location) {
  const query = (location.search || "").replace(/^\?/, "").replaceAll("?", "&");
  const sco = /^[A-Za-z0-9_-]+/.exec(new URLSearchParams(query).get("sco") || "");
  return sco ? sco[0] : launchedExperiment(location.hash);
}

/** What the page says for an LMS launch mode and credit (empty: nothing). */
export function modeNotice(mode, credit) {
  if (mode === "review") {
    return "Review: this is the attempt your LMS kept, shown read-only. Nothing you do here is recorded.";
  }
  if (mode === "browse") return "Browse mode: your LMS records no score for this visit.";
  if (credit === "no-credit") return "No credit: your LMS records no score for this launch.";
  return "";
}

/** The page's line about the LMS (created on first use; several messages join). */
function say(win, text) {
  const doc = win.document;
  if (!doc?.body || !text) return;
  let box = doc.getElementById("lms-notice");
  if (!box) {
    box = doc.createElement("div");
    box.id = "lms-notice";
    box.className = "notice";
    box.setAttribute("role", "alert");
    doc.body.insertBefore(box, doc.getElementById("app"));
  }
  if (!box.textContent.includes(text)) box.textContent = `${box.textContent} ${text}`.trim();
}

/** A number as a SCORM 1.2 CMIDecimal (`-12.5`, at most 6 decimals), or null. */
export function cmiDecimal(value) {
  return Number.isFinite(value) && Math.abs(value) < 1e10 ? String(Number(value.toFixed(6))) : null;
}

/** An option number (0-based, content order) as a choice response letter (`a`…`z`). */
export function choiceLetter(k) {
  return Number.isInteger(k) && k >= 0 && k < 26 ? String.fromCharCode(97 + k) : null;
}

/**
 * One graded question as `cmi.interactions.n` elements (id first, as the
 * data model asks): `row` is `[choice, given, correct, expected]` from
 * lms.rs (option numbers for a choice, values for a numeric question).
 */
export function interaction(id, index, row, time) {
  const [choice, given, correct, expected] = row;
  const format = choice ? choiceLetter : cmiDecimal;
  const out = [
    ["id", `${id}-q${index + 1}`],
    ["type", choice ? "choice" : "numeric"],
  ];
  const response = given == null ? null : format(given);
  if (response !== null) out.push(["student_response", response]);
  out.push(["result", correct ? "correct" : "wrong"]);
  const pattern = format(expected);
  if (pattern !== null) out.push(["correct_responses.0.pattern", pattern]);
  out.push(["weighting", "1"], ["time", time]);
  return out;
}

/** A time of day as a SCORM 1.2 CMITime (`HH:MM:SS`). */
export function cmiTime(date) {
  const two = (n) => String(n).padStart(2, "0");
  return `${two(date.getHours())}:${two(date.getMinutes())}:${two(date.getSeconds())}`;
}

/** Local-storage keys an older lab wrote an attempt under (readable by any tab). */
const LEAKED = /^labquiz:/;

/**
 * Runs a SCORM session against `api` for the page `win`. Returns the
 * session's state (for tests), or null when LMSInitialize refuses.
 */
export function startSession(win, api, now = () => Date.now()) {
  const call = (name, ...args) => {
    try {
      return String(api[name](...args));
    } catch {
      return "";
    }
  };
  if (call("LMSInitialize", "") !== "true") return null;
  const started = now();
  const get = (element) => call("LMSGetValue", element);
  const mode = get("cmi.core.lesson_mode");
  const credit = get("cmi.core.credit");
  const state = {
    experiment: scoOf(win.location),
    suspendData: get("cmi.suspend_data"),
    mastery: masteryOf(get("cmi.student_data.mastery_score")),
    finished: false,
    // The next free cmi.interactions index (the journal grows per grading).
    interactions: Math.max(0, Number(get("cmi.interactions._count")) || 0),
    // review: nothing is written; browse and no-credit: no score.
    review: mode === "review",
    scored: mode !== "review" && mode !== "browse" && credit !== "no-credit",
    refused: [],
  };
  // A value the LMS refuses is said on the page (with the LMS's reason),
  // never dropped in silence.
  const set = (element, value) => {
    if (call("LMSSetValue", element, value) === "false") {
      const code = call("LMSGetLastError");
      const why = call("LMSGetErrorString", code);
      state.refused.push(element);
      say(win, `Your LMS did not save ${element} (error ${code}${why ? `: ${why}` : ""}); tell your instructor.`);
    }
  };
  const status = get("cmi.core.lesson_status");
  if (!state.review && mode !== "browse" && (status === "" || status === "not attempted")) {
    set("cmi.core.lesson_status", "incomplete");
  }
  call("LMSCommit", "");
  // An attempt a lab before issue 51 kept in local storage, where another
  // tab or another learner would find it, is removed.
  try {
    for (const key of Object.keys(win.localStorage ?? {})) {
      if (LEAKED.test(key)) win.localStorage.removeItem(key);
    }
  } catch {
    // storage off
  }
  say(win, modeNotice(mode, credit));
  if (state.experiment === null) {
    // The launch's query was lost: nothing can be reported; say so here and
    // to the LMS rather than drop a score in silence.
    say(win, "This page is not connected to your LMS: scores will not be recorded. Reopen the activity from your course.");
    set("cmi.comments", "The lab was launched without its ?sco= query (the LMS dropped it): no score can be recorded.");
    call("LMSCommit", "");
  }

  // A SCO reports only the experiment it was launched for (an instructor
  // placed that one); others opened inside it behave as outside an LMS. A
  // launch that names none reports nothing rather than a wrong score.
  const ours = (id) => state.experiment !== null && id === state.experiment;
  const keep = (text) => {
    if (state.review || mode === "browse" || typeof text !== "string") return;
    if (text.length > SUSPEND_DATA_MAX) {
      say(win, "Your attempt is too long for your LMS and was not saved.");
      return;
    }
    state.suspendData = text;
    set("cmi.suspend_data", text);
  };

  win.labLms = Object.freeze({
    /** The attempt the LMS keeps for `id` (read by the wasm), or null. */
    suspendData: (id) => (ours(id) && state.suspendData ? state.suspendData : null),
    /** A review launch: the wasm shows the kept attempt read-only. */
    review: state.review,
    /** The LMS's learner (cmi.core.student_id): the report's fields are kept per learner. */
    learner: get("cmi.core.student_id"),
  });
  win.addEventListener("lab-quiz-progress", (e) => {
    if (!state.finished && ours(e.detail?.id)) keep(e.detail.suspendData);
  });
  win.addEventListener("lab-quiz-submitted", (e) => {
    const d = e.detail ?? {};
    if (state.finished || !ours(d.id) || !Number.isFinite(d.percent)) return;
    if (state.scored) {
      // The instructor's rule (best, last or first attempt) made `counted`.
      const counted = Number.isFinite(d.counted) ? d.counted : d.percent;
      set("cmi.core.score.min", "0");
      set("cmi.core.score.max", "100");
      set("cmi.core.score.raw", String(counted));
      set("cmi.core.lesson_status", lessonStatus(counted, state.mastery));
      const time = cmiTime(new Date(now()));
      for (const [i, row] of (Array.isArray(d.questions) ? d.questions : []).entries()) {
        if (!Array.isArray(row)) continue;
        const n = state.interactions++;
        for (const [key, value] of interaction(d.id, i, row, time)) {
          set(`cmi.interactions.${n}.${key}`, value);
        }
      }
    }
    keep(d.suspendData);
    call("LMSCommit", "");
  });
  // Leaving: no LMSCommit here. A runtime that posts a commit with a
  // synchronous request (scorm-again with an LMS server does) fails while
  // the page goes away, as browsers refuse such requests then; LMSFinish
  // commits the last values itself, with a beacon.
  win.addEventListener("pagehide", () => {
    if (state.finished) return;
    state.finished = true;
    call("LMSSetValue", "cmi.core.session_time", sessionTime(now() - started));
    // "suspend": the LMS keeps suspend_data for the next launch.
    call("LMSSetValue", "cmi.core.exit", "suspend");
    call("LMSFinish", "");
  });
  return state;
}

if (typeof window !== "undefined") {
  const api = getAPI(window);
  if (api) startSession(window, api);
}
