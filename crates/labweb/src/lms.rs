//! The quiz's side of the SCORM 1.2 bridge (`web/scorm.js` is the other).
//!
//! The wasm never talks to an LMS itself. It announces quiz events on
//! `window` and asks one JS global for a saved attempt:
//!
//! - `lab-quiz-progress` (`CustomEvent`), whenever the attempt's answers are
//!   kept: `detail = { id, suspendData }`;
//! - `lab-quiz-submitted`, when an attempt is graded:
//!   `detail = { id, score, max, percent, counted, questions, suspendData }`,
//!   with `score` right answers of `max` questions, `percent` their rounded
//!   percentage, `counted` the percentage the instructor's rule makes count
//!   (best, last or first graded attempt) and `questions` one
//!   `[choice, given, correct, expected]` per question (see [`interactions`]);
//! - `window.labLms.suspendData(id)`, set by `scorm.js` only inside an LMS:
//!   the attempt the LMS kept for experiment `id` (a
//!   [`labcore::lms::Suspended`] text), or `null`.
//!
//! Outside an LMS nobody listens and `window.labLms` does not exist, so the
//! quiz behaves as on the open site (its attempt lives in local storage),
//! except in a page launched as a SCO ([`in_sco`]): there nothing of an
//! attempt is stored in the browser.
//!
//! A package's launch (`index.html?sco=pid&attempts=2&score=first`) also
//! fixes the quiz's grading rules for the whole session: [`launch_rules`].

use labcore::content::Question;
use labcore::lms::{Suspended, Tally};
use labcore::quiz::{grade, Prepared, PreparedKind, Response, SavedAttempt};
use labcore::route::{AnswerKey, QuizRules};
use labcore::units::read_answer;
use wasm_bindgen::{JsCast, JsValue};
use web_sys::{CustomEvent, CustomEventInit, Element};

/// Marks a graded form, so a kept attempt says it was submitted.
pub const SUBMITTED_ATTR: &str = "data-submitted";

/// The experiment a quiz form belongs to (its article's `data-experiment`).
#[must_use]
pub fn experiment_of(form: &Element) -> Option<String> {
    form.closest("[data-experiment]")
        .ok()
        .flatten()?
        .get_attribute("data-experiment")
}

/// What a SCORM launch's query says (`index.html?sco=pid&attempts=2`, see
/// `cargo xtask dist --scorm`, read by [`labcore::lms::launch`]): the
/// package's rules, which no link opened inside the SCO changes. `None`
/// for a page not launched as a SCO.
#[must_use]
pub fn launch() -> Option<labcore::lms::Launch> {
    labcore::lms::launch(&web_sys::window()?.location().search().ok()?)
}

/// The grading rules of a SCORM launch; `None` outside a SCO.
#[must_use]
pub fn launch_rules() -> Option<QuizRules> {
    launch().map(|l| l.instructor.quiz)
}

/// `window.labLms`, which `scorm.js` sets only inside an LMS.
fn bridge() -> Option<JsValue> {
    let window = web_sys::window()?;
    let lms = js_sys::Reflect::get(&window, &JsValue::from_str("labLms")).ok()?;
    lms.is_object().then_some(lms)
}

/// `window.labLms[name]`, or undefined.
fn field(name: &str) -> JsValue {
    bridge()
        .and_then(|lms| js_sys::Reflect::get(&lms, &JsValue::from_str(name)).ok())
        .unwrap_or(JsValue::UNDEFINED)
}

/// True inside a SCO: the page was launched as one (its query names it)
/// or talks to an LMS. There the LMS record is the only place an attempt
/// lives (nothing of it in local storage, where another tab, user or LMS
/// attempt could read it), and the package, not the link, sets the quiz's
/// seed and answer key.
#[must_use]
pub fn in_sco() -> bool {
    bridge().is_some() || launch().is_some()
}

/// True when the LMS launched the SCO for review (`cmi.core.lesson_mode`
/// review): the kept attempt is shown read-only.
#[must_use]
pub fn review() -> bool {
    field("review").is_truthy()
}

/// Where the report's typed fields of experiment `id` are kept in local
/// storage: `labreport:<id>` on the open site; inside an LMS under the
/// LMS's learner (`labreport:<student_id>:<id>`), and nowhere when the
/// LMS names none.
#[must_use]
pub fn report_storage_key(id: &str) -> Option<String> {
    if bridge().is_none() {
        return (!in_sco()).then(|| format!("labreport:{id}"));
    }
    let learner = field("learner").as_string().filter(|s| !s.is_empty())?;
    Some(format!("labreport:{learner}:{id}"))
}

/// Whether answers are shown, for a page whose instructor's link is
/// `hash` (its Simulation tab's, with the class seed): inside a SCO the
/// package's `key=` (and no class seed) decides, on the open site the
/// link's; one rule for the Self-assessment tab and the lab report.
#[must_use]
pub fn answer_key(hash: &str) -> AnswerKey {
    if let Some(l) = launch() {
        return AnswerKey::in_force(l.instructor.answer_key, None);
    }
    let ids: Vec<&str> = labcore::registry().iter().map(|e| e.id).collect();
    let parsed = labcore::route::parse(hash, &ids);
    AnswerKey::in_force(parsed.instructor.answer_key, parsed.quiz_seed)
}

