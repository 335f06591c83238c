//! The lab report: one self-contained HTML file a student hands in.
//!
//! [`render`] is a pure function of the experiment's state, its content, the
//! link that reproduces the run, a date and (when the Self-assessment was
//! submitted) the quiz attempt. The file holds the title and aim, the date,
//! the link, every parameter with its unit, the status, readouts and live
//! tables, every plot as inline SVG drawn here from the plot data (crisp in
//! print) with a data table, the quiz score and answers, and a lined box for
//! the student's observations.
//!
//! Self-contained means no request anywhere: the CSS is inline (this is a
//! downloaded document, not the site, so the site's CSP does not apply), there
//! are no fonts, images or scripts, and the file carries its own
//! `Content-Security-Policy` (`default-src 'none'`) so even a browser that
//! opens it from disk fetches nothing. The only address in the file is the
//! link back to the lab, as text and as a link. The one `<script>` element
//! is data: a `type="application/json"` record of the quiz (see
//! [`DATA_ID`]) that no browser runs, for the lab's "Check a report" page.
//!
//! The student's name, group and observations (typed on the page, see
//! [`Student`]) are printed, and stay editable in the file. Whether the
//! quiz table shows expected answers is the instructor link's choice
//! ([`AnswerKey`]).
//!
//! Everything that comes from the student or a link (the note, text state,
//! quiz answers, the link itself) is escaped with
//! [`crate::content_html::escape`]; the content file's inline markup
//! (`<em>`, MathML) is ours and compiled in, and goes in as HTML, exactly as
//! on the site.

use crate::content::Content;
use crate::content_html::escape;
use crate::experiment::{Lab, ParamKind, ParamSpec, Readout, Status, Tone};
use crate::math;
use crate::plot::{decimate_min_max, log_ticks, nice_ticks, Axis, Plot, Series, SeriesRole};
use crate::quiz::{grade, score_percent, Prepared, PreparedKind, Response};
pub use crate::route::AnswerKey;
use crate::scene::style::{BAND_OPACITY, CANVAS, PLOT_BAND, REF_LINE_DASH_PX};
use crate::scene::{Role, Scene, ViewBox};
use crate::table::Table;
use crate::units::{format_number, power_of_ten};
use labcore::layout::page_colours::{MUTED, PAGE};
use labcore::layout::ticks::tick_labels;
use std::fmt::Write as _;

mod scene_svg;
pub mod wire;

/// Most rows of a plot's data table in the report: a long series is shown
/// at evenly spaced samples (first and last included), and the table says so.
pub const TABLE_ROWS: usize = 30;

/// Most rows of a live table (an open list) copied into the report.
pub const LIVE_TABLE_ROWS: usize = 60;

/// Ruled lines in the observations box.
pub const OBSERVATION_LINES: usize = 14;

/// Width and height of a plot's SVG drawing area, in SVG user units
/// (CSS pixels at 100 %; the figure scales to the page width).
const SVG_W: f64 = 640.0;
const SVG_H: f64 = 280.0;
/// Plot margins: left (y tick labels), right, top, bottom (x ticks and title).
const MARGIN: (f64, f64, f64, f64) = (64.0, 24.0, 12.0, 42.0);
/// Line segments per series at most: [`decimate_min_max`] buckets across the
/// plot width (about two per user unit), so the drawing looks like every
/// sample and a 20,000-sample run costs a few kilobytes.
const DRAW_BUCKETS: usize = 300;
/// Longest text value (a wall code) copied into the parameter table.
const TEXT_STATE_MAX: usize = 120;

/// A Self-assessment attempt: the questions as the student saw them (drawn
/// from `seed`) and the answers given, one per question. `submitted` is
/// false for an attempt not yet graded, which a report shows only when the
/// instructor's link asks for the answer key always ([`AnswerKey::Always`]).
#[derive(Clone, Copy, Debug)]
pub struct QuizResult<'a> {
    pub seed: u64,
    pub questions: &'a [Prepared],
    pub answers: &'a [Response],
    pub submitted: bool,
}

impl QuizResult<'_> {
    /// `(correct, total)` by [`crate::quiz::grade`]; a missing answer is blank.
    #[must_use]
    pub fn score(&self) -> (usize, usize) {
        let correct = self
            .questions
            .iter()
            .enumerate()
            .filter(|(i, q)| grade(q, &self.answer(*i, q)).correct)
            .count();
        (correct, self.questions.len())
    }

    fn answer(&self, i: usize, q: &Prepared) -> Response {
        self.answers.get(i).cloned().unwrap_or(match q.kind {
            PreparedKind::Choice { .. } => Response::Choice(None),
            PreparedKind::Numeric { .. } => Response::Text(String::new()),
        })
    }
}

/// What goes into a report.
#[derive(Clone, Copy)]
pub struct Report<'a> {
    pub experiment: &'a dyn Lab,
    pub content: &'a Content,
    /// The absolute address that reproduces the run (the page's URL with
    /// the state in its hash).
    pub link: &'a str,
    /// When the report was made, as the student's clock shows it.
    pub date: &'a str,
    /// The quiz attempt, when it was submitted.
    pub quiz: Option<QuizResult<'a>>,
    /// An instructor's note from the link (`note=`), shown as text.
    pub note: Option<&'a str>,
    /// What the student typed for the report: name, group, observations.
    pub student: Student<'a>,
    /// Whether the quiz table shows each question's expected answer (the
    /// link's `key=`, see [`AnswerKey::in_force`]).
    pub answer_key: AnswerKey,
    /// The moments the student marked in the run, in time order: a section
    /// each, with the scene and the readouts of that moment, and a triangle
    /// on every plot.
    pub marks: &'a [MarkedMoment<'a>],
    /// The moment on screen when the report was made, where the page showed
    /// a past moment of the run: `experiment` is then the run's end (the
    /// whole run, as the page's plots draw it), and the moment has a
    /// section and a line on every plot (issue 53 §2). `None` at the run's
    /// end.
    pub shown: Option<MarkedMoment<'a>>,
}

/// A marked moment of the run (issue 26 §3): its time and the state the
/// run had then (the timeline's, bit for bit the run's).
#[derive(Clone, Copy)]
pub struct MarkedMoment<'a> {
    /// Simulated time of the mark, seconds.
    pub t_s: f64,
    pub state: &'a dyn Lab,
}

/// The student's own entries, typed on the Simulation tab before the report
/// is made (the page keeps them per experiment) and printed in it; empty
/// ones print as blank lines to write on. In the file they stay editable
/// (no script: `contenteditable`), so a student can still type into them
/// before printing.
#[derive(Clone, Copy, Debug, Default)]
pub struct Student<'a> {
    pub name: &'a str,
    pub group: &'a str,
    pub observations: &'a str,
}

