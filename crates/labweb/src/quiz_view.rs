//! The graded Self-assessment tab.

use crate::dom::{escape, query, query_all};
use labcore::quiz::{grade, Prepared, PreparedKind, Response};
use wasm_bindgen::JsCast;
use web_sys::{Element, HtmlInputElement};

/// One attempt: the prepared questions and the seed they were drawn from.
pub struct Attempt {
    pub seed: u64,
    pub questions: Vec<Prepared>,
}

/// The form for an attempt.
pub fn render(attempt: &Attempt) -> String {
    let mut html = format!(
        "<p class=\"quiz-intro\" tabindex=\"-1\">{} questions. Questions marked <span class=\"badge\">new numbers</span> \
         draw fresh values for every attempt. Attempt seed <code class=\"quiz-seed\">{}</code>.</p><ol class=\"quiz-list\">",
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
                    labcore::quiz::format_number(*tolerance, 4),
                    if unit.is_empty() {
                        String::new()
                    } else {
                        format!(" {unit}")
                    }
                );
                html.push_str(&format!(
                    "<label class=\"quiz-prompt\" for=\"quiz-a{i}\"><span class=\"quiz-num\">{}.</span> {}{badge}</label>\
                     <div class=\"quiz-numeric\"><input type=\"text\" id=\"quiz-a{i}\" name=\"q{i}\" inputmode=\"decimal\" \
                     autocomplete=\"off\" spellcheck=\"false\" aria-describedby=\"quiz-tol{i}\">{unit_html}\
                     <span class=\"quiz-tol\" id=\"quiz-tol{i}\">{}</span></div>",
                    i + 1,
                    q.prompt,
                    escape(&tolerance_text)
                ));
            }
        }
        html.push_str(&format!(
            "<p class=\"quiz-feedback\" hidden></p><p class=\"quiz-explanation\" hidden>{}</p></li>",
            q.explanation
        ));
    }
    html.push_str(
        "</ol><div class=\"quiz-actions\"><button type=\"submit\" class=\"primary\">Submit answers</button>\
         <button type=\"button\" class=\"quiz-new\">New attempt</button></div>\
         <p class=\"quiz-score\" role=\"status\" aria-live=\"polite\"></p>",
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

/// Grades the form in place: marks each question right or wrong, shows the
/// expected answer and the explanation, and writes the score.
pub fn grade_form(form: &Element, attempt: &Attempt) {
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
            let text = if verdict.correct {
                "✓ Correct.".to_owned()
            } else if verdict.blank {
                format!("✗ No answer given. Expected {}.", verdict.expected)
            } else if verdict.unreadable {
                format!(
                    "✗ That is not a number in this question's unit. Expected {}.",
                    verdict.expected
                )
            } else {
                format!("✗ Not quite. Expected {}.", verdict.expected)
            };
            fb.set_text_content(Some(&text));
            crate::dom::set_hidden(&fb, false);
        }
        if let Some(ex) = query(&item, ".quiz-explanation") {
            crate::dom::set_hidden(&ex, false);
        }
    }
    // Answers are revealed now: lock this attempt (New attempt starts another).
    for control in query_all(form, "input, button[type=submit]") {
        let _ = control.set_attribute("disabled", "");
    }
    if let Some(out) = query(form, ".quiz-score") {
        out.scroll_into_view_with_bool(false);
        out.set_text_content(Some(&format!(
            "Score: {score} / {} ({}%). Press New attempt for fresh questions.",
            attempt.questions.len(),
            (100 * score) / attempt.questions.len().max(1)
        )));
    }
}