/// The attempt an LMS kept for `id`, when the page runs inside one and the
/// LMS has one for this experiment.
#[must_use]
pub fn suspended(id: &str) -> Option<Suspended> {
    let lms = bridge()?;
    let ask = field("suspendData").dyn_into::<js_sys::Function>().ok()?;
    let text = ask.call1(&lms, &JsValue::from_str(id)).ok()?.as_string()?;
    Suspended::decode(&text).filter(|s| s.id == id)
}

/// The form's attempt (`kept`: its seed and the answers in the form), with
/// the quiz's graded attempts, as an LMS keeps it.
#[must_use]
pub fn suspend_data(id: &str, form: &Element, kept: SavedAttempt, tally: Tally) -> String {
    Suspended {
        id: id.to_owned(),
        seed: kept.seed,
        answers: kept.answers,
        submitted: form.has_attribute(SUBMITTED_ATTR),
        tally,
    }
    .encode()
}

/// Announces that the attempt's answers changed (`lab-quiz-progress`);
/// `kept` is the attempt's seed and the answers in the form.
pub fn progress(form: &Element, kept: SavedAttempt, tally: Tally) {
    let Some(id) = experiment_of(form) else {
        return;
    };
    let data = suspend_data(&id, form, kept, tally);
    dispatch(
        "lab-quiz-progress",
        &[
            ("id", JsValue::from_str(&id)),
            ("suspendData", JsValue::from_str(&data)),
        ],
    );
}

/// Announces a graded attempt (`lab-quiz-submitted`): `score` right of the
/// attempt's `questions`, whose seed and answers are `kept`, `tally` already
/// counting it; `quiz` is the content's questions (for option numbers in
/// content order).
pub fn submitted(
    form: &Element,
    questions: &[Prepared],
    kept: SavedAttempt,
    score: usize,
    tally: Tally,
    quiz: &[Question],
) {
    let Some(id) = experiment_of(form) else {
        return;
    };
    let max = questions.len();
    let record = interactions(questions, &kept.answers, quiz);
    let data = suspend_data(&id, form, kept, tally);
    let percent = labcore::quiz::score_percent(score, max);
    dispatch(
        "lab-quiz-submitted",
        &[
            ("id", JsValue::from_str(&id)),
            ("score", JsValue::from_f64(score as f64)),
            ("max", JsValue::from_f64(max as f64)),
            ("percent", JsValue::from_f64(percent as f64)),
            (
                "counted",
                JsValue::from_f64(tally.counted.unwrap_or(percent) as f64),
            ),
            ("questions", record.into()),
            ("suspendData", JsValue::from_str(&data)),
        ],
    );
}

/// Each question of a graded attempt as `[choice, given, correct,
/// expected]` for `cmi.interactions` (`scorm.js` writes them): a choice
/// question's `given` and `expected` are option numbers in the content's
/// order, so every student's letters mean the same option whatever the
/// shuffle; a numeric question's are the value read in its unit and the
/// answer. `given` is null when blank or unreadable.
fn interactions(questions: &[Prepared], answers: &[Response], quiz: &[Question]) -> js_sys::Array {
    let out = js_sys::Array::new();
    for (i, (q, r)) in questions.iter().zip(answers).enumerate() {
        let (given, expected) = match (&q.kind, r) {
            (PreparedKind::Choice { options, answer }, _) => {
                let in_content = |k: usize| {
                    let at = match quiz.get(i) {
                        Some(Question::Choice { options: all, .. }) => {
                            options.get(k).and_then(|o| all.iter().position(|a| a == o))
                        }
                        _ => None,
                    };
                    at.unwrap_or(k) as f64
                };
                let picked = match r {
                    Response::Choice(Some(k)) => Some(in_content(*k)),
                    _ => None,
                };
                (picked, in_content(*answer))
            }
            (PreparedKind::Numeric { answer, unit, .. }, Response::Text(text)) => {
                (read_answer(text, unit).ok().map(|x| x.value), *answer)
            }
            (PreparedKind::Numeric { answer, .. }, _) => (None, *answer),
        };
        out.push(&js_sys::Array::of4(
            &JsValue::from_bool(matches!(q.kind, PreparedKind::Choice { .. })),
            &given.map_or(JsValue::NULL, JsValue::from_f64),
            &JsValue::from_bool(grade(q, r).correct),
            &JsValue::from_f64(expected),
        ));
    }
    out
}

fn dispatch(kind: &str, fields: &[(&str, JsValue)]) {
    let Some(window) = web_sys::window() else {
        return;
    };
    let detail = js_sys::Object::new();
    for (key, value) in fields {
        let _ = js_sys::Reflect::set(&detail, &JsValue::from_str(key), value);
    }
    let init = CustomEventInit::new();
    init.set_detail(&detail);
    if let Ok(event) = CustomEvent::new_with_event_init_dict(kind, &init) {
        let _ = window.dispatch_event(&event);
    }
}
