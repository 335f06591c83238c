//! Beyond the automated rules (issue 17 §6): every drag has a non-drag
//! alternative, and the scene can be put into words.
//!
//! - With the canvas focused, `]` and `[` choose the next or previous handle
//!   ([`labcore::Experiment::handles`]); it is drawn with a focus ring
//!   ([`labcore::Item::FocusRing`]) and the arrow keys move it
//!   ([`labcore::Experiment::move_handle`], the drag's own path). Escape lets
//!   go. With no handle chosen, the arrows keep their old meaning (a nudge of
//!   the experiment's current point).
//! - The "Move a point" form beside the canvas takes typed coordinates for
//!   the same handles.
//! - `D` on the canvas and the Describe button put
//!   [`labcore::Experiment::describe`] into the polite live region and show
//!   it on the page under the button, for sighted students too; the end of
//!   a run (the status phase turning [`labcore::Phase::Ended`]) announces it.

use super::SimState;
use crate::dom::{self, escape, query, Listener};
use glam::DVec2;
use labcore::units::format_number;
use labcore::{Handle, Item};
use std::cell::RefCell;
use std::rc::Rc;
use wasm_bindgen::JsCast;
use web_sys::{Element, Event, HtmlInputElement, HtmlSelectElement, KeyboardEvent};

/// Radius of the focus ring around the chosen handle, CSS pixels.
const RING_PX: f64 = 13.0;
/// The arrow keys' step: this fraction of the view's width (Shift: a tenth of it).
const STEP_FRACTION: f64 = 0.02;

/// The Describe button (beside the other actions under the canvas).
pub(super) fn describe_button_html() -> &'static str {
    "<button type=\"button\" class=\"mini\" data-a11y=\"describe\" aria-keyshortcuts=\"D\">Describe</button>"
}

/// Where Describe shows its text on the page (under the tools), besides
/// announcing it: a sighted student who presses it sees what it said. Not a
/// live region itself (the polite one announces the text once).
pub(super) const DESCRIPTION_HTML: &str = "<p class=\"sim-description\" hidden></p>";

/// The "Move a point" form: which handle, and its x and y typed. Hidden while
/// there is nothing to move.
pub(super) fn move_form_html() -> String {
    let coord = |axis: &str| {
        format!(
            "<div class=\"ctl ctl-number\"><label for=\"move-{axis}\">{axis}</label>\
             <span class=\"ctl-num\"><input type=\"text\" inputmode=\"decimal\" autocomplete=\"off\" spellcheck=\"false\" \
             id=\"move-{axis}\" data-move=\"{axis}\"><span class=\"unit\" data-move-unit>m</span></span></div>"
        )
    };
    format!(
        "<form class=\"sim-move\" aria-labelledby=\"move-title\" hidden>\
           <h3 class=\"sim-move-title\" id=\"move-title\">Move a point</h3>\
           <p class=\"sim-move-help\"><span data-for=\"keys\">Or, on the canvas: <kbd>[</kbd> <kbd>]</kbd> choose, arrow keys move.</span>\
           <span data-for=\"touch\">Or drag the point on the canvas.</span></p>\
           <div class=\"ctl ctl-choice\"><label for=\"move-handle\">Point</label>\
           <select id=\"move-handle\" data-move=\"handle\"></select></div>\
           {x}{y}\
           <div class=\"sim-move-go\"><button type=\"submit\" class=\"mini\">Move</button></div>\
         </form>",
        x = coord("x"),
        y = coord("y"),
    )
}

/// What the Move form shows, so the DOM is touched only on change.
#[derive(Clone, Debug, Default, PartialEq)]
pub(super) struct ShownMove {
    /// `(id, label)` of the options listed.
    options: Vec<(String, String)>,
    /// The option selected and the position its boxes show.
    selected: Option<(String, DVec2)>,
}

/// The handle after `current` in `handles` (`forward`) or before it,
/// wrapping; the first (or last) when none is chosen or it has gone.
#[must_use]
pub(super) fn cycle(handles: &[Handle], current: Option<&str>, forward: bool) -> Option<String> {
    let n = handles.len();
    if n == 0 {
        return None;
    }
    let i = current.and_then(|id| handles.iter().position(|h| h.id == id));
    let next = match (i, forward) {
        (None, true) => 0,
        (None, false) => n - 1,
        (Some(i), true) => (i + 1) % n,
        (Some(i), false) => (i + n - 1) % n,
    };
    Some(handles[next].id.clone())
}