/// Everything a report prints, copied out of the lab by [`Sheet::of`]:
/// plain owned data, so the experiment's module can hand it as bytes
/// ([`wire`]) to the report module, which is downloaded only when a student
/// asks for a report, and which turns it into the file ([`render_sheet`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Sheet {
    pub id: String,
    /// The experiment's number in the lab, its title and aim (inline HTML).
    pub number: u32,
    pub title: String,
    pub aim: Vec<String>,
    pub link: String,
    pub date: String,
    pub note: Option<String>,
    pub student: StudentSheet,
    pub answer_key: AnswerKey,
    /// Every parameter, in the experiment's order.
    pub params: Vec<ParamRow>,
    /// The text state the link carries, `(key, value)`.
    pub extra_state: Vec<(String, String)>,
    pub status: Status,
    pub scene: Scene,
    pub view: ViewBox,
    pub readouts: Vec<Readout>,
    pub tables: Vec<Table>,
    pub plots: Vec<Plot>,
    pub quiz: Option<QuizSheet>,
    /// The marked moments, in time order ([`MarkedMoment`]).
    pub marks: Vec<Moment>,
    /// The moment on screen, where it was not the run's end
    /// ([`Report::shown`]).
    pub shown: Option<Moment>,
}

/// A [`MarkedMoment`] as the report prints it: the time, and the status,
/// scene and readouts the run had then, and where it is on each plot.
#[derive(Clone, Debug, PartialEq)]
pub struct Moment {
    /// Simulated time of the mark, seconds.
    pub t_s: f64,
    pub status: Status,
    pub scene: Scene,
    pub view: ViewBox,
    pub readouts: Vec<Readout>,
    /// Per plot (by key), the points of its run's series then: their last
    /// samples ([`labcore::marks::plot_points`], as the page marks them).
    pub points: labcore::marks::PlotPoints,
}

impl Moment {
    fn of(m: &MarkedMoment<'_>) -> Moment {
        let mut scene = Scene::default();
        m.state.scene(&mut scene);
        Moment {
            t_s: m.t_s,
            status: m.state.status(),
            scene,
            view: m.state.view(),
            readouts: m.state.readouts(),
            points: labcore::marks::plot_points(m.state.plots()),
        }
    }

    /// Its points on the plot `key`.
    fn on(&self, key: &str) -> &[(f64, f64)] {
        self.points
            .iter()
            .find(|(k, _)| *k == key)
            .map_or(&[], |(_, p)| p)
    }

    /// `t = 0.67 s`.
    fn when(&self) -> String {
        format!("t = {:.2} s", self.t_s)
    }
}

/// One parameter as the report prints it: its value already written as the
/// page shows it (a number, a toggle's or a choice's label).
#[derive(Clone, Debug, PartialEq)]
pub struct ParamRow {
    pub key: String,
    pub label: String,
    pub value: String,
    pub unit: String,
    pub group: Option<String>,
}

/// [`Student`], owned.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct StudentSheet {
    pub name: String,
    pub group: String,
    pub observations: String,
}

/// [`QuizResult`], owned.
#[derive(Clone, Debug, PartialEq)]
pub struct QuizSheet {
    pub seed: u64,
    pub questions: Vec<Prepared>,
    pub answers: Vec<Response>,
    pub submitted: bool,
}

impl QuizSheet {
    fn result(&self) -> QuizResult<'_> {
        QuizResult {
            seed: self.seed,
            questions: &self.questions,
            answers: &self.answers,
            submitted: self.submitted,
        }
    }
}

impl Sheet {
    /// What `r` prints: the experiment's parameters, status, scene, view,
    /// readouts, tables and plots as they are now, with the rest of `r`.
    #[must_use]
    pub fn of(r: &Report<'_>) -> Sheet {
        let exp = r.experiment;
        let mut scene = Scene::default();
        exp.scene(&mut scene);
        let params = exp
            .params()
            .iter()
            .map(|spec| ParamRow {
                key: spec.key.to_owned(),
                label: spec.label.to_owned(),
                value: param_value(spec, exp.param(spec.key)),
                unit: spec.unit.to_owned(),
                group: spec.group.map(str::to_owned),
            })
            .collect();
        Sheet {
            id: exp.id().to_owned(),
            number: r.content.number,
            title: r.content.title.clone(),
            aim: r.content.aim.clone(),
            link: r.link.to_owned(),
            date: r.date.to_owned(),
            note: r.note.map(str::to_owned),
            student: StudentSheet {
                name: r.student.name.to_owned(),
                group: r.student.group.to_owned(),
                observations: r.student.observations.to_owned(),
            },
            answer_key: r.answer_key,
            params,
            extra_state: exp
                .extra_state()
                .into_iter()
                .map(|(k, v)| (k.to_owned(), v))
                .collect(),
            status: exp.status(),
            scene,
            view: exp.view(),
            readouts: exp.readouts(),
            tables: exp.tables(),
            plots: exp.plots().to_vec(),
            quiz: r.quiz.map(|q| QuizSheet {
                seed: q.seed,
                questions: q.questions.to_vec(),
                answers: q.answers.to_vec(),
                submitted: q.submitted,
            }),
            marks: r.marks.iter().map(Moment::of).collect(),
            shown: r.shown.as_ref().map(Moment::of),
        }
    }
}

/// The `id` of the report's machine-readable record: a
/// `<script type="application/json">` (data, never run; the file's policy
/// allows no script) holding `{"report":1,"id","date","quiz":{"seed",
/// "answers","score":[correct,total]}|null}`. Seeds are strings (a `u64`
/// does not fit a JavaScript number); an answer is an option index, `null`
/// (none) or the text typed. The lab's "Check a report" page reads it.
pub const DATA_ID: &str = "lab-report-data";

/// Longest typed answer kept in the record, in characters (longer is cut;
/// the form's own limit is far below).
const ANSWER_MAX_CHARS: usize = 400;

/// The file name of an experiment's report: `pid-report.html`.
#[must_use]
pub fn file_name(id: &str) -> String {
    format!("{id}-report.html")
}

/// A date and time as the report shows it: `2026-11-25 14:05 (UTC+01:00)`.
/// `month` is 1–12; `utc_offset_min` is local time minus UTC in minutes
/// (east positive; JavaScript's `getTimezoneOffset` has the opposite sign).
#[must_use]
pub fn date_text(
    year: i32,
    month: u32,
    day: u32,
    hour: u32,
    minute: u32,
    utc_offset_min: i32,
) -> String {
    let sign = if utc_offset_min < 0 { '-' } else { '+' };
    let off = utc_offset_min.unsigned_abs();
    format!(
        "{year:04}-{month:02}-{day:02} {hour:02}:{minute:02} (UTC{sign}{:02}:{:02})",
        off / 60,
        off % 60
    )
}

/// The whole report as one HTML document (see the module doc): what the
/// report module makes of the experiment's [`Sheet`].
#[must_use]
pub fn render(r: &Report<'_>) -> String {
    render_sheet(&Sheet::of(r))
}

/// The report from the bytes of a [`Sheet`] ([`wire::encode`]): what the
/// report module runs.
pub fn render_bytes(bytes: &[u8]) -> Result<String, wire::WireError> {
    Ok(render_sheet(&wire::decode(bytes)?))
}

