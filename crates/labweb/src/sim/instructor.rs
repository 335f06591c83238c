//! Instructor links on the Simulation tab: the note above the simulation,
//! locked and hidden controls, the Presets menu, and the placeholder of the
//! Instructor panel that builds a link from the current state.
//!
//! What a link holds is parsed and checked in `labcore::route`
//! ([`labcore::route::Instructor`]); this module only shows it. The panel
//! itself is `web/instructor.js`, which a student never needs: `main.js`
//! fetches it the first time the panel is opened and builds the panel from
//! the placeholder ([`panel_html`], [`SimState::show_instructor`],
//! [`SimState::link_written`]). A teaching aid, not security: a student may
//! edit the URL.

use super::SimState;
use crate::dom::{self, escape, query, query_all};
use labcore::route;
use labcore::{Lab, ParamSpec};
use web_sys::Event;

/// A small padlock drawn inline (no image request), hidden from screen
/// readers: the text beside it says "locked".
const LOCK_ICON: &str = "<svg class=\"lock-icon\" viewBox=\"0 0 16 16\" width=\"12\" height=\"12\" aria-hidden=\"true\" focusable=\"false\">\
<path d=\"M4.5 7V5a3.5 3.5 0 0 1 7 0v2\" fill=\"none\" stroke=\"currentColor\" stroke-width=\"1.8\"/>\
<rect x=\"2.5\" y=\"7\" width=\"11\" height=\"8\" rx=\"1.5\" fill=\"currentColor\"/></svg>";

/// The note above the simulation and the way out of the instructor's
/// settings (hidden until a link brings some).
pub(super) fn note_html() -> String {
    "<aside class=\"instructor-note\" aria-labelledby=\"instructor-note-title\" hidden>\
     <h3 id=\"instructor-note-title\">Instructor's note</h3><p class=\"instructor-note-text\"></p>\
     <button type=\"button\" class=\"mini\" data-instructor-leave>Leave the instructor's settings</button></aside>"
        .into()
}

/// The Presets menu: each preset is a link, so it can be shared or opened
/// in a new tab like any state.
pub(super) fn presets_html(exp: &dyn Lab) -> String {
    let presets = exp.presets();
    if presets.is_empty() {
        return String::new();
    }
    let items: String = presets
        .iter()
        .map(|p| {
            format!(
                "<li><a href=\"#/{id}/simulation?{query}\" data-preset=\"{name}\">{name}</a>\
                 <span class=\"preset-desc\">{desc}</span></li>",
                id = exp.id(),
                query = escape(p.query),
                name = escape(p.name),
                desc = escape(p.description),
            )
        })
        .collect();
    format!(
        "<details class=\"presets\"><summary>Presets <span class=\"ctl-count\">({})</span></summary>\
         <ul class=\"preset-list\">{items}</ul></details>",
        presets.len()
    )
}

/// The Instructor panel's placeholder, which `web/instructor.js` fills
/// with a lock and a hide box per parameter, the note, the quiz seed and
/// the link they make: one `<data>` per parameter (its key, unit and label)
/// and, from [`SimState::show_instructor`], the open link's settings.
pub(super) fn panel_html(specs: &[ParamSpec]) -> String {
    let params: String = specs
        .iter()
        .map(|s| {
            format!(
                "<data value=\"{}\" data-unit=\"{}\">{}</data>",
                s.key,
                escape(s.unit),
                escape(s.label)
            )
        })
        .collect();
    format!(
        "<details class=\"instructor-panel\"><summary>Instructor</summary>\
         <div class=\"instructor-body\"><p class=\"instructor-wait\">Loading…</p><div hidden>{params}</div></div></details>"
    )
}