impl SimState {
    fn focused(&self) -> Option<Handle> {
        let id = self.focused_handle.as_deref()?;
        self.exp.handles().into_iter().find(|h| h.id == id)
    }

    /// Puts `text` into the polite live region (a repeat is still announced).
    pub(super) fn say(&self, text: &str) {
        if let Some(live) = query(&self.panel, ".sim-live") {
            let same = live.text_content().as_deref() == Some(text);
            let text = if same {
                format!("{text}\u{a0}")
            } else {
                text.to_owned()
            };
            live.set_text_content(Some(&text));
        }
    }

    /// Announces the experiment's description of the scene.
    pub(super) fn describe_scene(&self) {
        self.say(&self.exp.describe());
    }

    /// Describe (the button or `D`): announces the description and shows it
    /// on the page, scrolled into view if it is not.
    pub(super) fn describe_on_request(&self) {
        let text = self.exp.describe();
        self.say(&text);
        if let Some(shown) = query(&self.panel, ".sim-description") {
            shown.set_text_content(Some(&text));
            dom::set_hidden(&shown, false);
            let options = web_sys::ScrollIntoViewOptions::new();
            options.set_block(web_sys::ScrollLogicalPosition::Nearest);
            shown.scroll_into_view_with_scroll_into_view_options(&options);
        }
    }

    fn say_handle(&self, h: &Handle, lead: &str) {
        if h.x_only {
            self.say(&format!(
                "{lead}{} at x = {} m.",
                h.label,
                labcore::units::format_fixed(h.at.x, 2)
            ));
        } else {
            self.say(&format!(
                "{lead}{} at {}.",
                h.label,
                h.typed_text(h.typed().1)
            ));
        }
    }

    /// The focus ring of the chosen handle, after the experiment's scene; a
    /// handle that has gone (a waypoint removed) is let go.
    pub(super) fn push_focus_ring(&mut self) {
        match self.focused() {
            Some(h) => self.scene.push(Item::FocusRing {
                center: h.at,
                radius_px: RING_PX,
            }),
            None => self.focused_handle = None,
        }
    }

    /// Keys of the canvas for handles and descriptions; `true` when the key
    /// was taken (the caller then prevents its default).
    pub(super) fn a11y_key(&mut self, e: &KeyboardEvent) -> bool {
        if e.ctrl_key() || e.meta_key() || e.alt_key() {
            return false;
        }
        let key = e.key();
        match key.as_str() {
            "[" | "]" => {
                self.student_acted();
                let handles = self.exp.handles();
                self.focused_handle = cycle(&handles, self.focused_handle.as_deref(), key == "]");
                match self.focused() {
                    Some(h) => self.say_handle(&h, "Chosen: "),
                    None => self.say("Nothing to move here yet."),
                }
                self.needs_paint = true;
                true
            }
            "Escape" if self.focused_handle.is_some() => {
                self.focused_handle = None;
                self.needs_paint = true;
                self.say("No point chosen.");
                true
            }
            "d" | "D" => {
                self.describe_on_request();
                true
            }
            "ArrowLeft" | "ArrowRight" | "ArrowUp" | "ArrowDown" => {
                let Some(h) = self.focused() else {
                    return false;
                };
                if h.x_only && matches!(key.as_str(), "ArrowUp" | "ArrowDown") {
                    return true;
                }
                let dir = match key.as_str() {
                    "ArrowLeft" => DVec2::NEG_X,
                    "ArrowRight" => DVec2::X,
                    "ArrowUp" => DVec2::Y,
                    _ => DVec2::NEG_Y,
                };
                let step = h.step_m.unwrap_or_else(|| {
                    let view = self.exp.view();
                    let fine = if e.shift_key() { 0.1 } else { 1.0 };
                    (view.max.x - view.min.x) * STEP_FRACTION * fine
                });
                self.student_acted();
                self.move_to(&h.id, h.at + dir * step, true);
                true
            }
            _ => false,
        }
    }

