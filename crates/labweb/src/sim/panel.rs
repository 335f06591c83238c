//! The side panel: parameter controls (grouped under collapsed headings),
//! readouts, live tables, the action buttons and the plot tools.

use super::{export_png, read_file, SimState};
use crate::dom::{self, escape, query, query_all, Listener};
use crate::plot_view;
use labcore::layout::ticks::step_decimals;
use labcore::units::format_number;
use labcore::{ParamKind, ParamSpec, Sanitized};
use std::cell::RefCell;
use std::rc::Rc;
use wasm_bindgen::JsCast;
use web_sys::{Element, Event, HtmlInputElement, HtmlSelectElement, PointerEvent};

/// Wires the controls form and the buttons of the Simulation panel to `state`.
pub(super) fn listen(
    state: &Rc<RefCell<SimState>>,
    panel: &Element,
    listeners: &mut Vec<Listener>,
) {
    // The browser is idle after a frame that left "The math" panel to it
    // ([`SimState::sync_math`]), or that asked for a scrub's rehearsal.
    let s = state.clone();
    listeners.push(Listener::new(panel.as_ref(), "lab-idle", move |_| {
        if let Ok(mut st) = s.try_borrow_mut() {
            if st.math_idle_asked {
                st.write_math_when_idle();
            }
            if st.rehearse_asked {
                st.rehearse_scrub();
            }
        }
    }));
    // The controls, and those that sit with the actions
    // ([`ParamSpec::with_actions`]).
    for form in dom::query_all(panel, ".sim-controls, .sim-actions") {
        // Enter in a number box applies it (on change) and never submits the
        // form (which would reload the page); a listener, not an inline
        // `onsubmit`, which the Content-Security-Policy forbids.
        listeners.push(Listener::new(form.as_ref(), "submit", |e: Event| {
            e.prevent_default();
        }));
        let s = state.clone();
        listeners.push(Listener::new(form.as_ref(), "input", move |e: Event| {
            let Some(input) = e
                .target()
                .and_then(|t| t.dyn_into::<HtmlInputElement>().ok())
            else {
                return;
            };
            let Some(key) = input.get_attribute("data-param") else {
                return;
            };
            // Number boxes apply on change (Enter or leaving the box), never
            // mid-typing: "1e9" on the way to "1e99", "0" on the way to "0.5".
            if input.type_() == "text" {
                return;
            }
            let value = input.value_as_number();
            let value = if input.type_() == "radio" {
                input.value().parse().unwrap_or(0.0)
            } else {
                value
            };
            let mut st = s.borrow_mut();
            st.student_acted();
            st.set_param(&key, value);
            // Mirror slider → number box now (the number box is not focused).
            if let Some(i) = st.exp.params().iter().position(|p| p.key == key) {
                st.shown_values[i] = None;
            }
        }));
        let s = state.clone();
        listeners.push(Listener::new(form.as_ref(), "change", move |e: Event| {
            let target = e.target();
            let mut st = s.borrow_mut();
            st.student_acted();
            if let Some(select) = target
                .clone()
                .and_then(|t| t.dyn_into::<HtmlSelectElement>().ok())
            {
                if let Some(key) = select.get_attribute("data-param") {
                    st.set_param(&key, select.value().parse().unwrap_or(f64::NAN));
                }
            } else if let Some(input) = target.and_then(|t| t.dyn_into::<HtmlInputElement>().ok()) {
                if let Some(key) = input.get_attribute("data-param") {
                    if input.type_() == "text" {
                        let raw = input.value();
                        let unit = st
                            .exp
                            .params()
                            .iter()
                            .find(|p| p.key == key)
                            .map_or("", |p| p.unit);
                        // One rule for commas and units everywhere (see
                        // `labcore::units::read_answer`); say what was read.
                        let reading = if raw.trim().is_empty() {
                            Err(None)
                        } else {
                            labcore::units::read_answer(&raw, unit).map_err(Some)
                        };
                        match reading {
                            Ok(r) => {
                                st.set_param(&key, r.value);
                                let plain = raw.trim().parse::<f64>().is_ok();
                                if !plain {
                                    st.show_message(Some(&format!(
                                        "Read “{}” as {}.",
                                        raw.trim(),
                                        r.read_as
                                    )));
                                }
                            }
                            Err(e) => {
                                let why = e.map_or_else(
                                    || "nothing was typed".to_owned(),
                                    |e| e.to_string(),
                                );
                                st.show_message(Some(&format!(
                                    "Could not read that: {why}. Kept the previous value."
                                )));
                                // Show the kept value again.
                                st.shown_values.iter_mut().for_each(|v| *v = None);
                            }
                        }
                        if let Some(i) = st.exp.params().iter().position(|p| p.key == key) {
                            st.shown_values[i] = None;
                        }
                        // Show the applied value even though the box has focus.
                        if let Some(spec) = st.exp.params().iter().find(|p| p.key == key).copied() {
                            set_control_value(&st.panel, &spec, st.exp.param(&key), None);
                        }
                    }
                }
            }
            st.announce_when_settled();
        }));
    }
    if let Some(sim) = query(panel, ".sim") {
        let s = state.clone();
        listeners.push(Listener::new(sim.as_ref(), "click", move |e: Event| {
            let target = e.target().and_then(|t| t.dyn_into::<Element>().ok());
            if let (Some(canvas), Some(m)) = (
                target
                    .as_ref()
                    .filter(|el| el.class_list().contains("plot-canvas")),
                e.dyn_ref::<web_sys::MouseEvent>(),
            ) {
                // A point of the plot (a click or a tap, not a swipe that
                // scrolls): the timeline goes to that moment.
                s.borrow_mut()
                    .go_to_plot_point(canvas, f64::from(m.client_x()));
                return;
            }
            let Some(button) = target.and_then(|el| el.closest("button").ok().flatten()) else {
                return;
            };
            let attr = |name: &str| button.get_attribute(name);
            let mut st = s.borrow_mut();
            if let Some(key) = attr("data-action") {
                st.branch_cause = st.exp.actions().iter().find(|a| a.key == key);
                let mut done = Ok(());
                st.guarded(|exp| done = exp.action(&key));
                if let Err(err) = done {
                    st.show_message(Some(&err.to_string()));
                }
                st.needs_paint = true;
                st.hash_dirty = true;
            } else if let Some(what) = attr("data-time") {
                match what.as_str() {
                    "play" => st.play_pressed(),
                    "step" => st.single_step(),
                    "back" => st.step_back(),
                    "end" => st.start_run_to_end(),
                    "reset" => st.reset_run(),
                    "mark" => st.toggle_mark(),
                    _ => {}
                }
            } else if let Some(step) = attr("data-unmark").and_then(|s| s.parse().ok()) {
                st.remove_mark(step);
            } else if let Some(step) = attr("data-goto").and_then(|s| s.parse().ok()) {
                // A mark's time: the timeline goes to that moment.
                st.student_acted();
                st.seek(step);
            } else if button.has_attribute("data-touch-mode") {
                st.touch_draws = !st.touch_draws;
                let on = st.touch_draws;
                let _ = button.set_attribute("aria-pressed", if on { "true" } else { "false" });
                let _ = st
                    .canvas
                    .set_attribute("data-touch", if on { "all" } else { "handles" });
            } else if attr("data-file").as_deref() == Some("pick") {
                if let Some(input) = query(&st.panel, "input.file-input")
                    .and_then(|i| i.dyn_into::<HtmlInputElement>().ok())
                {
                    input.click();
                }
            } else if attr("data-export").as_deref() == Some("text") {
                if let Some((name, text)) = st.exp.export_text() {
                    plot_view::download(&name, "text/plain", &text);
                }
            } else if attr("data-export").as_deref() == Some("report") {
                let marked = st.marked_states();
                // Scrubbed back, the report is the whole run (the record's
                // end) with the moment shown on it, as the page draws it.
                let st = &*st;
                let (end, shown) = match st.record_end.as_deref() {
                    Some(end) => (end, Some((st.clock.time_s(), &*st.exp))),
                    None => (&*st.exp, None),
                };
                crate::report_view::download(&st.panel, end, &st.link(), &marked, shown);
            } else if attr("data-export").as_deref() == Some("png") {
                st.scene_draft = false;
                st.paint();
                export_png(&st.canvas, &format!("{}.png", st.file_stem()));
            } else if let Some(key) = attr("data-plot-csv") {
                if let Some(plot) = st.run_plots().iter().find(|p| p.key == key) {
                    let name = format!("{}-{}.csv", st.file_stem(), plot.key);
                    plot_view::download(&name, "text/csv", &plot.to_csv());
                }
            } else if let Some(key) = attr("data-plot-fit") {
                st.plots.toggle_fit(&key);
                st.plots_force = true;
            } else if let Some(key) = attr("data-plot-table") {
                let st = &*st;
                st.plots.toggle_table(&key, st.run_plots());
            }
        }));
        let s = state.clone();
        listeners.push(Listener::new(sim.as_ref(), "change", move |e: Event| {
            let target = e.target().and_then(|t| t.dyn_into::<Element>().ok());
            if target.is_some_and(|t| t.has_attribute("data-report-field")) {
                let st = s.borrow();
                let _ = crate::report_view::remember(&st.panel, st.exp.id());
                return;
            }
            if let Some(input) = e
                .target()
                .and_then(|t| t.dyn_into::<HtmlInputElement>().ok())
                .filter(|i| i.type_() == "file")
            {
                if let Some(file) = input.files().and_then(|f| f.get(0)) {
                    read_file(&s, file);
                }
                input.set_value("");
                return;
            }
            let Some(select) = e
                .target()
                .and_then(|t| t.dyn_into::<HtmlSelectElement>().ok())
                .filter(|el| el.get_attribute("data-time").as_deref() == Some("speed"))
            else {
                return;
            };
            let mut st = s.borrow_mut();
            let v = select.value().parse().unwrap_or(1.0);
            st.clock.set_speed(v);
            st.hash_dirty = true;
        }));
        for kind in ["pointermove", "pointerdown", "pointerleave"] {
            let s = state.clone();
            listeners.push(Listener::new(sim.as_ref(), kind, move |e: Event| {
                let Some(e) = e.dyn_ref::<PointerEvent>() else {
                    return;
                };
                if kind == "pointerdown" {
                    // The caption follows the input in use (a touch hint on a phone).
                    if let Ok(mut st) = s.try_borrow_mut() {
                        let touch = e.pointer_type() == "touch";
                        if st.touch_input != touch {
                            st.touch_input = touch;
                            st.sync_hint();
                            st.sync_status();
                            st.shown_notice = None;
                        }
                    }
                }
                let Some(canvas) = e
                    .target()
                    .and_then(|t| t.dyn_into::<Element>().ok())
                    .filter(|el| el.class_list().contains("plot-canvas"))
                else {
                    return;
                };
                let mut st = s.borrow_mut();
                let st = &mut *st;
                let x = (kind != "pointerleave").then(|| f64::from(e.client_x()));
                st.with_shown_plots(|view, plots, palette| view.hover(&canvas, x, plots, palette));
            }));
        }
    }
}
pub(super) fn readouts_html(readouts: &[labcore::Readout]) -> String {
    readouts
        .iter()
        .map(|r| {
            format!(
                "<div class=\"readout\"><dt>{}</dt><dd data-readout=\"{}\">{}</dd></div>",
                escape(r.label),
                r.key,
                escape(&r.value)
            )
        })
        .collect()
}
/// The controls: ungrouped ones first, then each [`ParamSpec::group`] under a
/// collapsed heading (in the order the groups first appear).
pub(super) fn controls_html(specs: &[ParamSpec]) -> String {
    let mut html = group_html(specs, None);
    let mut groups: Vec<&str> = Vec::new();
    for g in specs
        .iter()
        .filter_map(|s| s.group)
        .filter(|g| *g != ParamSpec::WITH_ACTIONS)
    {
        if !groups.contains(&g) {
            groups.push(g);
        }
    }
    for g in groups {
        let body = group_html(specs, Some(g));
        // What the heading counts (points, not fields) comes with the
        // values, at the first sync and on every change.
        html.push_str(&format!(
            "<details class=\"ctl-group\"><summary>{g} <span class=\"ctl-count\" data-group=\"{g}\"></span></summary>\
             <div class=\"ctl-group-body\">{body}</div></details>",
            g = escape(g),
        ));
    }
    html
}

