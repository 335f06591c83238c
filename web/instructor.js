// The Instructor panel of the Simulation tab: a lock and a hide box per
// parameter, the note, the quiz seed, the lab report's answer key, and the
// link they make from the current state, with a Copy button.
//
// A student never needs it, so it is not part of any experiment's download:
// `main.js` fetches this file (shipped as `instructor.<hash>.js`) the first
// time a panel is opened, or as the pointer or keyboard focus reaches its
// summary, and calls `build`. The wasm module (labweb `sim/instructor.rs`)
// leaves a placeholder with what the panel needs:
//
//   <details class="instructor-panel" data-instructor="lock=kp&note=Hi&quiz=5">
//     <summary>Instructor</summary>
//     <div class="instructor-body">… <data value="kp" data-unit="">Kp</data> …</div>
//   </details>
//
// - one `<data>` per parameter: its key, unit and label (as text);
// - `data-instructor`: the open link's instructor settings as labcore's
//   `route::Instructor::query` writes them, then the quiz seed; rewritten
//   whenever a link sets them (the panel starts again from it);
// - a `lab-link` event on the open panel after each write of the page's link.
//
// The link is the page's own (`location.hash`, which the wasm keeps equal to
// the state shown) with the instructor's keys replaced by the panel's, each
// encoded as labcore's `route::encode` does, so `route::parse` reads them
// back exactly. The key names and the note's length are labcore's (xtask
// test `instructor_js_uses_labcores_link_keys`).

const NOTE_MAX_CHARS = 280;
const LOCK_KEY = "lock";
const HIDE_KEY = "hide";
const NOTE_KEY = "note";
const ANSWER_KEY_KEY = "key";
const QUIZ_KEY = "quiz";
/** The quiz's grading rules: the panel has no field for them, the link's stay. */
const RULE_KEYS = ["attempts", "score"];
const INSTRUCTOR_KEYS = [LOCK_KEY, HIDE_KEY, NOTE_KEY, ANSWER_KEY_KEY, QUIZ_KEY, ...RULE_KEYS];
const U64_MAX = 18446744073709551615n;
/** The hidden parameters' values, veiled (labcore's `route::VEILED_KEY`). */
const VEILED_KEY = "hv";

/** labcore's `route::veil`: each UTF-8 byte XOR-ed with a mask that changes
 * along the text, as two hex digits. Out of sight, not secret. */
const mask = (i) => (i * 29 + 0x5a) & 255;
const veil = (text) =>
  Array.from(new TextEncoder().encode(text), (b, i) => (b ^ mask(i)).toString(16).toUpperCase().padStart(2, "0")).join("");
/** labcore's `route::unveil`; null for a blob `veil` cannot have written. */
function unveil(blob) {
  if (!/^(?:[0-9a-fA-F]{2})*$/.test(blob)) return null;
  try {
    const bytes = Uint8Array.from(blob.match(/../g) ?? [], (h, i) => parseInt(h, 16) ^ mask(i));
    return new TextDecoder("utf-8", { fatal: true }).decode(bytes);
  } catch {
    return null;
  }
}