/// The report of `r` (see [`render`]).
#[must_use]
pub fn render_sheet(r: &Sheet) -> String {
    let mut h = String::with_capacity(64 * 1024);
    let title = format!("Lab report: {}", r.title);
    let _ = write!(
        h,
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\
         <meta http-equiv=\"Content-Security-Policy\" content=\"default-src 'none'; style-src 'unsafe-inline'\">\
         <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\
         <title>{}</title><style>{}{CSS}</style></head><body><main>",
        escape(&title),
        page_vars()
    );
    // Title block with room for the student's name.
    let _ = write!(
        h,
        "<header><p class=\"eyebrow\">Robotics virtual lab · Experiment {} · Lab report</p>\
         <h1>{}</h1><dl class=\"meta\"><div><dt>Date</dt><dd class=\"date\">{}</dd></div>\
         <div><dt>Name</dt><dd class=\"field\" contenteditable=\"true\" data-field=\"name\">{}</dd></div>\
         <div><dt>Group</dt><dd class=\"field\" contenteditable=\"true\" data-field=\"group\">{}</dd></div></dl>\
         <p class=\"link\">Reproduce this run: <a href=\"{link}\">{link}</a></p></header>",
        r.number,
        escape(&r.title),
        escape(&r.date),
        escape(r.student.name.trim()),
        escape(r.student.group.trim()),
        link = escape(&r.link),
    );
    if let Some(note) = r.note.as_deref().filter(|n| !n.trim().is_empty()) {
        let _ = write!(
            h,
            "<aside class=\"note\"><strong>Instructor's note:</strong> {}</aside>",
            escape(note)
        );
    }
    h.push_str("<section class=\"aim\"><h2>Aim</h2>");
    for p in &r.aim {
        // Content files are ours (trusted inline markup), as on the site.
        let _ = write!(h, "<p>{p}</p>");
    }
    h.push_str("</section>");

    parameters_section(&mut h, r);
    results_section(&mut h, r);
    // The moment on screen has its own section, unless a mark is its.
    let shown_marked = r.shown.as_ref().and_then(|m| {
        r.marks
            .iter()
            .position(|k| format!("{:.2}", k.t_s) == format!("{:.2}", m.t_s))
    });
    if let (Some(m), None) = (&r.shown, shown_marked) {
        h.push_str("<section class=\"marks\"><h2>The moment on screen</h2>");
        moment_section(
            &mut h,
            m,
            "moment",
            &format!("On screen when the report was made: {}", m.when()),
        );
        h.push_str("</section>");
    }
    marks_section(&mut h, &r.marks, shown_marked);
    plots_section(&mut h, r);
    quiz_section(
        &mut h,
        r.quiz.as_ref().map(QuizSheet::result).as_ref(),
        r.answer_key,
    );

    let typed = r.student.observations.trim();
    let lines = "<div class=\"line\"></div>".repeat(if typed.is_empty() {
        OBSERVATION_LINES
    } else {
        OBSERVATION_LINES / 3
    });
    let _ = write!(
        h,
        "<section class=\"observations\"><h2>Observations and conclusions</h2>\
         <p class=\"muted\">What did you see? Compare it with the theory, explain any difference, \
         and say what you would change next. (Type on the Simulation tab before making the report, \
         or into this box and the Name and Group fields before printing.)</p><div class=\"lines\">\
         <div class=\"obs-text\" contenteditable=\"true\" data-field=\"observations\">{}</div>{lines}</div></section>\
         <footer><p>Made by the Robotics virtual lab on {}. This file is self-contained: it needs no \
         network and makes no request. Open the link above to see the run again.</p></footer>",
        escape(typed),
        escape(&r.date)
    );
    data_record(&mut h, r);
    h.push_str("</main></body></html>\n");
    h
}

/// A string as a JSON string literal that is also safe inside a `<script>`
/// element: `<`, `>` and `&` are written as `\u` escapes, so no text can
/// close the element.
fn json_string(out: &mut String, text: &str) {
    out.push('"');
    for c in text.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '<' | '>' | '&' | '\u{2028}' | '\u{2029}' => {
                let _ = write!(out, "\\u{:04x}", c as u32);
            }
            c if c.is_control() => {
                let _ = write!(out, "\\u{:04x}", c as u32);
            }
            c => out.push(c),
        }
    }
    out.push('"');
}

/// The machine-readable record of the report (see [`DATA_ID`]).
fn data_record(h: &mut String, r: &Sheet) {
    let _ = write!(
        h,
        "<script type=\"application/json\" id=\"{DATA_ID}\">{{\"report\":1,\"id\":"
    );
    json_string(h, &r.id);
    h.push_str(",\"date\":");
    json_string(h, &r.date);
    h.push_str(",\"quiz\":");
    match r
        .quiz
        .as_ref()
        .map(QuizSheet::result)
        .filter(|q| q.submitted)
    {
        None => h.push_str("null"),
        Some(q) => {
            let _ = write!(h, "{{\"seed\":\"{}\",\"answers\":[", q.seed);
            for (i, question) in q.questions.iter().enumerate() {
                if i > 0 {
                    h.push(',');
                }
                match q.answer(i, question) {
                    Response::Choice(Some(k)) => {
                        let _ = write!(h, "{k}");
                    }
                    Response::Choice(None) => h.push_str("null"),
                    Response::Text(t) => {
                        json_string(h, &t.chars().take(ANSWER_MAX_CHARS).collect::<String>());
                    }
                }
            }
            let (correct, total) = q.score();
            let _ = write!(h, "],\"score\":[{correct},{total}]}}");
        }
    }
    h.push_str("}</script>");
}

/// The parameter table: every parameter (grouped ones under their group's
/// heading) with its value and unit, then the text state the link carries.
fn parameters_section(h: &mut String, r: &Sheet) {
    h.push_str(
        "<section class=\"params\"><h2>Parameters</h2><table class=\"data\"><thead><tr>\
         <th scope=\"col\">Parameter</th><th scope=\"col\">Value</th><th scope=\"col\">Unit</th>\
         <th scope=\"col\">Link key</th></tr></thead><tbody>",
    );
    let specs = &r.params;
    let row = |h: &mut String, spec: &ParamRow| {
        let _ = write!(
            h,
            "<tr data-param=\"{}\"><th scope=\"row\">{}</th><td class=\"num\">{}</td><td>{}</td><td><code>{}</code></td></tr>",
            escape(&spec.key),
            escape(&spec.label),
            escape(&spec.value),
            escape(&spec.unit),
            escape(&spec.key)
        );
    };
    for spec in specs.iter().filter(|s| s.group.is_none()) {
        row(h, spec);
    }
    let mut groups: Vec<&str> = Vec::new();
    for g in specs.iter().filter_map(|s| s.group.as_deref()) {
        if !groups.contains(&g) {
            groups.push(g);
        }
    }
    for g in groups {
        let _ = write!(
            h,
            "<tr class=\"group\"><th colspan=\"4\" scope=\"rowgroup\">{}</th></tr>",
            escape(g)
        );
        for spec in specs.iter().filter(|s| s.group.as_deref() == Some(g)) {
            row(h, spec);
        }
    }
    for (key, value) in &r.extra_state {
        let shown: String = value.chars().take(TEXT_STATE_MAX).collect();
        let more = if value.chars().count() > TEXT_STATE_MAX {
            "… (the whole value is in the link)"
        } else {
            ""
        };
        let _ = write!(
            h,
            "<tr data-param=\"{k}\"><th scope=\"row\">Text state</th><td class=\"text\">{}{more}</td><td></td><td><code>{k}</code></td></tr>",
            escape(&shown),
            k = escape(key)
        );
    }
    h.push_str("</tbody></table></section>");
}