/// The controls of group `g` (`None`: the main ones; [`ParamSpec::WITH_ACTIONS`]:
/// those beside the action buttons).
pub(super) fn group_html(specs: &[ParamSpec], g: Option<&str>) -> String {
    specs
        .iter()
        .filter(|s| s.group == g)
        .map(control_html)
        .collect()
}

fn control_html(spec: &ParamSpec) -> String {
    let key = spec.key;
    let label = escape(spec.label);
    let unit = escape(spec.unit);
    let v = format_number(spec.default, 4);
    match spec.kind {
        ParamKind::Slider => format!(
            "<div class=\"ctl ctl-slider\" data-ctl=\"{key}\"><label for=\"p-{key}\">{label}</label>\
             <input type=\"range\" id=\"p-{key}\" data-param=\"{key}\" min=\"{min}\" max=\"{max}\" step=\"{step}\" value=\"{v}\">\
             <span class=\"ctl-num\"><input type=\"text\" inputmode=\"decimal\" autocomplete=\"off\" spellcheck=\"false\" data-param=\"{key}\" min=\"{min}\" max=\"{max}\" step=\"any\" value=\"{v}\" aria-label=\"{label} value{unit_aria}\">\
             <span class=\"unit\" aria-hidden=\"true\">{unit}</span></span></div>",
            min = spec.min,
            max = spec.max,
            step = spec.step,
            unit_aria = if spec.unit.is_empty() { String::new() } else { format!(" in {unit}") },
        ),
        ParamKind::OptionalNumber => format!(
            "<div class=\"ctl ctl-number\" data-ctl=\"{key}\"><label for=\"p-{key}\">{label}</label>\
             <span class=\"ctl-num\"><input type=\"text\" inputmode=\"decimal\" autocomplete=\"off\" spellcheck=\"false\" id=\"p-{key}\" data-param=\"{key}\" min=\"{min}\" max=\"{max}\" step=\"any\" \
             placeholder=\"—\" aria-label=\"{label}{unit_aria}\"><span class=\"unit\" aria-hidden=\"true\">{unit}</span></span></div>",
            min = spec.min,
            max = spec.max,
            unit_aria = if spec.unit.is_empty() { String::new() } else { format!(" in {unit}") },
        ),
        ParamKind::Number => format!(
            "<div class=\"ctl ctl-number\" data-ctl=\"{key}\"><label for=\"p-{key}\">{label}</label>\
             <span class=\"ctl-num\"><input type=\"text\" inputmode=\"decimal\" autocomplete=\"off\" spellcheck=\"false\" id=\"p-{key}\" data-param=\"{key}\" min=\"{min}\" max=\"{max}\" step=\"1\" value=\"{v}\"></span></div>",
            min = spec.min,
            max = spec.max,
        ),
        ParamKind::Toggle { off, on } => format!(
            "<fieldset class=\"ctl ctl-toggle\" data-ctl=\"{key}\"><legend>{label}</legend><div class=\"seg\">\
             <label><input type=\"radio\" name=\"p-{key}\" data-param=\"{key}\" value=\"1\"{c1}><span>{on}</span></label>\
             <label><input type=\"radio\" name=\"p-{key}\" data-param=\"{key}\" value=\"0\"{c0}><span>{off}</span></label>\
             </div></fieldset>",
            on = escape(on),
            off = escape(off),
            c1 = if spec.default >= 0.5 { " checked" } else { "" },
            c0 = if spec.default < 0.5 { " checked" } else { "" },
        ),
        ParamKind::Choice(options) => {
            let opts: String = options
                .iter()
                .enumerate()
                .map(|(i, o)| {
                    let sel = if (i as f64 - spec.default).abs() < 0.5 { " selected" } else { "" };
                    format!("<option value=\"{i}\"{sel}>{}</option>", escape(o))
                })
                .collect();
            format!(
                "<div class=\"ctl ctl-choice\" data-ctl=\"{key}\"><label for=\"p-{key}\">{label}</label>\
                 <select id=\"p-{key}\" data-param=\"{key}\">{opts}</select></div>"
            )
        }
    }
}
/// Shows `value` in every control of `spec` (`None`: an empty optional field).
pub(super) fn set_control_value(
    panel: &Element,
    spec: &ParamSpec,
    value: Option<f64>,
    active: Option<&Element>,
) {
    for el in query_all(panel, &format!("[data-param=\"{}\"]", spec.key)) {
        let Some(v) = value else {
            if let Some(input) = el.dyn_ref::<HtmlInputElement>() {
                if active != Some(&el) {
                    input.set_value("");
                }
            }
            continue;
        };
        if let Some(input) = el.dyn_ref::<HtmlInputElement>() {
            match input.type_().as_str() {
                "radio" => input.set_checked((input.value() == "1") == (v >= 0.5)),
                "text" => {
                    if active != Some(&el) {
                        input.set_value(&format_number(v, (step_decimals(spec.step) + 1).min(3)));
                    }
                }
                _ => input.set_value(&format_number(v, 4)),
            }
        } else if let Some(select) = el.dyn_ref::<HtmlSelectElement>() {
            select.set_value(&format!("{}", v.round() as i64));
        }
    }
}
/// The HTML of the experiment's tables.
pub(super) fn tables_html(tables: &[labcore::Table]) -> String {
    tables
        .iter()
        .map(|t| {
            let head: String = t
                .columns
                .iter()
                .map(|c| format!("<th scope=\"col\">{}</th>", escape(c)))
                .collect();
            let body: String = t
                .rows
                .iter()
                .enumerate()
                .map(|(i, r)| {
                    let cells: String = r.iter().map(|c| format!("<td>{}</td>", escape(c))).collect();
                    let mark = if t.highlight == Some(i) {
                        " class=\"current\" aria-current=\"true\""
                    } else {
                        ""
                    };
                    format!("<tr{mark}>{cells}</tr>")
                })
                .collect();
            format!(
                "<div class=\"table-scroll live-table\" data-table=\"{}\" tabindex=\"0\"><table><caption>{}</caption>\
                 <thead><tr>{head}</tr></thead><tbody>{body}</tbody></table></div>",
                t.key,
                escape(&t.caption)
            )
        })
        .collect()
}

