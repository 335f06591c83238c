//! The graded Self-assessment tab.
//!
//! Worked answers and explanations are not in the page before submission:
//! [`render`] leaves their places empty and [`grade_form`] fills them from the
//! attempt held in memory. Submitting with unanswered questions asks for
//! confirmation first; the score shows at the top of the form. An
//! instructor's rules ([`Grading`]) limit the graded attempts and choose
//! which one's score counts.

use crate::dom::{escape, query, query_all};
use labcore::content::Question;
use labcore::lms::Tally;
use labcore::quiz::{grade, score_percent, Prepared, PreparedKind, Response, SavedAttempt};
use labcore::route::QuizRules;
use wasm_bindgen::JsCast;
use web_sys::{Element, HtmlInputElement};

/// One attempt: the prepared questions and the seed they were drawn from.
pub struct Attempt {
    pub seed: u64,
    pub questions: Vec<Prepared>,
}

/// How an experiment's quiz is graded: the instructor's rules (from the
/// link, or a SCORM package's launch) and the attempts graded so far.
#[derive(Clone, Copy, Debug, Default)]
pub struct Grading {
    pub rules: QuizRules,
    pub tally: Tally,
    /// The answer key in force is `never` ([`crate::lms::answer_key`]):
    /// a graded attempt marks each answer but shows no expected answer or
    /// explanation, as the lab report does.
    pub hide_key: bool,
}

impl Grading {
    /// The rules for `id` (a SCORM launch's, else `link_rules`), with the
    /// attempts the LMS counted; outside an LMS the count starts with the
    /// page (a teaching aid: the LMS's count is the one that holds).
    #[must_use]
    pub fn load(id: &str, link_rules: QuizRules) -> Grading {
        Grading {
            rules: crate::lms::launch_rules().unwrap_or(link_rules),
            tally: crate::lms::suspended(id).map_or_else(Tally::default, |s| s.tally),
            hide_key: false,
        }
    }
}

/// The form for an attempt.
pub fn render(attempt: &Attempt) -> String {
    let mut html = format!(
        "<p class=\"quiz-intro\" tabindex=\"-1\">{} questions. Questions marked <span class=\"badge\">new numbers</span> \
         draw fresh values for every attempt. Attempt seed <code class=\"quiz-seed\">{}</code>. \
         Type numbers with a decimal point (1.5); a comma only separates thousands (8,000).</p>\
         <p class=\"quiz-score\" role=\"status\" aria-live=\"polite\" tabindex=\"-1\" hidden></p>\
         <p class=\"quiz-confirm\" role=\"alert\" hidden></p><ol class=\"quiz-list\">",
        attempt.questions.len(),
        attempt.seed
    );
    for (i, q) in attempt.questions.iter().enumerate() {
        let badge = if q.parameterised {
            " <span class=\"badge\">new numbers</span>"
        } else {
            ""
        };
        html.push_str(&format!("<li class=\"quiz-q\" data-index=\"{i}\">"));
        match &q.kind {
            PreparedKind::Choice { options, .. } => {
                html.push_str(&format!(
                    "<fieldset><legend class=\"quiz-prompt\"><span class=\"quiz-num\">{}.</span> {}{badge}</legend>",
                    i + 1,
                    q.prompt
                ));
                for (k, option) in options.iter().enumerate() {
                    html.push_str(&format!(
                        "<label class=\"quiz-option\"><input type=\"radio\" name=\"q{i}\" value=\"{k}\"> <span>{option}</span></label>"
                    ));
                }
                html.push_str("</fieldset>");
            }
            PreparedKind::Numeric {
                unit, tolerance, ..
            } => {
                let unit_html = if unit.is_empty() {
                    String::new()
                } else {
                    format!("<span class=\"unit\">{}</span>", escape(unit))
                };
                let tolerance_text = format!(
                    "accepted within ±{}{}",
                    labcore::units::format_number(*tolerance, 4),
                    if unit.is_empty() {
                        String::new()
                    } else {
                        format!(" {unit}")
                    }
                );
                html.push_str(&format!(
                    "<label class=\"quiz-prompt\" for=\"quiz-a{i}\"><span class=\"quiz-num\">{}.</span> {}{badge}</label>\
                     <div class=\"quiz-numeric\"><input type=\"text\" id=\"quiz-a{i}\" name=\"q{i}\" inputmode=\"decimal\" maxlength=\"40\" \
                     autocomplete=\"off\" spellcheck=\"false\" aria-describedby=\"quiz-tol{i}\">{unit_html}\
                     <span class=\"quiz-tol\" id=\"quiz-tol{i}\">{}</span></div>",
                    i + 1,
                    q.prompt,
                    escape(&tolerance_text)
                ));
            }
        }
        // Filled by `grade_form` from the attempt in memory: no worked answer
        // sits in the page before submission.
        html.push_str(
            "<p class=\"quiz-feedback\" hidden></p><p class=\"quiz-explanation\" hidden></p></li>",
        );
    }
    html.push_str(
        "</ol><div class=\"quiz-actions\"><button type=\"submit\" class=\"primary\">Submit answers</button>\
         <button type=\"button\" class=\"quiz-new\">New attempt</button></div>",
    );
    html
}