/// A parameter's value as the page shows it: a number, a toggle's or a
/// choice's label, or "not set".
fn param_value(spec: &ParamSpec, value: Option<f64>) -> String {
    let Some(v) = value else {
        return "not set".into();
    };
    match spec.kind {
        ParamKind::Toggle { off, on } => (if v >= 0.5 { on } else { off }).to_owned(),
        ParamKind::Choice(options) => options
            .get(v.round().max(0.0) as usize)
            .map_or_else(|| format_number(v, 0), |o| (*o).to_owned()),
        _ => format_number(v, 6),
    }
}

/// The status, the readouts and the live tables.
fn results_section(h: &mut String, r: &Sheet) {
    let status = &r.status;
    let tone = match status.tone {
        Tone::Neutral => "neutral",
        Tone::Good => "good",
        Tone::Warning => "warning",
        Tone::Bad => "bad",
    };
    let _ = write!(
        h,
        "<section class=\"results\"><h2>Results</h2><p class=\"status {tone}\"><strong>Status:</strong> {}</p>",
        escape(&status.text)
    );
    // A report made at a past moment shows the whole run: its end here,
    // the moment in a section of its own and as a line on the plots.
    let when = if r.shown.is_some() {
        "at the run's end"
    } else {
        "when the report was made"
    };
    scene_figure(h, &r.scene, r.view, when);
    readouts_table(h, &r.readouts, "Readouts");
    for t in &r.tables {
        live_table(h, t);
    }
    h.push_str("</section>");
}

/// `scene` as a picture, captioned "The simulation {when}".
fn scene_figure(h: &mut String, scene: &Scene, view: ViewBox, when: &str) {
    let (picture, thinned) = scene_svg::scene_svg(scene, view);
    let thinned = if thinned.is_empty() {
        String::new()
    } else {
        format!(" ({})", escape(&thinned.join("; ")))
    };
    let _ = write!(
        h,
        "<figure class=\"scene\">{picture}<figcaption>The simulation {}{thinned}.</figcaption></figure>",
        escape(when)
    );
}

/// `readouts` as a table captioned `caption`.
fn readouts_table(h: &mut String, readouts: &[Readout], caption: &str) {
    if readouts.is_empty() {
        return;
    }
    let _ = write!(
        h,
        "<table class=\"data readouts\"><caption>{}</caption><thead><tr><th scope=\"col\">Quantity</th>\
         <th scope=\"col\">Value</th></tr></thead><tbody>",
        escape(caption)
    );
    for r in readouts {
        let _ = write!(
            h,
            "<tr data-readout=\"{}\"><th scope=\"row\">{}</th><td class=\"num\">{}</td></tr>",
            escape(r.key),
            escape(r.label),
            escape(&r.value)
        );
    }
    h.push_str("</tbody></table>");
}

/// A section per marked moment: its status, scene and readouts. The mark
/// `shown` (an index) was on screen when the report was made.
fn marks_section(h: &mut String, marks: &[Moment], shown: Option<usize>) {
    if marks.is_empty() {
        return;
    }
    h.push_str("<section class=\"marks\"><h2>Marked moments</h2>");
    for (i, m) in marks.iter().enumerate() {
        let on_screen = if shown == Some(i) {
            ", on screen when the report was made"
        } else {
            ""
        };
        let title = format!("Mark {}: {}{on_screen}", i + 1, m.when());
        moment_section(h, m, "mark", &title);
    }
    h.push_str("</section>");
}

/// One moment's section (`class`: `mark`, or `moment` for the one on
/// screen): its title, status, scene and readouts.
fn moment_section(h: &mut String, m: &Moment, class: &str, title: &str) {
    let t = m.when();
    let _ = write!(
        h,
        "<section class=\"{class}\" data-{class}-t=\"{:.2}\"><h3>{}</h3>\
         <p class=\"status\"><strong>Status:</strong> {}</p>",
        m.t_s,
        escape(title),
        escape(&m.status.text)
    );
    scene_figure(h, &m.scene, m.view, &format!("at {t}"));
    readouts_table(h, &m.readouts, &format!("Readouts at {t}"));
    h.push_str("</section>");
}

fn live_table(h: &mut String, t: &Table) {
    let head: String = t
        .columns
        .iter()
        .map(|c| format!("<th scope=\"col\">{}</th>", escape(c)))
        .collect();
    let _ = write!(
        h,
        "<table class=\"data live\" data-table=\"{}\"><caption>{}</caption><thead><tr>{head}</tr></thead><tbody>",
        escape(t.key),
        escape(&t.caption)
    );
    for (i, row) in t.rows.iter().take(LIVE_TABLE_ROWS).enumerate() {
        let mark = if t.highlight == Some(i) {
            " class=\"current\""
        } else {
            ""
        };
        let cells: String = row
            .iter()
            .map(|c| format!("<td>{}</td>", escape(c)))
            .collect();
        let _ = write!(h, "<tr{mark}>{cells}</tr>");
    }
    h.push_str("</tbody></table>");
    if t.rows.len() > LIVE_TABLE_ROWS {
        let _ = write!(
            h,
            "<p class=\"muted\">The first {LIVE_TABLE_ROWS} of {} rows.</p>",
            t.rows.len()
        );
    }
}

/// Where the report's moments are on one plot: the moment on screen (a
/// line at its x) and the marks (a triangle at each point).
struct Moments<'a> {
    shown: Option<(f64, &'a Moment)>,
    marks: Vec<(f64, f64)>,
}

impl<'a> Moments<'a> {
    fn on(plot: &Plot, r: &'a Sheet) -> Self {
        let shown = r.shown.as_ref().and_then(|m| {
            let x = m.on(plot.key).iter().map(|p| p.0).reduce(f64::max)?;
            Some((x, m))
        });
        let marks = r
            .marks
            .iter()
            .flat_map(|m| m.on(plot.key))
            .copied()
            .collect();
        Self { shown, marks }
    }

    /// What the figure's caption says of them.
    fn caption(&self) -> String {
        let mut out = String::new();
        if let Some((_, m)) = self.shown {
            let _ = write!(
                out,
                " The vertical line marks the moment on screen when the report was made, {}.",
                m.when()
            );
        }
        if !self.marks.is_empty() {
            out.push_str(" A triangle marks each marked moment.");
        }
        out
    }
}

fn plots_section(h: &mut String, r: &Sheet) {
    if r.plots.is_empty() {
        return;
    }
    h.push_str("<section class=\"plots\"><h2>Plots</h2>");
    for (i, full) in r.plots.iter().enumerate() {
        // Series with no samples yet (an unused pin slot) are left out.
        let mut plot = full.clone();
        plot.series.retain(|s| !s.is_empty());
        let plot = &plot;
        let moments = Moments::on(plot, r);
        let _ = write!(
            h,
            "<figure class=\"plot\" data-plot=\"{}\">{}<figcaption><strong>Figure {}.</strong> {}{}</figcaption></figure>",
            escape(plot.key),
            plot_svg(plot, i, &moments),
            i + 1,
            escape(&plot.summary()),
            escape(&moments.caption())
        );
        data_table(h, plot, i + 1);
    }
    h.push_str("</section>");
}

/// Colour (the site's light theme, from the style table) and dash of each
/// series role: every pair of roles differs in dash as well as colour, so
/// the figure reads in grey print too.
fn role_style(role: SeriesRole) -> (&'static str, &'static [f64]) {
    let style = role.style();
    (style.colour.light, style.dash_px)
}