impl SimState {
    /// Brings controls, readouts and the status badge up to date with the state.
    pub(super) fn sync_dom(&mut self) {
        let active = dom::document().active_element();
        let mut changed = false;
        for (i, spec) in self.exp.params().iter().enumerate() {
            let value = self.exp.param(spec.key);
            if self.shown_values.get(i) == Some(&Some(value)) {
                continue;
            }
            changed = true;
            set_control_value(&self.panel, spec, value, active.as_ref());
            if let Some(slot) = self.shown_values.get_mut(i) {
                *slot = Some(value);
            }
        }
        if changed {
            // A group heading counts its points ("Waypoints (2)").
            for span in query_all(&self.panel, ".ctl-count[data-group]") {
                if let Some(g) = span.get_attribute("data-group") {
                    let exp = &self.exp;
                    let n = labcore::experiment::group_count(exp.params(), &g, &|k| exp.param(k));
                    span.set_text_content(Some(&format!("({n})")));
                }
            }
        }
        let readouts = self.exp.readouts();
        if self.shown_readouts.len() != readouts.len() {
            // The set of readouts changed: rebuild the list.
            if let Some(list) = query(&self.panel, "dl.readouts") {
                list.set_inner_html(&readouts_html(&readouts));
            }
            self.shown_readouts = vec![String::new(); readouts.len()];
            self.readout_elements = readouts
                .iter()
                .map(|r| query(&self.panel, &format!("[data-readout=\"{}\"]", r.key)))
                .collect();
        }
        // Written with the panel's equations, whose results they are, when
        // the browser is idle: both change in the same frame. The status
        // goes with the readouts: ekf's verdict names the average NEES its
        // readout shows, and written in the frame it showed a step the
        // readouts had not reached (a fresh-clone e2e run read the verdict
        // beside an "Average NEES" of "--").
        self.readouts_in_idle = self.sync_math(&readouts);
        if !self.readouts_in_idle {
            self.write_readouts_and_status(&readouts);
        }
        self.sync_hint();
        self.sync_actions();
        let tables = self.exp.tables();
        if tables != self.shown_tables {
            // Rewritten in place (`dom::rewrite_markup`): A*'s table of the
            // open list changes its numbers at every expansion, and parsing
            // it anew was 0.4 ms of a scrub's text frame (unthrottled).
            if let Some(section) = query(&self.panel, ".tables") {
                dom::rewrite_markup(&section, &tables_html(&tables));
            }
            self.shown_tables = tables;
        }
        self.sync_move_form();
    }