fn response_of(item: &Element, kind: &PreparedKind) -> Response {
    match kind {
        PreparedKind::Choice { .. } => Response::Choice(
            query_all(item, "input[type=radio]")
                .into_iter()
                .filter_map(|e| e.dyn_into::<HtmlInputElement>().ok())
                .find(HtmlInputElement::checked)
                .and_then(|r| r.value().parse().ok()),
        ),
        PreparedKind::Numeric { .. } => Response::Text(
            query(item, "input")
                .and_then(|e| e.dyn_into::<HtmlInputElement>().ok())
                .map(|i| i.value())
                .unwrap_or_default(),
        ),
    }
}

/// The answers currently in the form, one per question (for saving an
/// attempt with [`SavedAttempt`]).
pub fn responses(form: &Element, attempt: &Attempt) -> Vec<Response> {
    attempt
        .questions
        .iter()
        .enumerate()
        .map(
            |(i, q)| match query(form, &format!(".quiz-q[data-index=\"{i}\"]")) {
                Some(item) => response_of(&item, &q.kind),
                None => match q.kind {
                    PreparedKind::Choice { .. } => Response::Choice(None),
                    PreparedKind::Numeric { .. } => Response::Text(String::new()),
                },
            },
        )
        .collect()
}

/// The attempt and its answers so far, ready to keep across a reload.
pub fn saved(form: &Element, attempt: &Attempt) -> SavedAttempt {
    SavedAttempt {
        seed: attempt.seed,
        answers: responses(form, attempt),
    }
}

/// Puts saved answers back into a freshly rendered form (answers that do not
/// fit this attempt's questions are left blank).
pub fn restore(form: &Element, attempt: &Attempt, saved: &SavedAttempt, grading: &mut Grading) {
    if saved.seed != attempt.seed {
        return;
    }
    for (i, answer) in saved.answers_for(&attempt.questions).iter().enumerate() {
        let Some(item) = query(form, &format!(".quiz-q[data-index=\"{i}\"]")) else {
            continue;
        };
        match answer {
            Response::Choice(Some(k)) => {
                if let Some(radio) = query(&item, &format!("input[type=radio][value=\"{k}\"]"))
                    .and_then(|e| e.dyn_into::<HtmlInputElement>().ok())
                {
                    radio.set_checked(true);
                }
            }
            Response::Text(text) if !text.is_empty() => {
                if let Some(input) =
                    query(&item, "input").and_then(|e| e.dyn_into::<HtmlInputElement>().ok())
                {
                    input.set_value(text);
                }
            }
            _ => {}
        }
    }
    // An attempt the LMS kept as submitted comes back graded.
    let graded_in_lms = crate::lms::experiment_of(form)
        .and_then(|id| crate::lms::suspended(&id))
        .is_some_and(|s| s.submitted && s.seed == attempt.seed);
    if graded_in_lms {
        grade_form(form, attempt, grading, false);
    }
}

/// Numbers (1-based) of the questions with no answer yet.
pub fn unanswered(form: &Element, attempt: &Attempt) -> Vec<usize> {
    responses(form, attempt)
        .iter()
        .enumerate()
        .filter(|(_, r)| r.is_blank())
        .map(|(i, _)| i + 1)
        .collect()
}

/// Shows `text` in the form's alert line.
fn alert(form: &Element, text: &str) {
    if let Some(confirm) = query(form, ".quiz-confirm") {
        confirm.set_text_content(Some(text));
        crate::dom::set_hidden(&confirm, false);
    }
}

/// The submit button: with unanswered questions the first press only asks
/// for confirmation (the form remembers it), the next one grades, unless
/// the instructor's attempts are used up (then it says so and grades
/// nothing). Returns true when the form was graded; `quiz` is the content's
/// questions (for the LMS's per-question record).
pub fn submit(form: &Element, attempt: &Attempt, grading: &mut Grading, quiz: &[Question]) -> bool {
    if !grading.rules.allows(grading.tally.graded) {
        alert(form, &grading.tally.line(&grading.rules, true));
        return false;
    }
    let missing = unanswered(form, attempt);
    let confirmed = form.has_attribute("data-confirm-unanswered");
    if !missing.is_empty() && !confirmed {
        let list = missing
            .iter()
            .map(ToString::to_string)
            .collect::<Vec<_>>()
            .join(", ");
        let text = if missing.len() == 1 {
            format!(
                "Question {list} has no answer. Answer it, or press Submit anyway to grade now."
            )
        } else {
            format!(
                "{} questions have no answer ({list}). Answer them, or press Submit anyway to grade now.",
                missing.len()
            )
        };
        alert(form, &text);
        let _ = form.set_attribute("data-confirm-unanswered", "");
        if let Some(button) = query(form, "button[type=submit]") {
            button.set_text_content(Some("Submit anyway"));
        }
        return false;
    }
    let score = grade_form(form, attempt, grading, true);
    crate::lms::submitted(
        form,
        &attempt.questions,
        saved(form, attempt),
        score,
        grading.tally,
        quiz,
    );
    true
}