/// The page colours the report's stylesheet uses, as custom properties with
/// the light theme's values (`labcore::layout::page_colours`, which
/// `web/style.css` is held to), and the frame's colour (the bound's).
fn page_vars() -> String {
    let mut s = String::from(":root{color-scheme:light");
    for c in &PAGE {
        let _ = write!(s, ";{}:{}", c.var, c.light);
    }
    let _ = write!(s, ";--c-bound:{}}}", ink(Role::Bound));
    s
}

/// The light theme's colour of a scene role, for a plot's grid and text.
fn ink(role: Role) -> &'static str {
    role.style().light()
}

/// A number for an SVG attribute: two decimals are finer than print.
fn n(v: f64) -> String {
    format_number(v, 2)
}

/// An axis title with its unit: `Time (s)`.
fn axis_title(label: &str, unit: &str) -> String {
    if unit.is_empty() {
        label.to_owned()
    } else {
        format!("{label} ({unit})")
    }
}

/// One legend entry: a swatch (line or band) and a label.
struct LegendEntry {
    colour: &'static str,
    dash: &'static [f64],
    band: bool,
    label: String,
}

/// Where a plot's data go in the picture: the drawing rectangle and the
/// axes' ranges (the y axis as log₁₀ when `log`).
struct PlotMap {
    left: f64,
    right: f64,
    top: f64,
    bottom: f64,
    x: (f64, f64),
    y: (f64, f64),
    log: bool,
}

impl PlotMap {
    fn fy(&self, v: f64) -> f64 {
        if self.log {
            math::log10(v.max(1e-300))
        } else {
            v
        }
    }

    fn px(&self, x: f64) -> f64 {
        self.left + (x - self.x.0) / (self.x.1 - self.x.0) * (self.right - self.left)
    }

    fn py(&self, y: f64) -> f64 {
        let (fy0, fy1) = (self.fy(self.y.0), self.fy(self.y.1));
        self.bottom - (self.fy(y) - fy0) / (fy1 - fy0) * (self.bottom - self.top)
    }
}

/// The plot as an SVG figure: axes with nice ticks (linear or log), bands,
/// reference lines, every series decimated to [`DRAW_BUCKETS`] min–max
/// buckets, markers, the report's moments and a legend. `index` makes the
/// clip path's id unique in the document.
fn plot_svg(plot: &Plot, index: usize, moments: &Moments<'_>) -> String {
    let mut s = String::new();
    // Legend first: its rows set the drawing's top.
    let legend = legend_entries(plot);
    let (placed, legend_h) = place_legend(&legend);
    let top = legend_h + MARGIN.2;
    let height = top + SVG_H;
    let (left, right, bottom) = (
        MARGIN.0,
        SVG_W - MARGIN.1,
        top + SVG_H - MARGIN.3 - MARGIN.2,
    );
    let _ = write!(
        s,
        "<svg viewBox=\"0 0 {w} {hh}\" width=\"{w}\" height=\"{hh}\" \
         role=\"img\" aria-labelledby=\"plot{index}-title\" font-family=\"system-ui, sans-serif\" font-size=\"11\">\
         <title id=\"plot{index}-title\">{}</title>",
        escape(plot.title),
        w = n(SVG_W),
        hh = n(height),
    );
    legend_svg(&mut s, &placed);
    let Some((x0, x1)) = plot.x_range() else {
        let _ = write!(
            s,
            "<rect x=\"{l}\" y=\"{t}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"{frame}\"/>\
             <text x=\"{}\" y=\"{}\" text-anchor=\"middle\" fill=\"{muted}\">No data yet: run the simulation first.</text></svg>",
            n(right - left),
            n(bottom - top),
            n((left + right) / 2.0),
            n((top + bottom) / 2.0),
            l = n(left),
            t = n(top),
            frame = ink(Role::Bound),
            muted = MUTED.light
        );
        return s;
    };
    // A rolling window reaches back to the moment on screen, so its line
    // is drawn on the run's curves as the page draws it.
    let x0 = moments
        .shown
        .map_or(x0, |(x, _)| if x.is_finite() { x0.min(x) } else { x0 });
    let (x0, x1) = widen(x0, x1);
    let log = plot.log_y;
    let (mut y0, mut y1) = plot.y_range((x0, x1)).unwrap_or((0.0, 1.0));
    if log {
        y0 = y0.max(1e-300);
        y1 = y1.max(y0);
        let (a, b) = (math::log10(y0).floor(), math::log10(y1).ceil());
        y0 = power_of_ten(a as i32);
        y1 = power_of_ten((if b > a { b } else { a + 1.0 }) as i32);
    } else {
        let (a, b) = widen(y0, y1);
        let pad = (b - a) * 0.05;
        y0 = a - pad;
        y1 = b + pad;
    }
    let map = PlotMap {
        left,
        right,
        top,
        bottom,
        x: (x0, x1),
        y: (y0, y1),
        log,
    };
    grid_svg(&mut s, plot, &map);
    let _ = write!(
        s,
        "<defs><clipPath id=\"plot{index}-clip\"><rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\"/></clipPath></defs>\
         <g clip-path=\"url(#plot{index}-clip)\">",
        n(left),
        n(top),
        n(right - left),
        n(bottom - top)
    );
    bands_and_lines_svg(&mut s, plot, &map);
    // Comparison runs first, so the latest run is drawn on top.
    let order = plot
        .series
        .iter()
        .filter(|s| s.comparison)
        .chain(plot.series.iter().filter(|s| !s.comparison));
    for series in order {
        series_path(&mut s, series, (x0, x1), log, &|x| map.px(x), &|y| {
            map.py(y)
        });
    }
    s.push_str("</g>");
    markers_svg(&mut s, plot, &map);
    moments_svg(&mut s, moments, &map);
    let _ = write!(
        s,
        "<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"{frame}\"/></svg>",
        n(left),
        n(top),
        n(right - left),
        n(bottom - top),
        frame = ink(Role::Bound)
    );
    s
}

/// The legend's entries: the series, then the bands, then the reference lines.
fn legend_entries(plot: &Plot) -> Vec<LegendEntry> {
    let mut legend: Vec<LegendEntry> = plot
        .series
        .iter()
        .map(|s| {
            let (colour, dash) = role_style(s.role);
            LegendEntry {
                colour,
                dash,
                band: false,
                label: if s.unit.is_empty() || s.unit == plot.y_unit {
                    s.label.clone()
                } else {
                    format!("{} ({})", s.label, s.unit)
                },
            }
        })
        .collect();
    legend.extend(plot.bands.iter().map(|b| LegendEntry {
        colour: PLOT_BAND.light,
        dash: &[],
        band: true,
        label: b.label.clone(),
    }));
    let (reference, _) = role_style(SeriesRole::Reference);
    legend.extend(plot.ref_lines.iter().map(|l| LegendEntry {
        colour: reference,
        dash: &REF_LINE_DASH_PX,
        band: false,
        label: l.label.clone(),
    }));
    legend
}

/// The legend laid out in rows (about 6.2 units per character at 11 px):
/// each entry's corner, and the legend's height.
fn place_legend(legend: &[LegendEntry]) -> (Vec<(f64, f64, &LegendEntry)>, f64) {
    let mut placed: Vec<(f64, f64, &LegendEntry)> = Vec::new();
    let (mut x, mut y) = (MARGIN.0, 14.0);
    for e in legend {
        let w = 30.0 + 6.2 * e.label.chars().count() as f64 + 14.0;
        if x + w > SVG_W && x > MARGIN.0 {
            x = MARGIN.0;
            y += 16.0;
        }
        placed.push((x, y, e));
        x += w;
    }
    let legend_h = if legend.is_empty() { 0.0 } else { y + 8.0 };
    (placed, legend_h)
}

