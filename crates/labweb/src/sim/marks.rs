//! Marks (issue 26 §3): "Mark this moment" (the button in the time bar and
//! `M`) keeps the step shown, live or scrubbed; each mark is a point on
//! every plot, a removable entry in the time bar, a section of the lab
//! report, and `marks=` in the link ([`labcore::marks`] says how marks
//! follow the run: a reset clears them, an input drops those after its
//! step).
//!
//! The state at a mark is the timeline's (bit for bit the run's at that
//! step): its plots give the mark's points, once, and the report's section
//! is drawn from it.

use super::SimState;
use crate::dom::{self, escape, query};
use labcore::marks::{self, Marks, MARKS_KEY};
use labcore::Lab;
use web_sys::Element;

/// The button, in the time bar after Run to end; the marks' list follows
/// the time (empty and hidden without marks).
pub(super) const BUTTON_HTML: &str = "<button type=\"button\" data-time=\"mark\" aria-pressed=\"false\" aria-keyshortcuts=\"M\" title=\"Mark this moment for the plots and the lab report (key M)\">\
     <svg viewBox=\"0 0 16 16\" width=\"14\" height=\"14\" aria-hidden=\"true\"><path fill=\"currentColor\" d=\"M3 1h10v14l-5-4-5 4z\"/></svg> <span class=\"tb-text\">Mark</span></button>";

/// The list of marks (each with its remove button), after the time.
pub(super) const LIST_HTML: &str =
    "<span class=\"tb-marks\" role=\"group\" aria-label=\"Marked moments\" hidden></span>";

/// The marks of the run and what the page shows of them.
#[derive(Default)]
pub(super) struct MarkState {
    pub(super) marks: Marks,
    /// The points of each mark whose state was reached, by step.
    points: Vec<(u64, marks::PlotPoints)>,
    /// The marks changed since the list and the plots were brought up to date.
    dirty: bool,
    /// What the button says: whether the step shown is marked.
    shown_pressed: Option<bool>,
}

impl SimState {
    /// Mark this moment (the button and `M`): marks the step shown, or
    /// unmarks it when it is marked.
    pub(super) fn toggle_mark(&mut self) {
        if self.timeline.is_none() {
            return;
        }
        self.timeline_commit();
        let step = self.clock.steps();
        let t = marks::time_text(step);
        if self.marks.marks.remove(step) {
            self.say(&format!("Mark at t = {t} s removed."));
        } else if self.marks.marks.add(step) {
            // The state shown is the state at this step: its plots now.
            self.marks
                .points
                .push((step, marks::plot_points(self.exp.plots())));
            self.say(&format!("Marked t = {t} s."));
        } else {
            self.show_message(Some(&format!(
                "A run keeps at most {} marks; remove one first.",
                marks::MAX_MARKS
            )));
            return;
        }
        self.marks_changed();
    }

    /// The remove button of the mark at `step`.
    pub(super) fn remove_mark(&mut self, step: u64) {
        if self.marks.marks.remove(step) {
            self.say(&format!(
                "Mark at t = {} s removed.",
                marks::time_text(step)
            ));
            self.marks_changed();
        }
    }

    /// The run starts again (a reset, a link, a file): no marks.
    pub(super) fn clear_marks(&mut self) {
        if !self.marks.marks.is_empty() {
            self.marks.marks.clear();
            self.marks_changed();
        }
    }

    /// An input at step `step` starts a new run from there: the marks
    /// after it go with the old run; one at `step` shows the state the input
    /// leaves (its points are taken again).
    pub(super) fn marks_new_run_from(&mut self, step: u64) {
        let at_step = self.marks.marks.steps().contains(&step);
        if self.marks.marks.drop_after(step) || at_step {
            self.marks.points.retain(|(s, _)| *s != step);
            self.marks_changed();
        }
    }

    /// Sets the marks a link names (`marks=`).
    pub(super) fn set_marks(&mut self, marks: Marks) {
        self.marks.marks = marks;
        self.marks_changed();
    }

