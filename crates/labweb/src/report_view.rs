//! The "Lab report" button of the Simulation tab: gathers what the report
//! needs from the page (the absolute link of the run, the student's clock,
//! the quiz attempt if it was submitted, an instructor's note and answer-key
//! choice from the link, the name, group and observations the student typed)
//! copies what the report prints into a [`labpage::report::Sheet`], and
//! hands it as bytes to the report module, which builds the file, then
//! offers the file as a download made in the page from a Blob (nothing
//! leaves the browser).
//!
//! The report module (`pkg/report.<hash>.wasm`, crate `labreport`) is
//! downloaded the first time it is needed (`main.js`'s `labReport`), not with
//! the experiment: making the file is about 18 KB of gzipped code that most
//! visits never run.
//!
//! The typed fields are kept in local storage per experiment
//! (`labreport:<id>`; inside an LMS per learner, see
//! [`crate::lms::report_storage_key`]), so they survive a reload and fill
//! the next report.
//! [`report_quiz_score`] serves the site's "Check a report" page.

use crate::dom::{self, escape, query, query_all};
use crate::plot_view;
use crate::quiz_view::{self, Attempt};
use labcore::quiz::Response;
use labcore::route::{self, Page};
use labcore::Lab;
use labpage::report::{self, AnswerKey, MarkedMoment, QuizResult, Report, Sheet, Student};
use wasm_bindgen::prelude::*;
use web_sys::Element;

/// The button, placed among the Simulation tab's actions.
pub const BUTTON_HTML: &str =
    "<button type=\"button\" class=\"mini\" data-export=\"report\">Lab report</button>";

/// The fields of the report a student fills in, in the order stored.
const FIELDS: [&str; 3] = ["name", "group", "observations"];
/// Separates the stored fields (a character no one types).
const SEPARATOR: char = '\u{1f}';

/// The fields kept for experiment `id`, joined by [`SEPARATOR`] in
/// [`FIELDS`] order (empty when none or no storage).
fn stored(id: &str) -> String {
    dom::window()
        .local_storage()
        .ok()
        .flatten()
        .zip(crate::lms::report_storage_key(id))
        .and_then(|(s, key)| s.get_item(&key).ok().flatten())
        .unwrap_or_default()
}

/// The Name, Group and Observations fields under the actions, filled with
/// what was kept for this experiment.
#[must_use]
pub fn fields_html(id: &str) -> String {
    let kept = stored(id);
    let mut kept = kept.split(SEPARATOR);
    let mut next = || escape(kept.next().unwrap_or(""));
    let (name, group, observations) = (next(), next(), next());
    format!(
        "<details class=\"report-fields\"><summary>Name, group and observations for the lab report \
         (kept in this browser, printed in the report)</summary>\
         <label class=\"instructor-field\">Name<input data-report-field=\"name\" maxlength=\"120\" value=\"{}\"></label>\
         <label class=\"instructor-field\">Group<input data-report-field=\"group\" maxlength=\"60\" value=\"{}\"></label>\
         <label class=\"instructor-field\">Observations and conclusions<textarea data-report-field=\"observations\" rows=\"5\" maxlength=\"4000\">{}</textarea></label></details>",
        name, group, observations
    )
}

/// What the fields in `panel` say now, joined by [`SEPARATOR`] in
/// [`FIELDS`] order (a separator typed becomes a space).
fn typed(panel: &Element) -> String {
    let mut out = String::new();
    for (i, f) in FIELDS.iter().enumerate() {
        if i > 0 {
            out.push(SEPARATOR);
        }
        // An input's or a textarea's `value` (one binding for both).
        let value = query(panel, &format!("[data-report-field={f}]"))
            .and_then(|el| js_sys::Reflect::get(&el, &JsValue::from_str("value")).ok())
            .and_then(|v| v.as_string())
            .unwrap_or_default();
        out.push_str(&value.replace(SEPARATOR, " "));
    }
    out
}

/// Keeps the fields of `panel` for experiment `id` (a field's `change`);
/// returns them as [`typed`] does.
pub fn remember(panel: &Element, id: &str) -> String {
    let text = typed(panel);
    if let (Some(storage), Some(key)) = (
        dom::window().local_storage().ok().flatten(),
        crate::lms::report_storage_key(id),
    ) {
        let _ = storage.set_item(&key, &text);
    }
    text
}