impl SimState {
    /// Shows the instructor's settings: the note, locked and hidden
    /// controls, and gives them to the Instructor panel.
    pub(super) fn show_instructor(&mut self) {
        let panel = &self.panel;
        if let Some(aside) = query(panel, ".instructor-note") {
            if let Some(p) = query(&aside, ".instructor-note-text") {
                // Text, never HTML.
                p.set_text_content(Some(
                    self.instructor
                        .note
                        .as_deref()
                        .unwrap_or("Your instructor set this simulation up."),
                ));
            }
            dom::set_hidden(
                &aside,
                self.instructor.is_empty() && self.quiz_seed.is_none(),
            );
        }
        for spec in self.exp.params() {
            let locked = self.instructor.is_locked(spec.key);
            let Some(wrapper) = query(panel, &format!(".sim [data-ctl=\"{}\"]", spec.key)) else {
                continue;
            };
            dom::set_hidden(&wrapper, self.instructor.is_hidden(spec.key));
            let _ = if locked {
                wrapper.class_list().add_1("locked")
            } else {
                wrapper.class_list().remove_1("locked")
            };
            for el in query_all(&wrapper, &format!("[data-param=\"{}\"]", spec.key)) {
                let _ = if locked {
                    el.set_attribute("disabled", "")
                } else {
                    el.remove_attribute("disabled")
                };
                // The number box names itself: say it is locked there too.
                if let Some(name) = el.get_attribute("aria-label") {
                    let base = el.get_attribute("data-aria").unwrap_or_else(|| {
                        let _ = el.set_attribute("data-aria", &name);
                        name.clone()
                    });
                    let _ = el.set_attribute(
                        "aria-label",
                        &if locked {
                            format!("{base} (locked)")
                        } else {
                            base
                        },
                    );
                }
            }
            let badge = query(&wrapper, ".ctl-lock");
            match (locked, badge) {
                (true, None) => {
                    if let Some(label) = query(&wrapper, "label, legend") {
                        let _ = label.insert_adjacent_html(
                            "beforeend",
                            &format!(" <span class=\"ctl-lock\">{LOCK_ICON} locked</span>"),
                        );
                    }
                }
                (false, Some(b)) => b.remove(),
                _ => {}
            }
        }
        // A group whose every control is hidden goes too.
        for group in query_all(panel, ".sim-controls details.ctl-group") {
            let all_hidden = query_all(&group, "[data-ctl]")
                .iter()
                .all(|c| c.has_attribute("hidden"));
            dom::set_hidden(&group, all_hidden);
        }
        // Presets would open other states without the locks: not offered
        // while an instructor's link fixes controls.
        if let Some(presets) = query(panel, "details.presets") {
            dom::set_hidden(
                &presets,
                !(self.instructor.locked.is_empty() && self.instructor.hidden.is_empty()),
            );
        }
        // The Instructor panel starts from the link that is open.
        if let Some(details) = query(panel, ".instructor-panel") {
            let _ = details.set_attribute("data-instructor", &self.instructor_query().join("&"));
        }
    }

    /// The experiment's live quantities, those the instructor hid marked
    /// so ("The math" says "hidden").
    pub(super) fn quantities(&self) -> Vec<labcore::live_math::Quantity> {
        let mut out = self.exp.quantities();
        for q in &mut out {
            q.hidden = self.instructor.is_hidden(q.key);
        }
        out
    }

    /// The link's instructor pairs: the locks, hidden controls and note
    /// ([`route::Instructor::query`]), then the quiz seed.
    pub(super) fn instructor_query(&self) -> Vec<String> {
        let mut pairs = self.instructor.query();
        pairs.extend(self.quiz_seed.map(|s| format!("{}={s}", route::QUIZ_KEY)));
        pairs
    }

    /// Tells an open Instructor panel that the page's link was written
    /// (`lab-link`): it rebuilds its own link from it.
    pub(super) fn link_written(&self) {
        if let (Some(details), Ok(event)) = (
            query(&self.panel, ".instructor-panel[open]"),
            Event::new("lab-link"),
        ) {
            let _ = details.dispatch_event(&event);
        }
    }

    /// A pointer or keyboard input on the canvas, through the locks.
    pub(super) fn guarded_input(&mut self, input: labcore::Input, modifiers: labcore::Modifiers) {
        if let labcore::Input::PointerMove { pressed: false, .. } = input {
            // A hover changes nothing the run records (no new run from the past).
            let _ = route::keep_locked(self.exp.as_mut(), &self.instructor, |exp| {
                exp.input_with(input, modifiers);
            });
            return;
        }
        self.guarded(|exp| exp.input_with(input, modifiers));
        self.timeline_linked(labcore::run_input::RunInput::Pointer(input, modifiers));
    }

    /// Runs a student's input through the locks (see
    /// [`route::keep_locked`]) and says which locked control it would have
    /// changed. Returns whether a lock put something back.
    pub(super) fn guarded(&mut self, op: impl FnOnce(&mut dyn Lab)) -> bool {
        self.timeline_input();
        let put_back = route::keep_locked(self.exp.as_mut(), &self.instructor, op);
        if let Some(label) = put_back.first() {
            self.show_message(Some(&format!("{label} is locked by your instructor.")));
            self.shown_values.iter_mut().for_each(|v| *v = None);
        }
        !put_back.is_empty()
    }
}
