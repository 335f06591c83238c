// SCORM 1.2 run-time glue. Loaded on every page; outside an LMS it finds no
// `API` object and does nothing at all.
//
// Inside an LMS (the lab uploaded as dist-scorm.zip, see README "LMS (SCORM
// 1.2)"), it finds the LMS's `API` object in a parent frame or the opener,
// calls LMSInitialize, and reports what the quiz of the experiment this SCO
// was launched for does (crates/labweb/src/lms.rs sends the events):
//   cmi.core.lesson_status   incomplete on the first launch; passed or failed
//                            on a submission (mastery: the LMS's
//                            cmi.student_data.mastery_score, else 70 %)
//   cmi.core.score.raw/min/max  the quiz's percentage, 0 and 100
//   cmi.suspend_data         the attempt (seed, answers, submitted), at most
//                            4,096 characters, so a relaunch resumes it
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
    experiment: launchedExperiment(win.location.hash),
    suspendData: call("LMSGetValue", "cmi.suspend_data"),
    mastery: masteryOf(call("LMSGetValue", "cmi.student_data.mastery_score")),
    finished: false,
  };
  const status = call("LMSGetValue", "cmi.core.lesson_status");
  if (status === "" || status === "not attempted") {
    call("LMSSetValue", "cmi.core.lesson_status", "incomplete");
  }
  call("LMSCommit", "");

  // A SCO reports only the experiment it was launched for (an instructor
  // placed that one); others opened inside it behave as outside an LMS.
  const ours = (id) => state.experiment === null || id === state.experiment;
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
    call("LMSSetValue", "cmi.core.score.min", "0");
    call("LMSSetValue", "cmi.core.score.max", "100");
    call("LMSSetValue", "cmi.core.score.raw", String(d.percent));
    call("LMSSetValue", "cmi.core.lesson_status", lessonStatus(d.percent, state.mastery));
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
