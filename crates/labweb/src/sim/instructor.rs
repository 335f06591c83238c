//! Instructor links on the Simulation tab: the note above the simulation,
//! locked and hidden controls, the Presets menu and the Instructor panel
//! that builds a link from the current state.
//!
//! What a link holds is parsed and checked in `labcore::route`
//! ([`labcore::route::Instructor`]); this module only shows it and wires
//! the panel. A teaching aid, not security: a student may edit the URL.

use super::SimState;
use crate::dom::{self, escape, query, query_all, Listener};
use labcore::route::{self, Instructor, NOTE_MAX_CHARS};
use labcore::{Lab, ParamSpec};
use std::cell::RefCell;
use std::rc::Rc;
use wasm_bindgen::{JsCast, JsValue};
use web_sys::{Element, Event, HtmlInputElement, HtmlSelectElement};

/// A small padlock drawn inline (no image request), hidden from screen
/// readers: the text beside it says "locked".
const LOCK_ICON: &str = "<svg class=\"lock-icon\" viewBox=\"0 0 16 16\" width=\"12\" height=\"12\" aria-hidden=\"true\" focusable=\"false\">\
<path d=\"M4.5 7V5a3.5 3.5 0 0 1 7 0v2\" fill=\"none\" stroke=\"currentColor\" stroke-width=\"1.8\"/>\
<rect x=\"2.5\" y=\"7\" width=\"11\" height=\"8\" rx=\"1.5\" fill=\"currentColor\"/></svg>";