    /// Shows the action buttons that have something to act on and hides
    /// the others ([`labcore::Experiment::action_shown`]). A button hidden
    /// while it has the focus (pressed from the keyboard) hands the focus
    /// to the first button shown beside it.
    fn sync_actions(&mut self) {
        // A bit per button, in the order of `actions()` (a handful).
        let mut shown = 0u32;
        for (i, a) in self.exp.actions().iter().enumerate().take(32) {
            if self.exp.action_shown(a.key) {
                shown |= 1 << i;
            }
        }
        if self.shown_actions == Some(shown) {
            return;
        }
        let active = dom::document().active_element();
        let (mut first, mut lost_focus) = (None, false);
        for (i, button) in query_all(&self.panel, "button[data-action]")
            .into_iter()
            .enumerate()
        {
            let show = i < 32 && shown >> i & 1 == 1;
            lost_focus |= !show && active.as_ref() == Some(&button);
            dom::set_hidden(&button, !show);
            if show && first.is_none() {
                first = Some(button);
            }
        }
        if let Some(b) = first.filter(|_| lost_focus) {
            if let Some(b) = b.dyn_ref::<web_sys::HtmlElement>() {
                let _ = b.focus();
            }
        }
        self.shown_actions = Some(shown);
    }

    /// Writes the readouts whose text changed (a write makes the browser
    /// lay the page out again), then the status badge: a verdict in the
    /// badge names a readout, so the two are written together, never one
    /// a frame before the other.
    fn write_readouts_and_status(&mut self, readouts: &[labcore::Readout]) {
        // The step they are of (what "The math" panel's `data-step` is
        // compared with: the two show one step where the two agree).
        if let Some(list) = query(&self.panel, "dl.readouts") {
            name_step(&list, self.clock.steps());
        }
        for ((r, shown), dd) in readouts
            .iter()
            .zip(self.shown_readouts.iter_mut())
            .zip(&self.readout_elements)
        {
            if *shown != r.value {
                if let Some(dd) = dd {
                    dom::set_text(dd, &r.value);
                }
                shown.clone_from(&r.value);
            }
        }
        self.sync_status();
    }

