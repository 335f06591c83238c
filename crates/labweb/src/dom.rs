//! Small DOM helpers and owned event listeners.
//!
//! Every listener is a [`Listener`]: dropping it removes the listener and frees
//! its closure, so leaving an experiment leaks nothing (no `Closure::forget`).

use wasm_bindgen::prelude::*;
use wasm_bindgen::JsCast;
use web_sys::{Document, Element, Event, EventTarget, HtmlElement, Window};

pub fn window() -> Window {
    web_sys::window().expect("a browser window")
}

pub fn document() -> Document {
    window().document().expect("a document")
}

pub fn by_id(id: &str) -> Option<Element> {
    document().get_element_by_id(id)
}

pub fn query(root: &Element, selector: &str) -> Option<Element> {
    root.query_selector(selector).ok().flatten()
}

pub fn query_all(root: &Element, selector: &str) -> Vec<Element> {
    let Ok(list) = root.query_selector_all(selector) else {
        return Vec::new();
    };
    (0..list.length())
        .filter_map(|i| list.get(i))
        .filter_map(|n| n.dyn_into::<Element>().ok())
        .collect()
}

pub use labpage::content_html::escape;

pub fn set_hidden(el: &Element, hidden: bool) {
    if let Some(h) = el.dyn_ref::<HtmlElement>() {
        h.set_hidden(hidden);
    }
}

#[wasm_bindgen]
extern "C" {
    /// `window.labShowArticle`, defined in `web/main.js`: the one place a
    /// page or a tab is shown (main.js shows it before the wasm runs).
    #[wasm_bindgen(catch, js_namespace = window, js_name = labShowArticle)]
    fn show_article_js(article: Option<&Element>, tab: &str) -> Result<(), JsValue>;
}

/// Shows the home page (`article` `None`), or `article` on the tab `tab`
/// (its slug): hides the other pages and panels, marks the tab selected and
/// the experiment current in the menu, and titles the document. The code is
/// `web/main.js`'s `labShowArticle`, which the page shows tabs with before
/// any wasm runs; the test pages (every experiment's content built in) take
/// it from main.js's text.
pub fn show_article(article: Option<&Element>, tab: &str) {
    #[cfg(feature = "reading")]
    install_show_article();
    if let Err(e) = show_article_js(article, tab) {
        web_sys::console::error_2(&"labShowArticle (web/main.js) failed:".into(), &e);
    }
}

/// On a test page (no main.js): defines `window.labShowArticle` from
/// main.js's own text, so the tests run the code the site ships.
#[cfg(feature = "reading")]
fn install_show_article() {
    const MAIN_JS: &str = include_str!("../../../web/main.js");
    let present =
        js_sys::Reflect::get(&window(), &"labShowArticle".into()).is_ok_and(|f| f.is_function());
    if present {
        return;
    }
    let begin = MAIN_JS
        .find("// labShowArticle: begin")
        .expect("main.js marks labShowArticle");
    let end = MAIN_JS
        .find("// labShowArticle: end")
        .expect("main.js marks labShowArticle");
    let _ = js_sys::Function::new_no_args(&MAIN_JS[begin..end]).call0(&JsValue::NULL);
}

/// Runs `f` in a task of its own (after the current one), so long work is
/// split below the 50 ms long-task budget. The callback frees itself once run.
pub fn defer(f: impl FnOnce() + 'static) {
    let callback = Closure::once_into_js(f);
    let _ =
        window().set_timeout_with_callback_and_timeout_and_arguments_0(callback.unchecked_ref(), 0);
}

/// Runs `f` at the next animation frame, where the browser lays the page out
/// anyway (so reading layout there forces no extra synchronous layout).
pub fn next_frame(f: impl FnOnce() + 'static) {
    let callback = Closure::once_into_js(f);
    let _ = window().request_animation_frame(callback.unchecked_ref());
}

/// Performance clock in milliseconds.
pub fn now_ms() -> f64 {
    window().performance().map_or(0.0, |p| p.now())
}

/// An event listener that is removed when dropped.
pub struct Listener {
    target: EventTarget,
    kind: &'static str,
    closure: Closure<dyn FnMut(Event)>,
}

impl Listener {
    pub fn new(target: &EventTarget, kind: &'static str, f: impl FnMut(Event) + 'static) -> Self {
        let closure = Closure::<dyn FnMut(Event)>::new(f);
        let _ = target.add_event_listener_with_callback(kind, closure.as_ref().unchecked_ref());
        Self {
            target: target.clone(),
            kind,
            closure,
        }
    }
}

impl Drop for Listener {
    fn drop(&mut self) {
        let _ = self
            .target
            .remove_event_listener_with_callback(self.kind, self.closure.as_ref().unchecked_ref());
    }
}

/// Shows a message in the page's notice bar (text only, never HTML).
pub fn notice(messages: &[String]) {
    let Some(bar) = by_id("notice") else { return };
    if messages.is_empty() {
        return;
    }
    if let Some(text) = query(&bar, ".notice-text") {
        text.set_text_content(Some(&messages.join(" ")));
    }
    set_hidden(&bar, false);
}

pub fn clear_notice() {
    if let Some(bar) = by_id("notice") {
        set_hidden(&bar, true);
    }
}

/// Shows a fatal error where the student can see it.
pub fn fatal(message: &str) {
    web_sys::console::error_1(&JsValue::from_str(message));
    if let Some(el) = by_id("fatal") {
        if let Some(text) = query(&el, ".fatal-text") {
            text.set_text_content(Some(message));
        }
        set_hidden(&el, false);
    }
}