    /// Moves handle `id` to `to` (keyboard or typed), through the
    /// instructor's locks like a pointer drag, and says where it went. A key
    /// move is `paced` like a drag (keys repeat); a typed one is not.
    /// Returns whether a lock held the point (the message says so).
    fn move_to(&mut self, id: &str, to: DVec2, paced: bool) -> bool {
        let locked = self.guarded(|exp| {
            exp.move_handle(id, to);
        });
        self.timeline_linked(labcore::run_input::RunInput::Handle(id.to_owned(), to));
        self.needs_paint = true;
        self.text_paced = paced;
        self.hash_dirty = true;
        self.shown_values.iter_mut().for_each(|v| *v = None);
        match self.exp.handles().into_iter().find(|h| h.id == id) {
            Some(h) => self.say_handle(&h, ""),
            None => {
                self.focused_handle = None;
                self.say("That point is gone.");
            }
        }
        locked
    }

    /// Brings the Move form up to date: the handles listed, the chosen one
    /// selected, its coordinates in the boxes (unless one is being typed in).
    pub(super) fn sync_move_form(&mut self) {
        let Some(form) = query(&self.panel, ".sim-move") else {
            return;
        };
        let handles = self.exp.handles();
        let options: Vec<(String, String)> = handles
            .iter()
            .map(|h| (h.id.clone(), h.label.clone()))
            .collect();
        let select = query(&form, "select[data-move=handle]")
            .and_then(|s| s.dyn_into::<HtmlSelectElement>().ok());
        if options != self.shown_move.options {
            dom::set_hidden(&form, options.is_empty());
            if let Some(select) = &select {
                let html: String = options
                    .iter()
                    .map(|(id, label)| {
                        format!(
                            "<option value=\"{}\">{}</option>",
                            escape(id),
                            escape(label)
                        )
                    })
                    .collect();
                select.set_inner_html(&html);
            }
            self.shown_move.options = options;
            self.shown_move.selected = None;
        }
        let chosen = self
            .focused()
            .or_else(|| {
                let picked = select.as_ref().map(HtmlSelectElement::value);
                handles
                    .iter()
                    .find(|h| Some(&h.id) == picked.as_ref())
                    .cloned()
            })
            .or_else(|| handles.first().cloned());
        let Some(h) = chosen else {
            return;
        };
        if self.shown_move.selected.as_ref() == Some(&(h.id.clone(), h.at)) {
            return;
        }
        if let Some(select) = &select {
            select.set_value(&h.id);
        }
        // A handle on a track has no y to type.
        if let Some(y_box) = query(&form, "input[data-move=y]")
            .and_then(|i| i.closest(".ctl").ok())
            .flatten()
        {
            dom::set_hidden(&y_box, h.x_only);
        }
        let active = dom::document().active_element();
        // Metres, or a grid cell's column and row (the controls' numbers).
        let (names, typed) = h.typed();
        let unit = if h.grid_rows.is_some() { "" } else { "m" };
        let labels = dom::query_all(&form, ".ctl-number label");
        let units = dom::query_all(&form, "[data-move-unit]");
        let inputs = dom::query_all(&form, "input[data-move]");
        for (i, v) in [typed.x, typed.y].into_iter().enumerate() {
            if let Some(label) = labels.get(i) {
                dom::set_text(label, names[i]);
            }
            if let Some(u) = units.get(i) {
                dom::set_text(u, unit);
            }
            if let Some(input) = inputs.get(i) {
                if active.as_ref() != Some(input) {
                    if let Some(input) = input.dyn_ref::<HtmlInputElement>() {
                        input.set_value(&format_number(v, 2));
                    }
                }
            }
        }
        self.shown_move.selected = Some((h.id, h.at));
    }