    /// Works out the parts of "The math" panel whose text changed (each
    /// equation's substituted form, its result and its text twin) and
    /// writes them, now or in the browser's idle time. Returns whether it
    /// left them, and so the readouts, to the idle time.
    ///
    /// - **A single input or the end of a motion** (a click, a typed value,
    ///   the end of a drag, a run that stops): written now, in the frame
    ///   that shows it, with whatever an idle chain had still to write.
    ///   The status a run ends with and its readouts change together.
    /// - **The pace of a run or of a stream of input** (a drag, a held key,
    ///   a timeline scrub): left to the browser's idle time after the
    ///   frame, and worked out and written then, the readouts with the
    ///   first equation and one equation an idle time
    ///   ([`SimState::math_pending`]), and laid out there
    ///   ([`SimState::write_math_when_idle`]).
    ///   Written in a frame, each formula made the browser lay the whole
    ///   page out in it (0.6–1.3 ms unthrottled), four times a second per
    ///   equation (issue 27, cost); worked out there, the numbers raised
    ///   the frames' script p95 (ekf on the phone stand-in: 5.1 ms open
    ///   against 3.7 ms closed, at 4×).
    /// - **Where the browser has no idle callbacks** (WebKit): the frames
    ///   after it write them one each ([`SimState::write_next_equation`]),
    ///   so no frame pays for the readouts and every formula together
    ///   (traced on the phone stand-in, ekf: the worst frame's layout fell
    ///   from 23–35 ms to 10–19 at 4×); at a pause or the end of a motion,
    ///   all at once.
    /// - **A streaming run or stream of input, for an equation out of the
    ///   window** (on a phone, below the scene): it is not written, every
    ///   write there costing the page a style, layout and paint pass for
    ///   nothing (DLS moved by held keys on the phone stand-in, scene in
    ///   view: the running p95 ×1.14 with the panel open; fk, whose second
    ///   equation is below the window there, laid out and painted the math
    ///   twice for once). The next write after it scrolls in, or the one
    ///   when the run or the stream settles, brings it up to date.
    ///
    /// Where an equation keeps its shape only its numbers' text is
    /// rewritten ([`dom::rewrite_markup`]), and each equation is its text
    /// twin's containing block (the stylesheet).
    fn sync_math(&mut self, readouts: &[labcore::Readout]) -> bool {
        #[cfg(feature = "bench-exports")]
        if self.bench_math_closed {
            return false;
        }
        self.math_pending.clear();
        if !self.text_settled && !self.equations_on_screen.iter().any(|&seen| seen) {
            return false;
        }
        let set = self.exp.equations().as_ptr() as usize;
        // A text update at the pace of a run or of a stream of input (a
        // drag, a held key, a timeline scrub) is worked out and written in
        // the idle time, at the latest by the next update (an equation out
        // of the window is left, [`SimState::collect_math`]). A settled one
        // (an input, the end of a motion) is written now, whatever an idle
        // chain had left: the status a run ends with and its readouts
        // change together.
        if !self.text_settled && set == self.shown_equations {
            if !self.math_idle_asked {
                // Its `lab-idle` event calls write_math_when_idle ([`listen`]).
                self.math_idle_asked = dom::when_idle(&self.panel, super::TEXT_INTERVAL_MS as u32);
            }
            if self.math_idle_asked {
                return true;
            }
        }
        let equations = super::panel_equations(self.exp.as_ref());
        if equations.is_empty() {
            return false;
        }
        let quantities = self.quantities();
        if set != self.shown_equations {
            // Another set of equations (a parameter chose it): write the
            // panel anew, symbols included.
            if let Some(section) = query(&self.panel, ".live-math") {
                section.set_outer_html(&labpage::math_panel::panel_html(
                    &equations,
                    &quantities,
                    readouts,
                ));
                // The observers watched the elements just replaced.
                self.math_watch = super::watch_equations(&self.panel);
                self.equations_on_screen = vec![true; self.math_watch.len()];
            }
            self.shown_equations = set;
            self.shown_math.clear();
            // The new panel holds no height.
            self.math_held_px = 0;
        }
        self.collect_math(&equations, &quantities, readouts);
        if self.text_at_once {
            while self.write_next_equation() {}
        }
        if self.text_settled {
            // Nothing moves now: the panel takes its own height again.
            self.release_math_height();
        }
        false
    }

