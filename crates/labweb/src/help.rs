//! The keyboard-shortcut help (issue 17 §6): `?` anywhere on the page (but
//! not while typing in a field) opens a modal dialog listing the shell's keys
//! and, on an experiment's page, that experiment's; Escape or Close shuts it
//! and focus goes back where it was.

use crate::dom::{self, escape, Listener};
use labcore::route::{self, Page};
use labcore::Lab;
use std::cell::RefCell;
use wasm_bindgen::{JsCast, JsValue};
use web_sys::{Element, Event, HtmlElement, KeyboardEvent};

/// The dialog's element id.
const DIALOG_ID: &str = "kbd-help";

thread_local! {
    /// The document's `?` listener and the dialog's own, kept for the page's life.
    static LISTENERS: RefCell<Vec<Listener>> = const { RefCell::new(Vec::new()) };
    /// Where focus was when the dialog opened.
    static RETURN_TO: RefCell<Option<HtmlElement>> = const { RefCell::new(None) };
}

/// Keys every page shares.
const SHELL_KEYS: &[(&str, &str)] = &[
    ("?", "Show this list of keys"),
    ("Escape", "Close this list, or the experiments menu"),
    ("Tab / Shift+Tab", "Move between controls"),
    (
        "← / →",
        "On the tabs: previous or next tab (Home and End: the first and last)",
    ),
];

/// Keys of the simulation canvas (with the canvas focused).
const CANVAS_KEYS: &[(&str, &str)] = &[
    (
        "[ / ]",
        "Choose the previous or next point to move (drawn with a ring)",
    ),
    (
        "← ↑ → ↓",
        "Move the chosen point (Shift: fine steps); with none chosen, nudge the current one",
    ),
    ("Escape", "Let go of the chosen point"),
    ("D", "Describe the scene (read out by a screen reader)"),
];

/// Keys of the time controls (animated experiments), anywhere in the
/// Simulation tab but in a text field.
const TIME_KEYS: &[(&str, &str)] = &[
    ("Space", "Play or pause (Replay once the run has ended)"),
    (".", "One step while paused"),
    (",", "One step back (the timeline)"),
    ("End", "Run to the end at once"),
    ("M", "Mark the moment shown (again: remove the mark)"),
];

/// Keys of the timeline slider and of the plots (focused).
const TIMELINE_KEYS: &[(&str, &str)] = &[
    (
        "← / →",
        "Slider: one step back or on; plot: the previous or next point",
    ),
    ("Page Up / Page Down", "Slider: one second back or on"),
    ("Home / End", "The run's start or end"),
];

fn rows(keys: &[(&str, &str)]) -> String {
    keys.iter()
        .map(|(k, what)| {
            let keys: Vec<String> = k
                .split(" / ")
                .map(|part| format!("<kbd>{}</kbd>", escape(part)))
                .collect();
            format!(
                "<tr><th scope=\"row\">{}</th><td>{}</td></tr>",
                keys.join(" / "),
                escape(what)
            )
        })
        .collect()
}

fn section(title: &str, keys: &[(&str, &str)]) -> String {
    format!(
        "<table class=\"kbd-table\"><caption>{}</caption><tbody>{}</tbody></table>",
        escape(title),
        rows(keys)
    )
}

/// The dialog's contents: the shell's keys, then those of `exp` (its canvas,
/// its time controls when animated, and its own hint).
#[must_use]
pub fn help_html(exp: Option<&dyn Lab>) -> String {
    let mut html = String::from("<h2 id=\"kbd-help-title\">Keyboard shortcuts</h2>");
    html.push_str(&section("Everywhere", SHELL_KEYS));
    if let Some(exp) = exp {
        if exp.animated() {
            html.push_str(&section("Simulation tab (not in a text field)", TIME_KEYS));
            html.push_str(&section("Timeline slider and plots", TIMELINE_KEYS));
        }
        html.push_str(&section("Simulation canvas", CANVAS_KEYS));
        html.push_str(&format!(
            "<p class=\"kbd-hint\"><strong>This experiment:</strong> {}</p>",
            escape(exp.hint())
        ));
    }
    html.push_str(
        "<form method=\"dialog\" class=\"kbd-close\"><button type=\"submit\" class=\"mini\">Close</button></form>",
    );
    html
}