/// The note above the simulation (hidden until a link brings one).
pub(super) fn note_html() -> String {
    "<aside class=\"instructor-note\" aria-labelledby=\"instructor-note-title\" hidden>\
     <h3 id=\"instructor-note-title\">Instructor's note</h3><p class=\"instructor-note-text\"></p></aside>"
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

/// The Instructor panel: a lock and a hide box per parameter, the note,
/// the quiz seed, and the link they make with a Copy button.
pub(super) fn panel_html(specs: &[ParamSpec]) -> String {
    let rows: String = specs
        .iter()
        .map(|s| {
            let label = escape(s.label);
            let unit = if s.unit.is_empty() {
                String::new()
            } else {
                format!(" <span class=\"unit\">({})</span>", escape(s.unit))
            };
            format!(
                "<tr><th scope=\"row\">{label}{unit}</th>\
                 <td><input type=\"checkbox\" data-lock=\"{key}\" aria-label=\"Lock {label}\"></td>\
                 <td><input type=\"checkbox\" data-hide=\"{key}\" aria-label=\"Hide {label}\"></td></tr>",
                key = s.key,
            )
        })
        .collect();
    format!(
        "<details class=\"instructor-panel\"><summary>Instructor</summary>\
         <div class=\"instructor-body\">\
         <p>Set up the simulation, then choose what your students may change. The link below opens \
         this state with the locked controls shown but fixed, the hidden ones left out and your note \
         above the simulation. It is a teaching aid, not a lock: a student can edit the link.</p>\
         <div class=\"table-scroll\"><table class=\"instructor-params\"><caption>Parameters</caption>\
         <thead><tr><th scope=\"col\">Parameter</th><th scope=\"col\">Lock</th><th scope=\"col\">Hide</th></tr></thead>\
         <tbody>{rows}</tbody></table></div>\
         <label class=\"instructor-field\">Note for the students (plain text, up to {NOTE_MAX_CHARS} characters)\
         <input type=\"text\" class=\"instructor-note-input\" maxlength=\"{NOTE_MAX_CHARS}\" autocomplete=\"off\"></label>\
         <label class=\"instructor-field\">Quiz seed (the same questions for the whole class; empty: each student draws their own)\
         <input type=\"text\" class=\"instructor-quiz\" inputmode=\"numeric\" autocomplete=\"off\" spellcheck=\"false\"></label>\
         <label class=\"instructor-field\">Expected answers in a student's lab report (by default never with a quiz seed, else after submission)\
         <select class=\"instructor-key\"><option value=\"\">Default</option>\
         <option value=\"never\">Never</option><option value=\"submitted\">After submission</option>\
         <option value=\"always\">Always</option></select></label>\
         <label class=\"instructor-field\">Link\
         <input type=\"text\" class=\"instructor-link\" readonly></label>\
         <p class=\"instructor-actions\"><button type=\"button\" class=\"mini\" data-instructor=\"copy\">Copy link</button> \
         <span class=\"instructor-copied\" role=\"status\"></span></p>\
         </div></details>"
    )
}

/// Wires the Instructor panel: any change rebuilds the link; Copy copies it.
pub(super) fn listen(
    state: &Rc<RefCell<SimState>>,
    panel: &Element,
    listeners: &mut Vec<Listener>,
) {
    let Some(details) = query(panel, ".instructor-panel") else {
        return;
    };
    for kind in ["input", "change", "toggle"] {
        let s = state.clone();
        listeners.push(Listener::new(details.as_ref(), kind, move |_| {
            if let Ok(st) = s.try_borrow() {
                st.sync_instructor_link();
            }
        }));
    }
    let s = state.clone();
    listeners.push(Listener::new(details.as_ref(), "click", move |e: Event| {
        let is_copy = e
            .target()
            .and_then(|t| t.dyn_into::<Element>().ok())
            .and_then(|el| el.closest("[data-instructor=copy]").ok().flatten())
            .is_some();
        if !is_copy {
            return;
        }
        let st = s.borrow();
        st.sync_instructor_link();
        let Some(field) = query(&st.panel, ".instructor-link")
            .and_then(|f| f.dyn_into::<HtmlInputElement>().ok())
        else {
            return;
        };
        // Selected, so Ctrl+C works where the clipboard is not offered.
        field.select();
        let said = if copy_text(&field.value()) {
            "Copied."
        } else {
            "Selected: press Ctrl+C (⌘C) to copy."
        };
        if let Some(out) = query(&st.panel, ".instructor-copied") {
            out.set_text_content(Some(said));
        }
    }));
}

/// `navigator.clipboard.writeText(text)` where the browser offers it
/// (secure contexts); `false` otherwise.
fn copy_text(text: &str) -> bool {
    let Ok(navigator) = js_sys::Reflect::get(&dom::window(), &JsValue::from_str("navigator"))
    else {
        return false;
    };
    let Ok(clipboard) = js_sys::Reflect::get(&navigator, &JsValue::from_str("clipboard")) else {
        return false;
    };
    if clipboard.is_undefined() || clipboard.is_null() {
        return false;
    }
    let Ok(write) = js_sys::Reflect::get(&clipboard, &JsValue::from_str("writeText")) else {
        return false;
    };
    let Some(write) = write.dyn_ref::<js_sys::Function>() else {
        return false;
    };
    match write.call1(&clipboard, &JsValue::from_str(text)) {
        Ok(promise) => {
            // A refusal (no permission) must not reach the console as an
            // unhandled rejection: the field is selected anyway.
            let ignore = wasm_bindgen::closure::Closure::once_into_js(|_: JsValue| {});
            if let Some(catch) = js_sys::Reflect::get(&promise, &JsValue::from_str("catch"))
                .ok()
                .and_then(|c| c.dyn_into::<js_sys::Function>().ok())
            {
                let _ = catch.call1(&promise, &ignore);
            }
            true
        }
        Err(_) => false,
    }
}

/// What the Instructor panel's form says: its locks, hides, note and seed.
fn read_panel(panel: &Element) -> (Instructor, Option<u64>) {
    let checked = |attr: &str| -> Vec<String> {
        query_all(panel, &format!(".instructor-panel input[{attr}]"))
            .into_iter()
            .filter_map(|el| {
                let input = el.dyn_into::<HtmlInputElement>().ok()?;
                if input.checked() {
                    input.get_attribute(attr)
                } else {
                    None
                }
            })
            .collect()
    };
    let note = query(panel, ".instructor-note-input")
        .and_then(|n| n.dyn_into::<HtmlInputElement>().ok())
        .map(|n| n.value())
        .unwrap_or_default();
    let quiz = query(panel, ".instructor-quiz")
        .and_then(|n| n.dyn_into::<HtmlInputElement>().ok())
        .and_then(|n| n.value().trim().parse::<u64>().ok());
    let answer_key = query(panel, ".instructor-key")
        .and_then(|n| n.dyn_into::<HtmlSelectElement>().ok())
        .and_then(|n| route::AnswerKey::from_slug(&n.value()));
    (
        Instructor {
            locked: checked("data-lock"),
            hidden: checked("data-hide"),
            note: route::clean_note(&note).0,
            answer_key,
            ..Instructor::default()
        },
        quiz,
    )
}

impl SimState {
    /// Shows the instructor's settings: the note, locked and hidden
    /// controls, and fills the Instructor panel with them.
    pub(super) fn show_instructor(&mut self) {
        let panel = &self.panel;
        if let Some(aside) = query(panel, ".instructor-note") {
            if let Some(p) = query(&aside, ".instructor-note-text") {
                // Text, never HTML.
                p.set_text_content(self.instructor.note.as_deref());
            }
            dom::set_hidden(&aside, self.instructor.note.is_none());
        }
        for spec in self.exp.params() {
            let locked = self.instructor.is_locked(spec.key);
            let Some(wrapper) = query(panel, &format!(".sim-controls [data-ctl=\"{}\"]", spec.key))
            else {
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
        // The panel starts from the link that is open.
        for el in query_all(panel, ".instructor-panel input[type=checkbox]") {
            let Ok(input) = el.dyn_into::<HtmlInputElement>() else {
                continue;
            };
            if let Some(key) = input.get_attribute("data-lock") {
                input.set_checked(self.instructor.is_locked(&key));
            } else if let Some(key) = input.get_attribute("data-hide") {
                input.set_checked(self.instructor.is_hidden(&key));
            }
        }
        if let Some(n) = query(panel, ".instructor-note-input")
            .and_then(|n| n.dyn_into::<HtmlInputElement>().ok())
        {
            n.set_value(self.instructor.note.as_deref().unwrap_or(""));
        }
        if let Some(q) =
            query(panel, ".instructor-quiz").and_then(|n| n.dyn_into::<HtmlInputElement>().ok())
        {
            q.set_value(&self.quiz_seed.map(|s| s.to_string()).unwrap_or_default());
        }
        if let Some(k) =
            query(panel, ".instructor-key").and_then(|n| n.dyn_into::<HtmlSelectElement>().ok())
        {
            k.set_value(
                self.instructor
                    .answer_key
                    .map_or("", route::AnswerKey::slug),
            );
        }
        self.sync_instructor_link();
    }

    /// The Instructor panel's link: the current state with the panel's
    /// locks, hides, note and quiz seed, as a full address.
    pub(super) fn sync_instructor_link(&self) {
        let Some(details) = query(&self.panel, ".instructor-panel") else {
            return;
        };
        if !details.has_attribute("open") {
            return;
        }
        let (mut instructor, quiz) = read_panel(&self.panel);
        // The panel has no field for the quiz's rules: the link's stay.
        instructor.quiz = self.instructor.quiz;
        let mut pairs = instructor.query();
        pairs.extend(quiz.map(|s| format!("{}={s}", route::QUIZ_KEY)));
        let hash = route::with_query(self.state_link(), &pairs);
        let location = dom::window().location();
        let base = location.href().unwrap_or_default();
        let base = base.split('#').next().unwrap_or("");
        if let Some(field) = query(&self.panel, ".instructor-link")
            .and_then(|f| f.dyn_into::<HtmlInputElement>().ok())
        {
            let link = format!("{base}{hash}");
            if field.value() != link {
                field.set_value(&link);
            }
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