    /// Lists in [`SimState::math_pending`] the equations whose parts differ
    /// from those shown, with their new parts, the first last (written by
    /// popping). At a run's or a stream's pace an equation out of the
    /// window waits (fk on a phone: the second, below the window, doubled
    /// the page's layout and paint of the math).
    fn collect_math(
        &mut self,
        equations: &[labcore::live_math::Equation],
        quantities: &[labcore::live_math::Quantity],
        readouts: &[labcore::Readout],
    ) {
        self.shown_math.resize(
            equations.len(),
            (String::new(), String::new(), String::new()),
        );
        self.math_step = Some(self.clock.steps());
        for (i, eq) in equations.iter().enumerate() {
            let seen = self.equations_on_screen.get(i).copied().unwrap_or(true);
            if !self.text_settled && !seen {
                self.math_step = None;
                continue;
            }
            let now = labpage::math_panel::live_parts(eq, quantities, readouts);
            if self.shown_math[i] != now {
                self.math_pending.push((i, now));
            }
        }
        self.math_pending.reverse();
        self.name_math_step();
    }

    /// Once every equation shows the numbers of [`SimState::math_step`],
    /// the panel says which step that is (`data-step`, as the readouts
    /// do): while a chain of idle writes goes on, its equations show two
    /// steps, and the panel keeps naming the last step it showed whole.
    fn name_math_step(&mut self) {
        if !self.math_pending.is_empty() {
            return;
        }
        if let (Some(step), Some(section)) =
            (self.math_step.take(), query(&self.panel, ".live-math"))
        {
            name_step(&section, step);
        }
    }