/// The aim's paragraphs (inline HTML) from the Aim tab of `panel`'s
/// article: a shipped module carries no reading content (the page has it).
fn aim_on_page(panel: &Element) -> Vec<String> {
    panel
        .closest("article.exp")
        .ok()
        .flatten()
        .map(|article| {
            query_all(&article, "[data-panel=aim] > p")
                .iter()
                .map(Element::inner_html)
                .collect()
        })
        .unwrap_or_default()
}

/// Builds `<id>-report.html` from the experiment's current state and offers
/// it as a download. `panel` is the Simulation panel (its article holds the
/// quiz); `hash` is the link of the state shown (`#/pid/simulation?…`, with
/// the instructor's keys); `marked` the run's marked moments, each with
/// the state at it (time in seconds, state), a section each. Where the page
/// shows a past moment of the run, `exp` is the run's end (the report shows
/// the whole run) and `shown` the moment (time in seconds, state).
pub fn download(
    panel: &Element,
    exp: &dyn Lab,
    hash: &str,
    marked: &[(f64, Box<dyn Lab>)],
    shown: Option<(f64, &dyn Lab)>,
) {
    let Some(entry) = labcore::find(exp.id()) else {
        return;
    };
    let Ok(content) = entry.content() else {
        return;
    };
    let location = dom::window().location();
    let href = location.href().unwrap_or_default();
    let page = href.split('#').next().unwrap_or_default();
    let link = format!("{page}{hash}");
    let date = now_text();
    let ids: Vec<&str> = labcore::registry().iter().map(|e| e.id).collect();
    let parsed = route::parse(hash, &ids);
    let answer_key = crate::lms::answer_key(hash);
    let quiz = attempt_on_page(panel, entry, content, answer_key == AnswerKey::Always);
    let fields = remember(panel, exp.id());
    let mut fields = fields.split(SEPARATOR);
    let mut next = || fields.next().unwrap_or("");
    let (name, group, observations) = (next(), next(), next());
    let note = match parsed.page {
        Page::Experiment { .. } => parsed.instructor.note,
        Page::Home => None,
    };
    let marks: Vec<MarkedMoment<'_>> = marked
        .iter()
        .map(|(t_s, state)| MarkedMoment {
            t_s: *t_s,
            state: state.as_ref(),
        })
        .collect();
    let mut sheet = Sheet::of(&Report {
        experiment: exp,
        marks: &marks,
        shown: shown.map(|(t_s, state)| MarkedMoment { t_s, state }),
        content,
        link: &link,
        date: &date,
        quiz: quiz
            .as_ref()
            .map(|(attempt, answers, submitted)| QuizResult {
                seed: attempt.seed,
                questions: &attempt.questions,
                answers,
                submitted: *submitted,
            }),
        note: note.as_deref(),
        student: Student {
            name,
            group,
            observations,
        },
        answer_key,
    });
    if sheet.aim.is_empty() {
        sheet.aim = aim_on_page(panel);
    }
    // Hidden means hidden: an instructor's `hide=m` prints no value.
    for row in &mut sheet.params {
        if parsed.instructor.hidden.contains(&row.key) {
            row.value = "hidden".into();
            row.unit.clear();
        }
    }
    make_file(
        &report::wire::encode(&sheet),
        report::file_name(exp.id()),
        panel,
    );
}

/// The page's bridge to the report module (`main.js`): `labReport(bytes,
/// done, failed)` loads the module the first time, then calls `done` with
/// the file's HTML or `failed` with the error.
const BRIDGE: &str = "labReport";

