// SCORM 1.2 run-time glue. `main.js` loads it only inside a frame or a
// window opened by another (how an LMS launches a SCO); even there, without
// an `API` object it does nothing at all.
//
// Inside an LMS (the lab uploaded as dist-scorm.zip, see README "LMS (SCORM
// 1.2)"), it finds the LMS's `API` object in a parent frame or the opener,
// calls LMSInitialize, and reports what the quiz of the experiment this SCO
// was launched for does (crates/labweb/src/lms.rs sends the events). The SCO
// is named by the launch's query (`index.html?sco=pid`), which an LMS keeps
// where some drop the `#` fragment; the quizzes of other experiments opened
// inside it are never reported.
//   cmi.core.lesson_status   incomplete on the first launch; passed or failed
//                            on a submission (mastery: the LMS's
//                            cmi.student_data.mastery_score, else 70 %)
//   cmi.core.score.raw/min/max  the percentage that counts (best, last or
//                            first graded attempt, see README), 0 and 100
//   cmi.interactions.n.*     each question of each graded attempt: id
//                            (`pid-q3`), type (choice or numeric),
//                            student_response, result (correct or wrong),
//                            correct_responses.0.pattern, weighting, time
//   cmi.suspend_data         the attempt (seed, answers, submitted, attempts
//                            graded), at most 4,096 characters, so a
//                            relaunch resumes it
//   cmi.core.session_time    on leaving (CMITimespan HHHH:MM:SS.SS)
// then LMSCommit, and LMSFinish when the page goes away.
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
 * The experiment a SCO was launched for: its launch query's `sco`
 * (`index.html?sco=pid`), else (a package from before the query) the hash it
 * was launched with; null when neither names one.
 */
export function scoOf(location) {
  const sco = new URLSearchParams(location.search || "").get("sco");
  return sco && /^[A-Za-z0-9_-]+$/.test(sco) ? sco : launchedExperiment(location.hash);
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
  const state = {
    experiment: scoOf(win.location),
    suspendData: call("LMSGetValue", "cmi.suspend_data"),
    mastery: masteryOf(call("LMSGetValue", "cmi.student_data.mastery_score")),
    finished: false,
    // The next free cmi.interactions index (the journal grows per grading).
    interactions: Math.max(0, Number(call("LMSGetValue", "cmi.interactions._count")) || 0),
  };
  const status = call("LMSGetValue", "cmi.core.lesson_status");
  if (status === "" || status === "not attempted") {
    call("LMSSetValue", "cmi.core.lesson_status", "incomplete");
  }
  call("LMSCommit", "");

  // A SCO reports only the experiment it was launched for (an instructor
  // placed that one); others opened inside it behave as outside an LMS. A
  // launch that names none reports nothing rather than a wrong score.
  const ours = (id) => state.experiment !== null && id === state.experiment;
  const keep = (text) => {
    if (typeof text !== "string" || text.length > SUSPEND_DATA_MAX) return;
    state.suspendData = text;
    call("LMSSetValue", "cmi.suspend_data", text);
  };

  win.labLms = Object.freeze({
    /** The attempt the LMS keeps for `id` (read by the wasm), or null. */
    suspendData: (id) => (ours(id) && state.suspendData ? state.suspendData : null),
  });
  win.addEventListener("lab-quiz-progress", (e) => {
    if (!state.finished && ours(e.detail?.id)) keep(e.detail.suspendData);
  });
  win.addEventListener("lab-quiz-submitted", (e) => {
    const d = e.detail ?? {};
    if (state.finished || !ours(d.id) || !Number.isFinite(d.percent)) return;
    // The instructor's rule (best, last or first attempt) made `counted`.
    const counted = Number.isFinite(d.counted) ? d.counted : d.percent;
    call("LMSSetValue", "cmi.core.score.min", "0");
    call("LMSSetValue", "cmi.core.score.max", "100");
    call("LMSSetValue", "cmi.core.score.raw", String(counted));
    call("LMSSetValue", "cmi.core.lesson_status", lessonStatus(counted, state.mastery));
    const time = cmiTime(new Date(now()));
    for (const [i, row] of (Array.isArray(d.questions) ? d.questions : []).entries()) {
      if (!Array.isArray(row)) continue;
      const n = state.interactions++;
      for (const [key, value] of interaction(d.id, i, row, time)) {
        call("LMSSetValue", `cmi.interactions.${n}.${key}`, value);
      }
    }
    keep(d.suspendData);
    call("LMSCommit", "");
  });
  win.addEventListener("pagehide", () => {
    if (state.finished) return;
    state.finished = true;
    call("LMSSetValue", "cmi.core.session_time", sessionTime(now() - started));
    // "suspend": the LMS keeps suspend_data for the next launch.
    call("LMSSetValue", "cmi.core.exit", "suspend");
    call("LMSCommit", "");
    call("LMSFinish", "");
  });
  return state;
}

if (typeof window !== "undefined") {
  const api = getAPI(window);
  if (api) startSession(window, api);
}