/// Whether a key press belongs to a text field (its `?` is a character).
fn typing(target: Option<&Element>) -> bool {
    target.is_some_and(|el| {
        let tag = el.tag_name().to_ascii_lowercase();
        matches!(tag.as_str(), "input" | "textarea" | "select")
            || el
                .get_attribute("contenteditable")
                .is_some_and(|v| v != "false")
    })
}

/// The experiment the page shows now, if any.
fn current_experiment() -> Option<Box<dyn Lab>> {
    let hash = dom::window().location().hash().unwrap_or_default();
    let ids: Vec<&str> = labcore::registry().iter().map(|e| e.id).collect();
    match route::parse(&hash, &ids).page {
        Page::Experiment { id, .. } => labcore::find(&id).map(|e| (e.make)()),
        Page::Home => None,
    }
}

fn call(el: &Element, method: &str) {
    if let Ok(f) = js_sys::Reflect::get(el, &JsValue::from_str(method)) {
        if let Some(f) = f.dyn_ref::<js_sys::Function>() {
            let _ = f.call0(el);
        }
    }
}

/// The dialog, made on first use.
fn dialog() -> Option<Element> {
    if let Some(d) = dom::by_id(DIALOG_ID) {
        return Some(d);
    }
    let doc = dom::document();
    let d = doc.create_element("dialog").ok()?;
    d.set_id(DIALOG_ID);
    d.set_class_name("kbd-help");
    let _ = d.set_attribute("aria-labelledby", "kbd-help-title");
    doc.body()?.append_child(&d).ok()?;
    // Closed (Escape, Close): focus goes back to where it was.
    let listener = Listener::new(d.as_ref(), "close", |_| {
        if let Some(el) = RETURN_TO.with(|r| r.borrow_mut().take()) {
            let _ = el.focus();
        }
    });
    LISTENERS.with(|l| l.borrow_mut().push(listener));
    Some(d)
}

/// Opens the help (or leaves it open).
pub fn open() {
    let Some(d) = dialog() else {
        return;
    };
    if d.has_attribute("open") {
        return;
    }
    let exp = current_experiment();
    d.set_inner_html(&help_html(exp.as_deref()));
    let active = dom::document()
        .active_element()
        .and_then(|a| a.dyn_into::<HtmlElement>().ok());
    RETURN_TO.with(|r| *r.borrow_mut() = active);
    call(&d, "showModal");
    if let Some(close) = d
        .query_selector(".kbd-close button")
        .ok()
        .flatten()
        .and_then(|b| b.dyn_into::<HtmlElement>().ok())
    {
        let _ = close.focus();
    }
}

/// Listens for `?` on the whole page (once).
pub fn install() {
    if LISTENERS.with(|l| !l.borrow().is_empty()) {
        return;
    }
    let listener = Listener::new(dom::document().as_ref(), "keydown", |e: Event| {
        let Some(k) = e.dyn_ref::<KeyboardEvent>() else {
            return;
        };
        if k.key() != "?" || k.ctrl_key() || k.meta_key() || k.alt_key() {
            return;
        }
        let target = e.target().and_then(|t| t.dyn_into::<Element>().ok());
        if typing(target.as_ref()) {
            return;
        }
        e.prevent_default();
        open();
    });
    LISTENERS.with(|l| l.borrow_mut().push(listener));
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_help_lists_the_shell_keys_and_the_experiments() {
        let home = help_html(None);
        assert!(home.contains("<kbd>?</kbd>"));
        assert!(!home.contains("Simulation canvas"));
        let pid = (labcore::find("pid").unwrap().make)();
        let html = help_html(Some(pid.as_ref()));
        assert!(html.contains("<kbd>Space</kbd>"), "pid is animated");
        assert!(html.contains("<kbd>[</kbd> / <kbd>]</kbd>"));
        assert!(html.contains("<kbd>Page Up</kbd>"), "the slider's keys");
        assert!(html.contains(&escape(pid.hint())));
        let fk = (labcore::find("fk").unwrap().make)();
        assert!(!help_html(Some(fk.as_ref())).contains("<kbd>Space</kbd>"));
        assert!(!html.contains("style="), "no inline style (CSP)");
    }
}
