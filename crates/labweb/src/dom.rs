//! Small DOM helpers and owned event listeners.
//!
//! Every listener is a [`Listener`]: dropping it removes the listener and frees
//! its closure, so leaving an experiment leaks nothing (no `Closure::forget`).

use std::cell::Cell;
use std::rc::Rc;
use wasm_bindgen::prelude::*;
use wasm_bindgen::JsCast;
use web_sys::{Document, Element, Event, EventTarget, HtmlElement, Window};

#[wasm_bindgen]
extern "C" {
    /// The page's window, looked up once: `web_sys::window()` checks the
    /// global's type in JavaScript at every call, and a frame asked for it
    /// dozens of times (0.3 ms of a workspace scrub frame, unthrottled).
    #[wasm_bindgen(thread_local_v2, js_name = window)]
    static WINDOW: Window;
    /// The page's document, looked up once.
    #[wasm_bindgen(thread_local_v2, js_name = document)]
    static DOCUMENT: Document;
    /// `performance.now()`, called directly.
    #[wasm_bindgen(js_namespace = performance, js_name = now)]
    fn performance_now() -> f64;
}

pub fn window() -> Window {
    WINDOW.with(Window::clone)
}

pub fn document() -> Document {
    DOCUMENT.with(Document::clone)
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

/// Writes `text` into an element that holds only text, rewriting its text
/// node in place ([`rewrite_markup`]). `textContent` would replace the node:
/// the browser then drops and rebuilds its layout box and re-checks every
/// `:has()` rule of the elements above it, each frame the timeline's time
/// changes. The text goes through the HTML parser, which reads `\r` as
/// `\n` and drops NUL: no page text holds either.
pub fn set_text(el: &Element, text: &str) {
    rewrite_markup(el, &escape(text));
}

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

    /// `window.labRewriteMarkup`, defined in `web/main.js`: writes markup
    /// into an element keeping the nodes that stay.
    #[wasm_bindgen(catch, js_namespace = window, js_name = labRewriteMarkup)]
    fn rewrite_markup_js(el: &Element, html: &str) -> Result<(), JsValue>;

    /// `window.labWatchBox`, defined in `web/main.js`: calls `on_change`
    /// with an element's size and whether it is in the window whenever the
    /// browser's observers see either change; returns the function that
    /// stops it.
    /// `window.labWhenIdle`, defined in `web/main.js` ([`when_idle`]).
    #[wasm_bindgen(catch, js_namespace = window, js_name = labWhenIdle)]
    fn when_idle_js(el: &Element, timeout_ms: u32) -> Result<bool, JsValue>;
    #[wasm_bindgen(catch, js_namespace = window, js_name = labWatchBox)]
    fn watch_box_js(
        el: &Element,
        on_change: &Closure<dyn FnMut(f64, f64, bool)>,
    ) -> Result<js_sys::Function, JsValue>;
}

/// What the browser's observers last saw of a watched element
/// ([`watch_box`]): its size in CSS px and whether any of it is in the
/// window.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SeenBox {
    /// Width, CSS px (0 until the element was laid out with a size).
    pub width: f64,
    /// Height, CSS px.
    pub height: f64,
    /// Whether some of it is in the window (true until first told).
    pub in_window: bool,
}

impl SeenBox {
    /// Laid out with a size and in the window.
    #[must_use]
    pub fn on_screen(&self) -> bool {
        self.height > 0.0 && self.in_window
    }
}

/// Reads `el`'s size and whether some of it is in the window now, as the
/// observers of [`watch_box`] would tell (vertically: a box scrolled above
/// or below the window, or hidden with no size, is out). A read after the
/// page changed lays the page out at once: use it only where no watch has
/// told yet.
#[must_use]
pub fn read_box(el: &Element) -> SeenBox {
    let rect = el.get_bounding_client_rect();
    let view_h = window()
        .inner_height()
        .ok()
        .and_then(|h| h.as_f64())
        .unwrap_or(f64::INFINITY);
    SeenBox {
        width: rect.width(),
        height: rect.height(),
        in_window: rect.bottom() > 0.0 && rect.top() < view_h,
    }
}

