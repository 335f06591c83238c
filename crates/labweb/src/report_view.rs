//! The "Lab report" button of the Simulation tab: gathers what the report
//! needs from the page (the absolute link of the run, the student's clock,
//! the quiz attempt if it was submitted, an instructor's note from the link),
//! has [`labcore::report::render`] build the file and offers it as a
//! download made in the page from a Blob (nothing leaves the browser).

use crate::dom::{self, query};
use crate::plot_view;
use crate::quiz_view::{self, Attempt};
use labcore::quiz::Response;
use labcore::report::{self, QuizResult, Report};
use labcore::route::{self, Page};
use labcore::Experiment;
use web_sys::Element;

/// The button, placed among the Simulation tab's actions.
pub const BUTTON_HTML: &str =
    "<button type=\"button\" class=\"mini\" data-export=\"report\">Lab report</button>";

/// Builds `<id>-report.html` from the experiment's current state and offers
/// it as a download. `panel` is the Simulation panel (its article holds the
/// quiz); `hash` is the link of the state shown (`#/pid/simulation?…`).
pub fn download(panel: &Element, exp: &dyn Experiment, hash: &str) {
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
    let quiz = submitted_quiz(panel, entry, content);
    let note = note_in_link(&location.hash().unwrap_or_default());
    let html = report::render(&Report {
        experiment: exp,
        content,
        link: &link,
        date: &date,
        quiz: quiz.as_ref().map(|(attempt, answers)| QuizResult {
            seed: attempt.seed,
            questions: &attempt.questions,
            answers,
        }),
        note: note.as_deref(),
    });
    plot_view::download(
        &report::file_name(exp.id()),
        "text/html;charset=utf-8",
        &html,
    );
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

/// The attempt on the Self-assessment tab and the answers in its form, when
/// it has been graded (the score line is shown only then). The questions are
/// drawn again from the seed the form shows, exactly as the tab drew them.
fn submitted_quiz(
    panel: &Element,
    entry: &labcore::Entry,
    content: &labcore::Content,
) -> Option<(Attempt, Vec<Response>)> {
    let article = panel.closest("article.exp").ok().flatten()?;
    let form = query(&article, "form.quiz")?;
    let score = query(&form, ".quiz-score")?;
    if score.has_attribute("hidden") {
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
    Some((attempt, answers))
}

/// An instructor's note (`note=…`) in the page's link, if any.
fn note_in_link(hash: &str) -> Option<String> {
    let ids: Vec<&str> = labcore::registry().iter().map(|e| e.id).collect();
    match route::parse(hash, &ids).page {
        Page::Experiment { params, .. } => params
            .into_iter()
            .find(|(k, _)| k == "note")
            .map(|(_, v)| v),
        Page::Home => None,
    }
}