    fn marks_changed(&mut self) {
        let kept = self.marks.marks.steps();
        self.marks.points.retain(|(s, _)| kept.contains(s));
        self.marks.dirty = true;
        self.hash_dirty = true;
        self.plots_force = true;
    }

    /// The link's `marks=`, when the link reproduces the marked states:
    /// the run had no input after its start.
    pub(super) fn marks_link(&self) -> Option<String> {
        let tl = self.timeline.as_ref()?;
        let last = *self.marks.marks.steps().last()?;
        tl.unbroken_to(tl.end().max(last))
            .then(|| format!("{MARKS_KEY}={}", self.marks.marks.link_value()))
    }

    /// Whether the timeline holds the state at `step`.
    fn recorded(&self, step: u64) -> bool {
        self.timeline
            .as_ref()
            .is_some_and(|tl| (tl.first()..=tl.end()).contains(&step))
    }

    /// The state at `step` from the timeline (`None` when not recorded).
    fn state_at(&mut self, step: u64) -> Option<Box<dyn Lab>> {
        if !self.recorded(step) {
            return None;
        }
        let tl = self.timeline.as_mut()?;
        tl.commit(self.exp.as_ref());
        let (_, lab) = tl.state_at(step, &mut |exp: &mut dyn Lab| {
            exp.step(labcore::clock::Clock::DT_S);
        });
        Some(lab)
    }

    /// Each mark the run has reached, with the state at it (for the lab
    /// report): (time in seconds, state).
    pub(super) fn marked_states(&mut self) -> Vec<(f64, Box<dyn Lab>)> {
        let steps = self.marks.marks.steps().to_vec();
        steps
            .into_iter()
            .filter_map(|s| {
                let lab = self.state_at(s)?;
                Some((s as f64 * labcore::clock::Clock::DT_S, lab))
            })
            .collect()
    }

    /// Brings the marks' list, the button and the plots' points up to date
    /// (a mark a link named gets its points once the run reaches it).
    pub(super) fn sync_marks(&mut self) {
        let missing: Vec<u64> = self
            .marks
            .marks
            .steps()
            .iter()
            .copied()
            .filter(|s| !self.marks.points.iter().any(|(p, _)| p == s) && self.recorded(*s))
            .collect();
        for step in missing {
            if let Some(lab) = self.state_at(step) {
                self.marks
                    .points
                    .push((step, marks::plot_points(lab.plots())));
                self.marks.dirty = true;
                self.plots_force = true;
            }
        }
        let pressed = self.marks.marks.steps().contains(&self.clock.steps());
        if self.marks.shown_pressed != Some(pressed) {
            if let Some(button) = query(&self.panel, "[data-time=mark]") {
                let _ =
                    button.set_attribute("aria-pressed", if pressed { "true" } else { "false" });
            }
            self.marks.shown_pressed = Some(pressed);
        }
        if !self.marks.dirty {
            return;
        }
        self.marks.dirty = false;
        if let Some(list) = query(&self.panel, ".tb-marks") {
            write_list(&list, &self.marks.marks);
        }
        self.plots.set_marks(&self.marks.points);
    }
}

/// The marks' list: per mark its time (a button that shows that moment)
/// and a remove button.
fn write_list(list: &Element, marks: &Marks) {
    let html: String = marks
        .steps()
        .iter()
        .map(|&s| {
            let t = escape(&marks::time_text(s));
            format!(
                "<span class=\"tb-mark\" data-mark=\"{s}\"><button type=\"button\" data-goto=\"{s}\" title=\"Show this moment\">▼ {t} s</button><button type=\"button\" class=\"tb-unmark\" \
                 data-unmark=\"{s}\" aria-label=\"Remove the mark at t = {t} s\" title=\"Remove this mark\">×</button></span>"
            )
        })
        .collect();
    list.set_inner_html(&html);
    dom::set_hidden(list, marks.is_empty());
}