    /// The Move form's submit: reads x and y, moves the chosen handle.
    fn move_from_form(&mut self, form: &Element) {
        let value = |sel: &str| {
            query(form, sel)
                .and_then(|e| e.dyn_into::<HtmlInputElement>().ok())
                .map(|i| i.value())
                .unwrap_or_default()
        };
        let Some(id) = query(form, "select[data-move=handle]")
            .and_then(|s| s.dyn_into::<HtmlSelectElement>().ok())
            .map(|s| s.value())
            .filter(|v| !v.is_empty())
        else {
            return;
        };
        self.focused_handle = Some(id.clone());
        let Some(handle) = self.focused() else {
            return;
        };
        let (names, _) = handle.typed();
        let unit = if handle.grid_rows.is_some() { "" } else { "m" };
        let read = |axis: &str, name: &str| {
            let raw = value(&format!("input[data-move={axis}]"));
            if raw.trim().is_empty() {
                return Err(format!("{name}: nothing was typed"));
            }
            labcore::units::read_answer(&raw, unit)
                .map(|r| r.value)
                .map_err(|e| format!("{name}: {e}"))
        };
        self.student_acted();
        // A handle on a track keeps its height: only x is read.
        let y = if handle.x_only {
            Ok(handle.typed().1.y)
        } else {
            read("y", names[1])
        };
        match (read("x", names[0]), y) {
            (Ok(x), Ok(y)) => {
                let typed = DVec2::new(x, y);
                let to = handle.from_typed(typed);
                self.focused_handle = Some(id.clone());
                let locked = self.move_to(&id, to, false);
                match self.focused() {
                    // The lock's own message stays: it says why.
                    Some(_) if locked => {}
                    Some(h) if (h.at - to).length() > 0.006 => self.show_message(Some(&format!(
                        "{} could not go to {}; it is at {}.",
                        h.label,
                        h.typed_text(typed),
                        h.typed_text(h.typed().1)
                    ))),
                    _ => self.show_message(None),
                }
            }
            (Err(e), _) | (_, Err(e)) => {
                self.show_message(Some(&format!(
                    "Could not read that ({e}). The point stays where it was."
                )));
            }
        }
        self.shown_move.selected = None;
    }
}

/// Wires the Move form and the Describe button.
pub(super) fn listen(
    state: &Rc<RefCell<SimState>>,
    panel: &Element,
    listeners: &mut Vec<Listener>,
) {
    if let Some(form) = query(panel, ".sim-move") {
        let s = state.clone();
        let f = form.clone();
        listeners.push(Listener::new(form.as_ref(), "submit", move |e: Event| {
            e.prevent_default();
            s.borrow_mut().move_from_form(&f);
        }));
        let s = state.clone();
        listeners.push(Listener::new(form.as_ref(), "change", move |e: Event| {
            let Some(select) = e
                .target()
                .and_then(|t| t.dyn_into::<HtmlSelectElement>().ok())
            else {
                return;
            };
            let mut st = s.borrow_mut();
            st.focused_handle = Some(select.value());
            // The boxes show the newly chosen point at once (before any typing).
            st.shown_move.selected = None;
            st.sync_move_form();
            st.needs_paint = true;
        }));
    }
    if let Some(button) = query(panel, "[data-a11y=describe]") {
        let s = state.clone();
        listeners.push(Listener::new(button.as_ref(), "click", move |_| {
            s.borrow().describe_on_request();
        }));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn handles(ids: &[&str]) -> Vec<Handle> {
        ids.iter()
            .map(|id| Handle::new(*id, id.to_uppercase(), DVec2::ZERO))
            .collect()
    }

    #[test]
    fn brackets_cycle_through_the_handles_and_wrap() {
        let h = handles(&["start", "goal", "o1"]);
        assert_eq!(cycle(&h, None, true).as_deref(), Some("start"));
        assert_eq!(cycle(&h, None, false).as_deref(), Some("o1"));
        assert_eq!(cycle(&h, Some("start"), true).as_deref(), Some("goal"));
        assert_eq!(cycle(&h, Some("o1"), true).as_deref(), Some("start"));
        assert_eq!(cycle(&h, Some("start"), false).as_deref(), Some("o1"));
        // A handle that has gone: start again from the first.
        assert_eq!(cycle(&h, Some("w9"), true).as_deref(), Some("start"));
        assert_eq!(cycle(&[], Some("start"), true), None);
    }

    #[test]
    fn the_move_form_has_a_labelled_picker_and_two_labelled_boxes() {
        let html = move_form_html();
        assert!(html.contains("<label for=\"move-handle\">Point</label>"));
        assert!(html.contains("<label for=\"move-x\">x</label>"));
        assert!(html.contains("<label for=\"move-y\">y</label>"));
        assert!(html.contains(" hidden>"), "hidden until there is a point");
        assert!(!html.contains("style="), "no inline style (CSP)");
    }
}