fn legend_svg(s: &mut String, placed: &[(f64, f64, &LegendEntry)]) {
    for (lx, ly, e) in placed {
        if e.band {
            let _ = write!(
                s,
                "<rect x=\"{}\" y=\"{}\" width=\"24\" height=\"9\" fill=\"{}\" fill-opacity=\"0.25\" stroke=\"{}\" stroke-width=\"0.8\"/>",
                n(*lx),
                n(ly - 7.0),
                e.colour,
                e.colour
            );
        } else {
            let _ = write!(
                s,
                "<line x1=\"{}\" y1=\"{y}\" x2=\"{}\" y2=\"{y}\" stroke=\"{}\" stroke-width=\"2.5\"{}/>",
                n(*lx),
                n(lx + 24.0),
                e.colour,
                dash_attr(e.dash),
                y = n(ly - 3.5)
            );
        }
        let _ = write!(
            s,
            "<text x=\"{}\" y=\"{}\" fill=\"{}\">{}</text>",
            n(lx + 30.0),
            n(*ly),
            ink(Role::Text),
            escape(&e.label)
        );
    }
}

/// Grid lines with their tick labels, and the axis titles.
fn grid_svg(s: &mut String, plot: &Plot, map: &PlotMap) {
    let (grid, text) = (ink(Role::Grid), ink(Role::Text));
    let PlotMap {
        left,
        right,
        top,
        bottom,
        log,
        ..
    } = *map;
    let x_ticks = nice_ticks(map.x.0, map.x.1, 8);
    let x_labels = tick_labels(&x_ticks, false);
    for (t, label) in x_ticks.iter().zip(&x_labels) {
        let x = map.px(*t);
        let _ = write!(
            s,
            "<line x1=\"{x}\" y1=\"{}\" x2=\"{x}\" y2=\"{}\" stroke=\"{grid}\"/>\
             <text x=\"{x}\" y=\"{}\" text-anchor=\"middle\" fill=\"{text}\">{}</text>",
            n(top),
            n(bottom),
            n(bottom + 14.0),
            escape(label),
            x = n(x)
        );
    }
    let (y0, y1) = map.y;
    let y_ticks = if log {
        log_ticks(y0, y1, 7)
    } else {
        nice_ticks(y0, y1, 7)
    };
    let y_labels = tick_labels(&y_ticks, log);
    for (t, label) in y_ticks.iter().zip(&y_labels) {
        let y = map.py(*t);
        let _ = write!(
            s,
            "<line x1=\"{}\" y1=\"{y}\" x2=\"{}\" y2=\"{y}\" stroke=\"{grid}\"/>\
             <text x=\"{}\" y=\"{}\" text-anchor=\"end\" fill=\"{text}\">{}</text>",
            n(left),
            n(right),
            n(left - 6.0),
            n(y + 4.0),
            escape(label),
            y = n(y)
        );
    }
    let _ = write!(
        s,
        "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\" fill=\"{text}\" font-size=\"12\">{}</text>\
         <text transform=\"translate(14 {}) rotate(-90)\" text-anchor=\"middle\" fill=\"{text}\" font-size=\"12\">{}</text>",
        n((left + right) / 2.0),
        n(bottom + 32.0),
        escape(&axis_title(plot.x_label, plot.x_unit)),
        n((top + bottom) / 2.0),
        escape(&axis_title(plot.y_label, plot.y_unit)),
    );
}

/// Shaded bands and dashed reference lines.
fn bands_and_lines_svg(s: &mut String, plot: &Plot, map: &PlotMap) {
    let PlotMap {
        left,
        right,
        top,
        bottom,
        ..
    } = *map;
    for b in &plot.bands {
        let (bx, by, bw, bh) = match b.axis {
            Axis::Y => {
                let (ya, yb) = (map.py(b.hi), map.py(b.lo));
                (left, ya.min(yb), right - left, (yb - ya).abs())
            }
            Axis::X => {
                let (xa, xb) = (map.px(b.lo), map.px(b.hi));
                (xa.min(xb), top, (xb - xa).abs(), bottom - top)
            }
        };
        if [bx, by, bw, bh].iter().all(|v| v.is_finite()) {
            let _ = write!(
                s,
                "<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"{}\" fill-opacity=\"{}\"/>",
                n(bx),
                n(by),
                n(bw),
                n(bh),
                PLOT_BAND.light,
                n(BAND_OPACITY)
            );
        }
    }
    let (reference, _) = role_style(SeriesRole::Reference);
    for l in &plot.ref_lines {
        let (xa, ya, xb, yb) = match l.axis {
            Axis::Y => (left, map.py(l.value), right, map.py(l.value)),
            Axis::X => (map.px(l.value), top, map.px(l.value), bottom),
        };
        if [xa, ya, xb, yb].iter().all(|v| v.is_finite()) {
            let _ = write!(
                s,
                "<line x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke=\"{reference}\" stroke-width=\"1.2\"{}/>",
                n(xa),
                n(ya),
                n(xb),
                n(yb),
                dash_attr(&REF_LINE_DASH_PX)
            );
        }
    }
}

/// Event markers: a ring and a label on the side with more room.
fn markers_svg(s: &mut String, plot: &Plot, map: &PlotMap) {
    let (left, right, top) = (map.left, map.right, map.top);
    let text = ink(Role::Text);
    for m in &plot.markers {
        if !(m.x.is_finite() && m.y.is_finite()) || (map.log && m.y <= 0.0) {
            continue;
        }
        let (mx, my) = (map.px(m.x), map.py(m.y));
        let anchor_end = mx > (left + right) / 2.0;
        let _ = write!(
            s,
            "<circle cx=\"{}\" cy=\"{}\" r=\"4\" fill=\"{}\" stroke=\"{text}\" stroke-width=\"1.5\"/>\
             <text x=\"{}\" y=\"{}\" text-anchor=\"{}\" fill=\"{text}\">{}</text>",
            n(mx),
            n(my),
            CANVAS.light,
            n(if anchor_end { mx - 7.0 } else { mx + 7.0 }),
            n((my - 7.0).max(top + 10.0)),
            if anchor_end { "end" } else { "start" },
            escape(&m.label)
        );
    }
}

/// The report's moments on a plot, as the page draws them: the moment on
/// screen as a vertical line in the text colour with a small triangle at
/// its top (the page's cursor), each mark as a downward triangle at its
/// point with a white outline.
fn moments_svg(s: &mut String, moments: &Moments<'_>, map: &PlotMap) {
    let text = ink(Role::Text);
    let inside = |x: f64| x.is_finite() && x >= map.x.0 && x <= map.x.1;
    if let Some((x, m)) = moments.shown.filter(|(x, _)| inside(*x)) {
        let px = map.px(x);
        let _ = write!(
            s,
            "<g class=\"cursor\" data-x=\"{x}\"><title>{}</title><line x1=\"{p}\" y1=\"{t}\" x2=\"{p}\" y2=\"{b}\" stroke=\"{text}\" stroke-width=\"1.5\"/>\
             <path d=\"M{} {t}h10l-5 7z\" fill=\"{text}\"/></g>",
            escape(&m.when()),
            n(px - 5.0),
            p = n(px),
            t = n(map.top),
            b = n(map.bottom),
        );
    }
    for &(x, y) in &moments.marks {
        if !inside(x) || !y.is_finite() || (map.log && y <= 0.0) {
            continue;
        }
        let (px, py) = (map.px(x), map.py(y));
        let _ = write!(
            s,
            "<path class=\"mark\" d=\"M{} {}h12l-6 10z\" fill=\"{text}\" stroke=\"{}\" stroke-width=\"1.5\"/>",
            n(px - 6.0),
            n(py - 10.0),
            CANVAS.light
        );
    }
}