    /// Writes the readouts and the next equation [`SimState::sync_math`]
    /// left, in the browser's idle time after a frame, and has the page laid
    /// out there (a read of the panel's height), so the next frame only
    /// paints the numbers that changed. While equations are left it asks
    /// for the next idle time, after the following frame: each frame then
    /// paints one equation's new numbers, not every equation's at once
    /// (issue 27, cost: with the panel in view on the phone stand-in, the
    /// frame after the write carried the whole panel's paint four times a
    /// second, and the running p95 rose by a median 6 %, up to 12 %). An
    /// equation's result may so follow its readout by a frame or two. At a
    /// pause, an input or the end of a motion, [`SimState::sync_math`]
    /// writes them all at once, in that frame, and lets the height go.
    ///
    /// While the run streams, the panel keeps the tallest height it had
    /// ([`SimState::math_held_px`]): a substituted form that wraps onto one
    /// line fewer would move everything below the panel up, and back down
    /// at the next update. A student reading a plot below saw it jump four
    /// times a second, and the browser painted the whole page again each
    /// time (ekf on a phone: 2.2 ms of paint, unthrottled, against 0.4 ms
    /// for the equations alone).
    fn write_math_when_idle(&mut self) {
        self.math_idle_asked = false;
        if std::mem::take(&mut self.readouts_in_idle) {
            // The readouts and every equation's numbers of one state: the
            // text update's, or a later one where a frame came first. Worked
            // out here, not in the frame (ekf, panel in view on the phone
            // stand-in: the frames' script p95 read 5.1 ms open against
            // 3.7 ms closed, at 4×).
            let readouts = self.exp.readouts();
            self.write_readouts_and_status(&readouts);
            let equations = super::panel_equations(self.exp.as_ref());
            let quantities = self.quantities();
            self.collect_math(&equations, &quantities, &readouts);
        }
        if self.math_held_px == 0 && !self.math_pending.is_empty() {
            // A stream's first write holds the height the panel had before
            // it (read where the last frame left the page laid out): an
            // equation that trades its words for numbers, ekf's innovation
            // at its first reading, is shorter.
            self.hold_math_height();
        }
        let wrote = self.write_next_equation();
        if !self.math_pending.is_empty() {
            // Where it cannot be asked, the frames write the rest, one each.
            self.math_idle_asked = dom::when_idle(&self.panel, super::TEXT_INTERVAL_MS as u32);
        }
        if wrote {
            self.hold_math_height();
        }
    }

    /// Holds "The math" panel at its height now where that is its tallest
    /// while the run streams ([`SimState::math_held_px`]).
    fn hold_math_height(&mut self) {
        let Some(section) = query(&self.panel, ".live-math") else {
            return;
        };
        let Some(section) = section.dyn_ref::<web_sys::HtmlElement>() else {
            return;
        };
        let height_px = section.offset_height();
        if height_px > self.math_held_px {
            self.math_held_px = height_px;
            let _ = section
                .style()
                .set_property("min-height", &format!("{height_px}px"));
        }
    }

    /// Lets "The math" panel take its own height again
    /// ([`SimState::write_math_when_idle`] held it while a run streamed).
    fn release_math_height(&mut self) {
        if self.math_held_px == 0 {
            return;
        }
        self.math_held_px = 0;
        if let Some(section) = query(&self.panel, ".live-math") {
            if let Some(section) = section.dyn_ref::<web_sys::HtmlElement>() {
                let _ = section.style().remove_property("min-height");
            }
        }
    }