/// Has the report module turn `sheet` into the file and offers it as
/// `file`. The button says it is busy meanwhile; if the module cannot be
/// loaded (offline before it was ever fetched, a broken host) or refuses
/// the bytes, the notice bar says so and the page goes on.
fn make_file(sheet: &[u8], file: String, panel: &Element) {
    let button = query(panel, "[data-export=report]");
    let busy = move |on: bool| {
        if let Some(b) = &button {
            let _ = if on {
                b.set_attribute("aria-busy", "true")
            } else {
                b.remove_attribute("aria-busy")
            };
        }
    };
    let failed = |why: String| {
        dom::notice(&[format!(
            "The lab report could not be made ({why}). Check the connection and press Lab report again."
        )]);
    };
    let bridge = js_sys::Reflect::get(&dom::window(), &JsValue::from_str(BRIDGE))
        .ok()
        .and_then(|f| f.dyn_into::<js_sys::Function>().ok());
    let Some(bridge) = bridge else {
        failed("the page has no report module".into());
        return;
    };
    busy(true);
    let done_busy = busy.clone();
    // One of the two callbacks runs; `once_into_js` frees the one that does.
    let done = Closure::once_into_js(move |html: JsValue| {
        done_busy(false);
        match html.as_string() {
            Some(html) => plot_view::download(&file, "text/html;charset=utf-8", &html),
            None => failed("the report module returned no file".into()),
        }
    });
    let fail = Closure::once_into_js(move |e: JsValue| {
        busy(false);
        failed(error_text(&e));
    });
    let bytes = js_sys::Uint8Array::from(sheet);
    if let Err(e) = bridge.call3(&JsValue::NULL, &bytes, &done, &fail) {
        failed(error_text(&e));
    }
}

/// An error's message (`Error.message`, or the value itself as text).
fn error_text(e: &JsValue) -> String {
    js_sys::Reflect::get(e, &JsValue::from_str("message"))
        .ok()
        .and_then(|m| m.as_string())
        .or_else(|| e.as_string())
        .unwrap_or_else(|| "unknown error".into())
}

/// The student's local date and time with its offset from UTC.
fn now_text() -> String {
    let d = js_sys::Date::new_0();
    // `getTimezoneOffset` is UTC minus local time.
    let offset = -(d.get_timezone_offset() as i32);
    report::date_text(
        d.get_full_year() as i32,
        d.get_month() + 1,
        d.get_date(),
        d.get_hours(),
        d.get_minutes(),
        offset,
    )
}

/// The attempt on the Self-assessment tab, the answers in its form and
/// whether it was graded (the score line is shown only then); an attempt
/// not yet graded only when `unsubmitted_too`. The questions are drawn
/// again from the seed the form shows, exactly as the tab drew them.
fn attempt_on_page(
    panel: &Element,
    entry: &labcore::Entry,
    content: &labcore::Content,
    unsubmitted_too: bool,
) -> Option<(Attempt, Vec<Response>, bool)> {
    let article = panel.closest("article.exp").ok().flatten()?;
    let form = query(&article, "form.quiz")?;
    let submitted = !query(&form, ".quiz-score")?.has_attribute("hidden");
    if !(submitted || unsubmitted_too) {
        return None;
    }
    let seed: u64 = query(&form, ".quiz-seed")?
        .text_content()?
        .trim()
        .parse()
        .ok()?;
    let questions = labcore::quiz::prepare(content, entry.generators, seed).ok()?;
    let attempt = Attempt { seed, questions };
    let answers = quiz_view::responses(&form, &attempt);
    Some((attempt, answers, submitted))
}

/// The "Check a report" page's grader: the score of `answers` (one per
/// question: an option's index, `null` for none, or the text typed) to the
/// questions experiment `id` draws from `seed` (a whole number as text),
/// as `[correct, total]`. Empty when `id` is not in this module, the seed
/// is not a whole number or the number of answers differs.
#[wasm_bindgen]
pub fn report_quiz_score(id: &str, seed: &str, answers: js_sys::Array) -> Vec<u32> {
    let Some(entry) = labcore::find(id) else {
        return Vec::new();
    };
    let (Ok(content), Ok(seed)) = (entry.content(), seed.trim().parse::<u64>()) else {
        return Vec::new();
    };
    let Ok(questions) = labcore::quiz::prepare(content, entry.generators, seed) else {
        return Vec::new();
    };
    if questions.len() != answers.length() as usize {
        return Vec::new();
    }
    let mut responses = Vec::with_capacity(questions.len());
    for i in 0..answers.length() {
        let a = answers.get(i);
        responses.push(match (a.as_f64(), a.as_string()) {
            (Some(k), _) if k >= 0.0 && k.fract() == 0.0 => Response::Choice(Some(k as usize)),
            (_, Some(text)) => Response::Text(text),
            _ => Response::Choice(None),
        });
    }
    let (correct, total) = QuizResult {
        seed,
        questions: &questions,
        answers: &responses,
        submitted: true,
    }
    .score();
    vec![correct as u32, total as u32]
}