/// The line shown after grading: `✗ Not quite: read as 8000 m. Expected 8 m.`
/// (without the expected answer when `hide_key`).
fn feedback(verdict: &labcore::quiz::Grade, hide_key: bool) -> String {
    let read = verdict
        .read_as
        .as_ref()
        .map_or(String::new(), |r| format!(" (read as {r})"));
    let expected = if hide_key {
        String::new()
    } else {
        format!(" Expected {}.", verdict.expected)
    };
    if verdict.correct {
        format!("✓ Correct{read}.")
    } else if verdict.blank {
        format!("✗ No answer given.{expected}")
    } else if verdict.unreadable {
        let why = verdict
            .problem
            .as_deref()
            .unwrap_or("that is not a number in this question's unit");
        format!("✗ Could not read the answer: {why}.{expected}")
    } else {
        format!("✗ Not quite{read}.{expected}")
    }
}

/// Grades the form in place: marks each question right or wrong, shows how
/// each answer was read, the expected answer and the explanation (written
/// into the page only now), and the score at the top with what the
/// instructor's rules make of it; `record` counts it as a graded attempt
/// (not when a kept attempt is shown again). Returns the number of right
/// answers.
pub fn grade_form(form: &Element, attempt: &Attempt, grading: &mut Grading, record: bool) -> usize {
    let mut score = 0;
    for item in query_all(form, ".quiz-q") {
        let Some(index) = item
            .get_attribute("data-index")
            .and_then(|s| s.parse::<usize>().ok())
        else {
            continue;
        };
        let Some(q) = attempt.questions.get(index) else {
            continue;
        };
        let verdict = grade(q, &response_of(&item, &q.kind));
        if verdict.correct {
            score += 1;
        }
        let _ = item.class_list().remove_2("right", "wrong");
        let _ = item
            .class_list()
            .add_1(if verdict.correct { "right" } else { "wrong" });
        if let Some(fb) = query(&item, ".quiz-feedback") {
            fb.set_text_content(Some(&feedback(&verdict, grading.hide_key)));
            crate::dom::set_hidden(&fb, false);
        }
        if let Some(ex) = query(&item, ".quiz-explanation").filter(|_| !grading.hide_key) {
            // Content files are ours (trusted inline HTML/MathML).
            ex.set_inner_html(&q.explanation);
            crate::dom::set_hidden(&ex, false);
        }
    }
    // Answers are revealed now: lock this attempt (New attempt starts another).
    for control in query_all(form, "input, button[type=submit]") {
        let _ = control.set_attribute("disabled", "");
    }
    // The button says what happened, not "Submit anyway" any more.
    if let Some(button) = query(form, "button[type=submit]") {
        button.set_text_content(Some("Submitted"));
    }
    if let Some(confirm) = query(form, ".quiz-confirm") {
        crate::dom::set_hidden(&confirm, true);
    }
    let total = attempt.questions.len();
    let percent = score_percent(score, total);
    if record {
        grading.tally.record(percent, &grading.rules);
    }
    if let Some(out) = query(form, ".quiz-score") {
        out.set_text_content(Some(&format!(
            "Score: {score} / {total} ({percent}%). {}",
            grading.tally.line(&grading.rules, false)
        )));
        crate::dom::set_hidden(&out, false);
        out.scroll_into_view_with_bool(true);
    }
    let _ = form.set_attribute(crate::lms::SUBMITTED_ATTR, "");
    score
}

/// Local-storage key of an experiment's attempt in progress.
fn storage_key(experiment_id: &str) -> String {
    format!("labquiz:{experiment_id}")
}

/// The attempt saved for this experiment: inside a SCO only the LMS's
/// (see [`crate::lms`]), else the one [`store`] kept, if any (and readable).
pub fn load_saved(experiment_id: &str) -> Option<SavedAttempt> {
    if crate::lms::in_sco() {
        return crate::lms::suspended(experiment_id).map(|kept| kept.attempt());
    }
    let storage = web_sys::window()?.local_storage().ok()??;
    let text = storage.get_item(&storage_key(experiment_id)).ok()??;
    SavedAttempt::decode(&text)
}

/// Keeps the attempt's seed and answers so a reload restores them
/// (silently does nothing when storage is unavailable, e.g. private mode;
/// never inside a SCO, where the LMS keeps it), and tells an LMS, if there
/// is one (`lab-quiz-progress`, with the attempts graded so far).
pub fn store(experiment_id: &str, form: &Element, attempt: &Attempt, tally: Tally) {
    let storage = web_sys::window().filter(|_| !crate::lms::in_sco());
    if let Some(Ok(Some(storage))) = storage.map(|w| w.local_storage()) {
        let _ = storage.set_item(&storage_key(experiment_id), &saved(form, attempt).encode());
    }
    crate::lms::progress(form, saved(form, attempt), tally);
}