    /// Writes the next equation [`SimState::sync_math`] left for a later
    /// frame. Returns whether there was one.
    pub(super) fn write_next_equation(&mut self) -> bool {
        let Some((i, parts)) = self.math_pending.pop() else {
            return false;
        };
        if let Some(block) = query(&self.panel, &format!("[data-equation=\"{i}\"]")) {
            if let Some(numbers) = query(&block, ".equation-numbers") {
                dom::rewrite_markup(&numbers, &parts.0);
            }
            if let Some(result) = query(&block, ".equation-result") {
                dom::rewrite_markup(&result, &parts.1);
            }
            if let Some(text) = query(&block, ".equation-text") {
                dom::rewrite_markup(&text, &parts.2);
            }
        }
        if let Some(shown) = self.shown_math.get_mut(i) {
            *shown = parts;
        }
        self.name_math_step();
        true
    }

    /// Which equations of "The math" panel are in the window now, as the
    /// browser's observers last told ([`dom::watch_box`]); read, before the
    /// frame writes anything, only where there are none.
    pub(super) fn measure_math(&mut self) {
        self.equations_on_screen.resize(self.math_watch.len(), true);
        for (i, watch) in self.math_watch.iter().enumerate() {
            let seen = match watch {
                Some(watch) => watch.seen.get(),
                // No observers (a page without main.js's helper): read it.
                None => query(&self.panel, &format!(".live-math [data-equation=\"{i}\"]"))
                    .map(|block| dom::read_box(&block)),
            };
            if let Some(seen) = seen {
                self.equations_on_screen[i] = seen.on_screen();
            }
        }
    }

    pub(super) fn set_param(&mut self, key: &str, value: f64) {
        let label = self
            .exp
            .params()
            .iter()
            .find(|s| s.key == key)
            .map_or(key, |s| s.label);
        if self.instructor.is_locked(key) {
            // The controls are disabled; this catches anything that still
            // reaches here (a script, an old event).
            self.show_message(Some(&format!("{label} is locked by your instructor.")));
            self.shown_values.iter_mut().for_each(|v| *v = None);
            self.needs_paint = true;
            return;
        }
        self.timeline_input();
        self.timeline_linked(labcore::run_input::RunInput::Param(key.to_owned(), value));
        match self.exp.set_param(key, value) {
            Ok(Sanitized::InRange(_)) => self.show_message(None),
            Ok(Sanitized::Clamped(v)) => self.show_message(Some(&format!(
                "{label} is limited to its range; using {}.",
                format_number(v, 3)
            ))),
            Err(e) => {
                self.show_message(Some(&format!("{label}: {e}. Kept the previous value.")));
                // Force the control back to the kept value.
                self.shown_values.iter_mut().for_each(|v| *v = None);
            }
        }
        self.needs_paint = true;
        self.hash_dirty = true;
    }
}

/// Writes `step` as `el`'s `data-step`, only where it names another step:
/// a repaint of what has not changed writes nothing to the page.
fn name_step(el: &Element, step: u64) {
    let text = step.to_string();
    if el.get_attribute("data-step").as_deref() != Some(text.as_str()) {
        let _ = el.set_attribute("data-step", &text);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grouped_controls_go_under_one_collapsed_heading_after_the_others() {
        const SPECS: [ParamSpec; 4] = [
            ParamSpec::slider("a", "A", "m", 0.0, 1.0, 0.1, 0.5),
            ParamSpec::optional_number("w1x", "Waypoint 1 x", "m", 0.0, 9.0).in_group("Waypoints"),
            ParamSpec::slider("b", "B", "m", 0.0, 1.0, 0.1, 0.5),
            ParamSpec::optional_number("w1y", "Waypoint 1 y", "m", 0.0, 9.0).in_group("Waypoints"),
        ];
        let html = controls_html(&SPECS);
        assert_eq!(html.matches("<details class=\"ctl-group\">").count(), 1);
        assert!(
            !html.contains("<details class=\"ctl-group\" open"),
            "collapsed"
        );
        let details = html.find("<details").unwrap();
        assert!(
            html.find("id=\"p-b\"").unwrap() < details,
            "ungrouped controls first"
        );
        assert!(html.find("id=\"p-w1x\"").unwrap() > details);
        assert!(html.find("id=\"p-w1y\"").unwrap() > details);
        // The count (points set, not fields) comes with the values.
        assert!(
            html.contains("Waypoints <span class=\"ctl-count\" data-group=\"Waypoints\"></span>")
        );
    }
}
