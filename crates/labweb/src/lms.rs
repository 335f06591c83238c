//! The quiz's side of the SCORM 1.2 bridge (`web/scorm.js` is the other).
//!
//! The wasm never talks to an LMS itself. It announces quiz events on
//! `window` and asks one JS global for a saved attempt:
//!
//! - `lab-quiz-progress` (`CustomEvent`), whenever the attempt's answers are
//!   kept: `detail = { id, suspendData }`;
//! - `lab-quiz-submitted`, when an attempt is graded:
//!   `detail = { id, score, max, percent, suspendData }`, with `score` right
//!   answers of `max` questions and `percent` their rounded percentage;
//! - `window.labLms.suspendData(id)`, set by `scorm.js` only inside an LMS:
//!   the attempt the LMS kept for experiment `id` (a
//!   [`labcore::lms::Suspended`] text), or `null`.
//!
//! Outside an LMS nobody listens and `window.labLms` does not exist, so the
//! quiz behaves exactly as before (its attempt lives in local storage).

use crate::quiz_view::{saved, Attempt};
use labcore::lms::Suspended;
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

/// The attempt an LMS kept for `id`, when the page runs inside one and the
/// LMS has one for this experiment.
#[must_use]
pub fn suspended(id: &str) -> Option<Suspended> {
    let window = web_sys::window()?;
    let lms = js_sys::Reflect::get(&window, &JsValue::from_str("labLms")).ok()?;
    if !lms.is_object() {
        return None;
    }
    let ask = js_sys::Reflect::get(&lms, &JsValue::from_str("suspendData"))
        .ok()?
        .dyn_into::<js_sys::Function>()
        .ok()?;
    let text = ask.call1(&lms, &JsValue::from_str(id)).ok()?.as_string()?;
    Suspended::decode(&text).filter(|s| s.id == id)
}

/// The form's attempt as an LMS keeps it.
#[must_use]
pub fn suspend_data(id: &str, form: &Element, attempt: &Attempt) -> String {
    let kept = saved(form, attempt);
    Suspended {
        id: id.to_owned(),
        seed: kept.seed,
        answers: kept.answers,
        submitted: form.has_attribute(SUBMITTED_ATTR),
    }
    .encode()
}

/// Announces that the attempt's answers changed (`lab-quiz-progress`).
pub fn progress(form: &Element, attempt: &Attempt) {
    let Some(id) = experiment_of(form) else {
        return;
    };
    let data = suspend_data(&id, form, attempt);
    dispatch(
        "lab-quiz-progress",
        &[
            ("id", JsValue::from_str(&id)),
            ("suspendData", JsValue::from_str(&data)),
        ],
    );
}

/// Announces a graded attempt (`lab-quiz-submitted`): `score` right of the
/// attempt's questions.
pub fn submitted(form: &Element, attempt: &Attempt, score: usize) {
    let Some(id) = experiment_of(form) else {
        return;
    };
    let max = attempt.questions.len();
    let data = suspend_data(&id, form, attempt);
    dispatch(
        "lab-quiz-submitted",
        &[
            ("id", JsValue::from_str(&id)),
            ("score", JsValue::from_f64(score as f64)),
            ("max", JsValue::from_f64(max as f64)),
            (
                "percent",
                JsValue::from_f64(labcore::quiz::score_percent(score, max) as f64),
            ),
            ("suspendData", JsValue::from_str(&data)),
        ],
    );
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