const escapeHtml = (s) =>
  s.replace(/[&<>"']/g, (c) => ({ "&": "&amp;", "<": "&lt;", ">": "&gt;", '"': "&quot;", "'": "&#39;" })[c]);

/** labcore's `route::encode`: every UTF-8 byte but A–Z a–z 0–9 - . _ ~ as %XX. */
const encode = (s) =>
  Array.from(new TextEncoder().encode(s), (b) => {
    const c = String.fromCharCode(b);
    return /[A-Za-z0-9._~-]/.test(c) ? c : `%${b.toString(16).toUpperCase().padStart(2, "0")}`;
  }).join("");

/** A query key as labcore's `route::decode` reads it (`+` a space, %XX a byte). */
const decodeKey = (k) =>
  k.replace(/\+/g, " ").replace(/%([0-9a-fA-F]{2})/g, (_, hex) => String.fromCharCode(parseInt(hex, 16)));

/** labcore's `route::clean_note`: control characters become spaces, the
 * ends are trimmed, at most NOTE_MAX_CHARS characters; empty: no note. */
function cleanNote(raw) {
  // eslint-disable-next-line no-control-regex
  const text = raw.replace(/[\u0000-\u001f\u007f-\u009f]/g, " ").trim();
  if (!text) return null;
  const chars = Array.from(text);
  return chars.length > NOTE_MAX_CHARS ? chars.slice(0, NOTE_MAX_CHARS).join("").trimEnd() : text;
}

/** The quiz seed typed: a whole number as Rust's `u64` parses it, or null. */
function quizSeed(raw) {
  const text = raw.trim();
  if (!/^\+?[0-9]+$/.test(text)) return null;
  const seed = BigInt(text);
  return seed <= U64_MAX ? seed.toString() : null;
}

function panelHtml(params) {
  const rows = params
    .map(({ key, label, unit }) => {
      const k = escapeHtml(key);
      const l = escapeHtml(label);
      const u = unit ? ` <span class="unit">(${escapeHtml(unit)})</span>` : "";
      return (
        `<tr><th scope="row">${l}${u}</th>` +
        `<td><input type="checkbox" data-lock="${k}" aria-label="Lock ${l}"></td>` +
        `<td><input type="checkbox" data-hide="${k}" aria-label="Hide ${l}"></td></tr>`
      );
    })
    .join("");
  return (
    "<p>Set up the simulation, then choose what your students may change. The link below opens " +
    "this state with the locked controls shown but fixed, the hidden ones left out and your note " +
    "above the simulation. It is a teaching aid, not a lock: a student can edit the link.</p>" +
    '<div class="table-scroll"><table class="instructor-params"><caption>Parameters</caption>' +
    '<thead><tr><th scope="col">Parameter</th><th scope="col">Lock</th><th scope="col">Hide</th></tr></thead>' +
    `<tbody>${rows}</tbody></table></div>` +
    `<label class="instructor-field">Note for the students (plain text, up to ${NOTE_MAX_CHARS} characters)` +
    `<input type="text" class="instructor-note-input" maxlength="${NOTE_MAX_CHARS}" autocomplete="off"></label>` +
    '<label class="instructor-field">Quiz seed (the same questions for the whole class; empty: each student draws their own)' +
    '<input type="text" class="instructor-quiz" inputmode="numeric" autocomplete="off" spellcheck="false"></label>' +
    "<label class=\"instructor-field\">Expected answers in a student's lab report (by default never with a quiz seed, else after submission)" +
    '<select class="instructor-key"><option value="">Default</option>' +
    '<option value="never">Never</option><option value="submitted">After submission</option>' +
    '<option value="always">Always</option></select></label>' +
    '<label class="instructor-field">Link' +
    '<input type="text" class="instructor-link" readonly></label>' +
    '<p class="instructor-actions"><button type="button" class="mini" data-instructor="copy">Copy link</button> ' +
    '<span class="instructor-copied" role="status"></span></p>'
  );
}

/** Sets the panel's fields from the open link's settings (`data-instructor`). */
function fill(panel) {
  const settings = new URLSearchParams(panel.dataset.instructor ?? "");
  const list = (key) => (settings.get(key) ?? "").split(",").filter(Boolean);
  const locked = list(LOCK_KEY);
  const hidden = list(HIDE_KEY);
  for (const box of panel.querySelectorAll("input[data-lock]")) box.checked = locked.includes(box.dataset.lock);
  for (const box of panel.querySelectorAll("input[data-hide]")) box.checked = hidden.includes(box.dataset.hide);
  panel.querySelector(".instructor-note-input").value = settings.get(NOTE_KEY) ?? "";
  panel.querySelector(".instructor-quiz").value = settings.get(QUIZ_KEY) ?? "";
  panel.querySelector(".instructor-key").value = settings.get(ANSWER_KEY_KEY) ?? "";
}

/** The panel's link: the page's link (`hash`) with the instructor's keys
 * replaced by the panel's, in the order labcore writes them (locks, hides,
 * note, the link's grading rules, answer key, quiz seed), as a full address. */
function instructorLink(panel, hash) {
  const at = hash.indexOf("?");
  const path = at < 0 ? hash : hash.slice(0, at);
  const keyOf = (pair) => decodeKey(pair.split("=", 1)[0]);
  // The page's hidden values come out of their veil, in their place.
  const pairs = (at < 0 ? [] : hash.slice(at + 1).split("&").filter(Boolean)).flatMap((p) => {
    const text = keyOf(p) === VEILED_KEY ? unveil(p.slice(p.indexOf("=") + 1)) : null;
    return text === null ? [p] : text.split("&");
  });
  let out = pairs.filter((p) => !INSTRUCTOR_KEYS.includes(keyOf(p)));
  const boxes = (attr) => [...panel.querySelectorAll(`input[data-${attr}]`)].filter((b) => b.checked).map((b) => b.dataset[attr]);
  const checked = (attr) => boxes(attr).map(encode);
  const locked = checked(LOCK_KEY);
  const hidden = checked(HIDE_KEY);
  // The values the panel hides go veiled, together where the first stood
  // (labcore's `route::veil_hidden`).
  const isHidden = (p) => boxes(HIDE_KEY).includes(keyOf(p));
  const first = out.findIndex(isHidden);
  if (first >= 0) {
    const veiled = `${VEILED_KEY}=${veil(out.filter(isHidden).join("&"))}`;
    out = out.filter((p) => !isHidden(p));
    out.splice(first, 0, veiled);
  }
  if (locked.length) out.push(`${LOCK_KEY}=${locked.join(",")}`);
  if (hidden.length) out.push(`${HIDE_KEY}=${hidden.join(",")}`);
  const note = cleanNote(panel.querySelector(".instructor-note-input").value);
  if (note) out.push(`${NOTE_KEY}=${encode(note)}`);
  out.push(...pairs.filter((p) => RULE_KEYS.includes(keyOf(p))));
  const answerKey = panel.querySelector(".instructor-key").value;
  if (answerKey) out.push(`${ANSWER_KEY_KEY}=${encode(answerKey)}`);
  const seed = quizSeed(panel.querySelector(".instructor-quiz").value);
  if (seed !== null) out.push(`${QUIZ_KEY}=${seed}`);
  const base = location.href.split("#")[0];
  return `${base}${path}${out.length ? `?${out.join("&")}` : ""}`;
}

/** Rebuilds the open panel's link from the page's current link. */
function sync(panel) {
  const field = panel.querySelector(".instructor-link");
  const hash = location.hash;
  // The panel lives on the Simulation tab, whose link holds the state.
  if (!panel.open || !field || !/^#\/[^/?]+\/simulation(\?|$)/.test(hash)) return;
  const link = instructorLink(panel, hash);
  if (field.value !== link) field.value = link;
}

/** Selects the link (so Ctrl+C works where the clipboard is not offered)
 * and copies it where the browser allows. */
function copy(panel) {
  sync(panel);
  const field = panel.querySelector(".instructor-link");
  field.select();
  let copied = false;
  try {
    const writing = navigator.clipboard?.writeText(field.value);
    if (writing) {
      // A refusal (no permission) must not reach the console as an
      // unhandled rejection: the field is selected anyway.
      writing.catch(() => {});
      copied = true;
    }
  } catch {
    copied = false;
  }
  panel.querySelector(".instructor-copied").textContent = copied
    ? "Copied."
    : "Selected: press Ctrl+C (⌘C) to copy.";
}

const built = new WeakSet();

/** Builds the Instructor panel in the placeholder `panel` (once; its
 * listeners go with it when the simulation is mounted again) and brings its
 * link up to date. */
export function build(panel) {
  if (!built.has(panel)) {
    built.add(panel);
    const body = panel.querySelector(".instructor-body");
    const params = [...body.querySelectorAll("data")].map((d) => ({
      key: d.value,
      label: d.textContent,
      unit: d.dataset.unit ?? "",
    }));
    body.innerHTML = panelHtml(params);
    fill(panel);
    for (const kind of ["input", "change", "toggle", "lab-link"]) panel.addEventListener(kind, () => sync(panel));
    panel.addEventListener("click", (e) => {
      if (e.target.closest?.("[data-instructor=copy]")) copy(panel);
    });
    // A link that sets the instructor's settings (opened, Back, a preset)
    // puts the panel back to them, as it put the page.
    new MutationObserver(() => {
      fill(panel);
      sync(panel);
    }).observe(panel, { attributes: true, attributeFilter: ["data-instructor"] });
  }
  sync(panel);
}

// A link typed or followed (not a write of the page's own, which says
// `lab-link`): the open panels follow it.
addEventListener("hashchange", () => {
  for (const panel of document.querySelectorAll(".instructor-panel[open]")) if (built.has(panel)) sync(panel);
});