/// A degenerate range widened around its value, so the axis has a width.
fn widen(lo: f64, hi: f64) -> (f64, f64) {
    if hi - lo > 1e-12 * lo.abs().max(hi.abs()).max(1e-300) {
        (lo, hi)
    } else {
        let pad = if lo == 0.0 { 1.0 } else { lo.abs() * 0.1 };
        (lo - pad, hi + pad)
    }
}

fn dash_attr(dash: &[f64]) -> String {
    if dash.is_empty() {
        String::new()
    } else {
        let pattern: Vec<String> = dash.iter().map(|d| format_number(*d, 2)).collect();
        format!(" stroke-dasharray=\"{}\"", pattern.join(" "))
    }
}

/// One series as an SVG path of its min–max decimated samples.
fn series_path(
    s: &mut String,
    series: &Series,
    (x0, x1): (f64, f64),
    log: bool,
    px: &dyn Fn(f64) -> f64,
    py: &dyn Fn(f64) -> f64,
) {
    let points = decimate_min_max(&series.x, &series.y, (x0, x1), DRAW_BUCKETS, |y| {
        !log || y > 0.0
    });
    if points.is_empty() {
        return;
    }
    let (colour, dash) = role_style(series.role);
    let mut d = String::with_capacity(points.len() * 14);
    for (i, (x, y)) in points.iter().enumerate() {
        let _ = write!(
            d,
            "{}{},{}",
            if i == 0 { "M" } else { "L" },
            n(px(*x)),
            n(py(*y))
        );
    }
    if points.len() == 1 {
        // A single sample: a dot.
        let _ = write!(
            s,
            "<circle cx=\"{}\" cy=\"{}\" r=\"2.5\" fill=\"{colour}\"/>",
            n(px(points[0].0)),
            n(py(points[0].1))
        );
        return;
    }
    let _ = write!(
        s,
        "<path d=\"{d}\" fill=\"none\" stroke=\"{colour}\" stroke-width=\"{}\" stroke-linejoin=\"round\"{}{}/>",
        if series.comparison { "1.5" } else { "2.2" },
        dash_attr(dash),
        if series.comparison {
            " stroke-opacity=\"0.6\""
        } else {
            ""
        }
    );
}

/// Indices of at most `max` evenly spaced samples of `len`, the first and
/// the last included (all of them when `len ≤ max`).
#[must_use]
pub fn table_rows(len: usize, max: usize) -> Vec<usize> {
    if len <= max {
        return (0..len).collect();
    }
    if max < 2 {
        return (0..max).collect();
    }
    let mut rows: Vec<usize> = (0..max)
        .map(|k| ((k as f64) * (len - 1) as f64 / (max - 1) as f64).round() as usize)
        .collect();
    rows.dedup();
    rows
}

/// A value in a data table: four decimals in the usual range, otherwise
/// four significant digits with an exponent.
fn cell(v: f64) -> String {
    let a = v.abs();
    if a == 0.0 || (1e-3..1e6).contains(&a) {
        format_number(v, 4)
    } else {
        format!("{v:.3e}")
    }
}

/// The plot's data as a table, at most [`TABLE_ROWS`] evenly spaced rows.
fn data_table(h: &mut String, plot: &Plot, figure: usize) {
    let total = plot.series.iter().map(Series::len).max().unwrap_or(0);
    let shared_x = plot.series.windows(2).all(|w| w[0].x == w[1].x);
    let col = |label: &str, unit: &str| {
        format!(
            "<th scope=\"col\">{}</th>",
            escape(&axis_title(label, unit))
        )
    };
    let head = if shared_x {
        let mut row = col(plot.x_label, plot.x_unit);
        for s in &plot.series {
            row.push_str(&col(&s.label, s.unit));
        }
        format!("<tr>{row}</tr>")
    } else {
        // Each series has its own x: its name over an (x, y) pair of columns.
        let mut names = String::new();
        let mut pairs = String::new();
        for s in &plot.series {
            let _ = write!(
                names,
                "<th scope=\"colgroup\" colspan=\"2\">{}</th>",
                escape(&s.label)
            );
            pairs.push_str(&col(plot.x_label, plot.x_unit));
            pairs.push_str(&col(plot.y_label, s.unit));
        }
        format!("<tr>{names}</tr><tr>{pairs}</tr>")
    };
    let _ = write!(
        h,
        "<table class=\"data plot-data\" data-plot-table=\"{}\"><caption>Data of figure {figure}: {}</caption>\
         <thead>{head}</thead><tbody>",
        escape(plot.key),
        escape(plot.title)
    );
    if total == 0 {
        let cols = if shared_x {
            plot.series.len() + 1
        } else {
            plot.series.len() * 2
        };
        let _ = write!(h, "<tr><td colspan=\"{cols}\">No samples yet.</td></tr>");
    } else if shared_x {
        let xs = &plot.series[0].x;
        for i in table_rows(xs.len(), TABLE_ROWS) {
            let _ = write!(h, "<tr><td>{}</td>", escape(&cell(xs[i])));
            for s in &plot.series {
                let _ = write!(
                    h,
                    "<td>{}</td>",
                    s.y.get(i).map_or(String::new(), |v| escape(&cell(*v)))
                );
            }
            h.push_str("</tr>");
        }
    } else {
        let picks: Vec<Vec<usize>> = plot
            .series
            .iter()
            .map(|s| table_rows(s.len(), TABLE_ROWS))
            .collect();
        let rows = picks.iter().map(Vec::len).max().unwrap_or(0);
        for r in 0..rows {
            h.push_str("<tr>");
            for (s, p) in plot.series.iter().zip(&picks) {
                match p.get(r) {
                    Some(&i) => {
                        let _ = write!(
                            h,
                            "<td>{}</td><td>{}</td>",
                            escape(&cell(s.x[i])),
                            escape(&cell(s.y[i]))
                        );
                    }
                    None => h.push_str("<td></td><td></td>"),
                }
            }
            h.push_str("</tr>");
        }
    }
    h.push_str("</tbody></table>");
    if total > TABLE_ROWS {
        let _ = write!(
            h,
            "<p class=\"muted table-note\">{TABLE_ROWS} evenly spaced rows of {total} samples (first and last included); \
             the figure is drawn from every sample, and the plot's CSV button in the lab exports them all.</p>"
        );
    }
}