/// An element watched by [`watch_box`]; dropped, the watch stops.
pub struct BoxWatch {
    /// The latest report; `None` before the first.
    pub seen: Rc<Cell<Option<SeenBox>>>,
    stop: js_sys::Function,
    _on_change: Closure<dyn FnMut(f64, f64, bool)>,
}

impl Drop for BoxWatch {
    fn drop(&mut self) {
        let _ = self.stop.call0(&JsValue::NULL);
    }
}

/// Watches `el`'s size and whether it is in the window with the browser's
/// observers (`web/main.js`'s `labWatchBox`), so a frame learns both
/// without reading a size: a read after the page changed (a slider moved,
/// a text written) makes the browser lay the whole page out at once, in the
/// frame. `None` where the observers are missing.
#[must_use]
pub fn watch_box(el: &Element) -> Option<BoxWatch> {
    #[cfg(feature = "reading")]
    install_from_main_js("labWatchBox");
    let seen = Rc::new(Cell::new(None));
    let told = seen.clone();
    let on_change = Closure::<dyn FnMut(f64, f64, bool)>::new(move |width, height, in_window| {
        told.set(Some(SeenBox {
            width,
            height,
            in_window,
        }));
    });
    let stop = watch_box_js(el, &on_change).ok()?;
    Some(BoxWatch {
        seen,
        stop,
        _on_change: on_change,
    })
}

/// Writes `html` into `el` as `innerHTML` would, keeping every element the
/// new markup keeps (same name and attributes at the same place) and
/// rewriting in place only the text that changed. "The math" panel writes a
/// streaming run's numbers this way: the browser then lays out and repaints
/// the numbers, not a formula parsed anew. The code is `web/main.js`'s
/// `labRewriteMarkup` (the browser's own parser reads the markup); without
/// it, `innerHTML`.
pub fn rewrite_markup(el: &Element, html: &str) {
    #[cfg(feature = "reading")]
    install_from_main_js("labRewriteMarkup");
    if rewrite_markup_js(el, html).is_err() {
        el.set_inner_html(html);
    }
}

/// Shows the home page (`article` `None`), or `article` on the tab `tab`
/// (its slug): hides the other pages and panels, marks the tab selected and
/// the experiment current in the menu, and titles the document. The code is
/// `web/main.js`'s `labShowArticle`, which the page shows tabs with before
/// any wasm runs; the test pages (every experiment's content built in) take
/// it from main.js's text.
pub fn show_article(article: Option<&Element>, tab: &str) {
    #[cfg(feature = "reading")]
    install_from_main_js("labShowArticle");
    if let Err(e) = show_article_js(article, tab) {
        web_sys::console::error_2(&"labShowArticle (web/main.js) failed:".into(), &e);
    }
}

/// On a test page (no main.js): defines `window.<name>` from main.js's own
/// text (between its `// <name>: begin` and `// <name>: end` lines), so the
/// tests run the code the site ships.
#[cfg(feature = "reading")]
fn install_from_main_js(name: &str) {
    const MAIN_JS: &str = include_str!("../../../web/main.js");
    let present = js_sys::Reflect::get(&window(), &name.into()).is_ok_and(|f| f.is_function());
    if present {
        return;
    }
    let marked = |mark: &str| {
        MAIN_JS
            .find(&format!("// {name}: {mark}"))
            .unwrap_or_else(|| panic!("main.js marks {name}"))
    };
    let code = &MAIN_JS[marked("begin")..marked("end")];
    let _ = js_sys::Function::new_no_args(code).call0(&JsValue::NULL);
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

/// Sends `el` the event `lab-idle` once the browser's main thread is idle
/// between frames (`requestIdleCallback`), `timeout_ms` later at the latest
/// on a busy page. The code is `web/main.js`'s `labWhenIdle`. Returns false
/// where the browser has no idle callbacks (WebKit's Safari).
pub fn when_idle(el: &Element, timeout_ms: u32) -> bool {
    #[cfg(feature = "reading")]
    install_from_main_js("labWhenIdle");
    when_idle_js(el, timeout_ms).unwrap_or(false)
}

/// Performance clock in milliseconds.
pub fn now_ms() -> f64 {
    performance_now()
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