fn quiz_section(h: &mut String, quiz: Option<&QuizResult<'_>>, key: AnswerKey) {
    h.push_str("<section class=\"quiz\"><h2>Self-assessment</h2>");
    let q = match quiz {
        Some(q) if q.submitted || key == AnswerKey::Always => q,
        _ => {
            h.push_str("<p class=\"muted\">The self-assessment had not been submitted when this report was made.</p></section>");
            return;
        }
    };
    let expected_shown = key != AnswerKey::Never;
    let expected_head = if expected_shown {
        "<th scope=\"col\">Expected</th>"
    } else {
        ""
    };
    if q.submitted {
        let (correct, total) = q.score();
        let _ = write!(
            h,
            "<p class=\"score\"><strong>Score: {correct} / {total} ({}%)</strong> · attempt seed <code>{}</code></p>\
             <p class=\"muted integrity\">Graded in the student's browser. This file keeps the answers and the \
             seed, so the lab's \u{201c}Check a report\u{201d} page (<code>check.html</code>) can grade them again and \
             show whether this score matches them. It cannot show whether the answers were edited: a file whose \
             answers and score were changed together passes. The score the LMS recorded is the authority.</p>",
            score_percent(correct, total),
            q.seed
        );
    } else {
        let _ = write!(
            h,
            "<p class=\"muted\">Not submitted when this report was made. The questions of attempt seed \
             <code>{}</code> with their expected answers, as the instructor's link asks:</p>",
            q.seed
        );
    }
    if !expected_shown {
        h.push_str("<p class=\"muted\">Expected answers are not shown in this report (the instructor's link).</p>");
    }
    let _ = write!(
        h,
        "<table class=\"data answers\"><thead><tr><th scope=\"col\">#</th><th scope=\"col\">Question</th>\
         <th scope=\"col\">Answer given</th>{expected_head}<th scope=\"col\">Result</th></tr></thead><tbody>"
    );
    for (i, question) in q.questions.iter().enumerate() {
        let answer = q.answer(i, question);
        let verdict = grade(question, &answer);
        // Options and prompts are content (trusted markup); typed text is escaped.
        let given = match (&question.kind, &answer) {
            (PreparedKind::Choice { options, .. }, Response::Choice(Some(k))) => options
                .get(*k)
                .cloned()
                .unwrap_or_else(|| "(no answer)".into()),
            (_, Response::Text(t)) if !t.trim().is_empty() => {
                let shown: String = t.chars().take(200).collect();
                match &verdict.read_as {
                    Some(read) if read.trim() != shown.trim() => format!(
                        "{} <span class=\"muted\">(read as {})</span>",
                        escape(&shown),
                        escape(read)
                    ),
                    _ => escape(&shown),
                }
            }
            _ => "<span class=\"muted\">(no answer)</span>".into(),
        };
        let expected = if !expected_shown {
            String::new()
        } else {
            let text = match question.kind {
                PreparedKind::Choice { .. } => verdict.expected.clone(),
                PreparedKind::Numeric { .. } => escape(&verdict.expected),
            };
            format!("<td class=\"expected\">{text}</td>")
        };
        let (class, mark) = if !q.submitted {
            ("open", "")
        } else if verdict.correct {
            ("right", "✓ correct")
        } else {
            ("wrong", "✗ wrong")
        };
        let _ = write!(
            h,
            "<tr class=\"{class}\"><td>{}</td><td>{}</td><td>{given}</td>{expected}<td>{mark}</td></tr>",
            i + 1,
            question.prompt
        );
    }
    h.push_str("</tbody></table></section>");
}

/// The report's style sheet: light, print-first, A4 and Letter.
const CSS: &str = "\
*{box-sizing:border-box}\
body{margin:0;background:var(--panel);color:var(--text);font:11pt/1.45 system-ui,-apple-system,'Segoe UI',Roboto,Arial,sans-serif}\
main{max-width:180mm;margin:0 auto;padding:12mm 8mm}\
h1{font-size:20pt;margin:.1em 0 .3em;line-height:1.2}\
h2{font-size:14pt;margin:1.4em 0 .5em;padding-bottom:.15em;border-bottom:1.5px solid var(--accent);break-after:avoid;page-break-after:avoid}\
.eyebrow{margin:0;color:var(--muted);font-size:9.5pt;letter-spacing:.03em;text-transform:uppercase}\
.meta{display:flex;flex-wrap:wrap;gap:.4em 2em;margin:.4em 0}\
.meta div{display:flex;gap:.5em;align-items:baseline}\
.meta dt{font-weight:600}.meta dd{margin:0}\
.meta dd.field{min-width:38mm;border-bottom:1px solid var(--text);min-height:1.2em;padding:0 .2em}\
.link{font-size:9.5pt;overflow-wrap:anywhere;word-break:break-all;margin:.4em 0}\
a{color:#0057a0}\
.note{border-left:4px solid #B36B00;background:#fdf5e8;padding:.4em .8em;margin:1em 0}\
.muted{color:var(--muted)}\
table.data{border-collapse:collapse;width:100%;margin:.5em 0 1em;font-size:9.5pt;break-inside:avoid;page-break-inside:avoid}\
table.data caption{text-align:left;font-weight:600;padding:.2em 0}\
table.data th,table.data td{border:1px solid #c9d0d8;padding:.2em .45em;text-align:left;vertical-align:top}\
table.data thead th{background:#eef2f6}\
table.data td.num,table.plot-data td{font-variant-numeric:tabular-nums}\
table.data td.text{overflow-wrap:anywhere;word-break:break-all;font-family:ui-monospace,Menlo,Consolas,monospace;font-size:8.5pt}\
tr.group th{background:var(--bg);font-style:italic}\
tr.current td{font-weight:600}\
.status.good{color:var(--good)}.status.warning{color:var(--warn)}.status.bad{color:var(--bad)}\
figure.plot,figure.scene{margin:1em 0 .4em;break-inside:avoid;page-break-inside:avoid}\
figure.scene svg{display:block;max-width:100%;height:auto;margin:0 auto}\
figure.plot svg{display:block;width:100%;height:auto;max-width:100%}\
figcaption{font-size:9pt;color:#3b434c;margin-top:.3em}\
.table-note{font-size:8.5pt;margin-top:-.6em}\
table.answers td:last-child{white-space:nowrap}table.answers td:nth-child(2){width:45%}\
tr.right td:last-child{color:var(--good);font-weight:600}tr.wrong td:last-child{color:var(--bad);font-weight:600}\
.observations{break-inside:avoid;page-break-inside:avoid}\
.lines{border:1px solid var(--c-bound);border-radius:4px;padding:0 4mm}\
.line{height:9mm;border-bottom:1px solid #c9d0d8}\
.obs-text{white-space:pre-wrap;overflow-wrap:anywhere;line-height:9mm;min-height:9mm;border-bottom:1px solid #c9d0d8}\
[contenteditable]:focus{outline:2px solid var(--accent);outline-offset:1px}\
.integrity{font-size:8.5pt}\
.line:last-child{border-bottom:0}\
footer{margin-top:2em;font-size:8.5pt;color:var(--muted);border-top:1px solid var(--line)}\
code{font-family:ui-monospace,Menlo,Consolas,monospace;font-size:.92em}\
@page{size:auto;margin:15mm 14mm}\
@page :first{margin-top:12mm}\
@media print{main{max-width:none;padding:0}a{color:var(--text)}body{font-size:10pt}h2{margin-top:1em}\
*{-webkit-print-color-adjust:exact;print-color-adjust:exact}}\
";

#[cfg(test)]
mod tests;
