//! The harness the page tests share (`runs.rs`, `timeline.rs`): a minimal
//! copy of the shell booted on a link, and animation frames the test drives
//! (the browser's `requestAnimationFrame` replaced by a queue the test
//! empties with a frame time of its choosing), so no step depends on the
//! wall clock.
#![allow(dead_code)] // each test file uses its own part of the harness

use labcore::clock::Clock;
use labcore::Lab;
use std::cell::Cell;
use wasm_bindgen::{JsCast, JsValue};
use web_sys::{HtmlElement, KeyboardEvent, KeyboardEventInit};

pub fn document() -> web_sys::Document {
    web_sys::window().unwrap().document().unwrap()
}

pub fn js(body: &str) -> JsValue {
    js_sys::Function::new_no_args(body)
        .call0(&JsValue::NULL)
        .unwrap()
}

/// Replaces `requestAnimationFrame` and `requestIdleCallback` by queues
/// (once): `__frame(t)` runs the frame callbacks queued so far with frame
/// time `t` (ms), and `__idle()` the idle callbacks, as a browser does
/// after a frame.
pub const FRAME_QUEUE: &str = r#"
if (!window.__frames) {
  const queue = (window.__frames = new Map());
  const idle = (window.__idles = new Map());
  let next = 0;
  window.requestAnimationFrame = (cb) => { queue.set(++next, cb); return next; };
  window.cancelAnimationFrame = (id) => { queue.delete(id); };
  window.requestIdleCallback = (cb) => { idle.set(++next, cb); return next; };
  window.cancelIdleCallback = (id) => { idle.delete(id); };
  const run = (q, arg) => {
    const due = [...q.values()];
    q.clear();
    for (const cb of due) cb(arg);
  };
  window.__frame = (t) => run(queue, t);
  window.__idle = () => run(idle, { didTimeout: false, timeRemaining: () => 50 });
}
"#;

thread_local! {
    /// The test's frame time, ms: it only ever grows.
    static NOW_MS: Cell<f64> = const { Cell::new(1000.0) };
}

/// One animation frame, `gap_ms` after the last, and the idle time after
/// it ([`idle`]).
pub fn frame(gap_ms: f64) {
    frame_alone(gap_ms);
    idle();
}

/// One animation frame, `gap_ms` after the last, with no idle time after
/// it (yet).
pub fn frame_alone(gap_ms: f64) {
    let t = NOW_MS.with(|n| {
        n.set(n.get() + gap_ms);
        n.get()
    });
    js_sys::Function::new_with_args("t", "window.__frame(t)")
        .call1(&JsValue::NULL, &JsValue::from_f64(t))
        .unwrap();
}

/// The browser's idle time between frames: the idle callbacks asked for so
/// far run.
pub fn idle() {
    js("window.__idle()");
}

/// Whether the page has asked for an idle callback that has not run yet.
pub fn idle_asked() -> bool {
    js("return window.__idles.size > 0;").as_bool().unwrap()
}

/// A frame gap that gives one fixed step per frame at 1× for hundreds of
/// frames (the accumulator gains 0.033 ms a frame).
pub const ONE_STEP_MS: f64 = 16.7;

/// A minimal copy of the shell, booted on `hash` (written without an event,
/// so no late `hashchange` reaches a later test).
pub fn mount(hash: &str) {
    js(FRAME_QUEUE);
    labweb::unmount();
    if let Some(old) = document().get_element_by_id("lab-under-test") {
        old.remove();
    }
    let wrapper = document().create_element("div").unwrap();
    wrapper.set_id("lab-under-test");
    document().body().unwrap().append_child(&wrapper).unwrap();
    // The site's own rules for the badge: its marks are CSS, as in the page
    // (the rest of the style sheet is left out: it only slows the frames).
    let badge_rules: String = include_str!("../../../../web/style.css")
        .lines()
        .filter(|l| l.starts_with(".sim-status["))
        .collect();
    wrapper.set_inner_html(&format!(
        "<nav id=\"lab-nav\"></nav>\
         <div id=\"notice\" hidden><span class=\"notice-text\"></span></div>\
         <div id=\"fatal\" hidden><span class=\"fatal-text\"></span></div>\
         <main id=\"app\" style=\"width:600px\"></main>\
         <style>{}</style>\
         <style>.sim-canvas{{display:block;width:400px;height:400px}}</style>",
        badge_rules
    ));
    web_sys::window()
        .unwrap()
        .history()
        .unwrap()
        .replace_state_with_url(&JsValue::NULL, "", Some(hash))
        .unwrap();
    labweb::boot();
    labweb::paint_now();
}

pub fn element(selector: &str) -> HtmlElement {
    document()
        .query_selector(selector)
        .unwrap()
        .unwrap_or_else(|| panic!("{selector} exists"))
        .dyn_into()
        .unwrap()
}

pub fn text(selector: &str) -> String {
    element(selector).text_content().unwrap_or_default()
}

pub fn attr(selector: &str, name: &str) -> Option<String> {
    element(selector).get_attribute(name)
}

/// What the page's run shows: steps counted, status, readouts, plots and
/// the scene's description (Debug text, so a NaN equals a NaN).
pub fn shown() -> (u64, String) {
    labweb::inspect_sim(|exp, steps| (steps, snapshot(exp))).expect("a simulation is mounted")
}

pub fn snapshot(exp: &dyn Lab) -> String {
    format!(
        "status {:?}\nreadouts {:?}\nplots {:?}\ndescribe {}",
        exp.status(),
        exp.readouts(),
        exp.plots(),
        exp.describe()
    )
}

/// The experiment built fresh and left alone for `steps` fixed steps.
pub fn left_alone(entry: &labcore::Entry, steps: u64) -> Box<dyn Lab> {
    let mut exp = (entry.make)();
    for _ in 0..steps {
        exp.step(Clock::DT_S);
    }
    exp
}

pub fn press_key_on_canvas(key: &str) {
    let init = KeyboardEventInit::new();
    init.set_key(key);
    init.set_bubbles(true);
    let event = KeyboardEvent::new_with_keyboard_event_init_dict("keydown", &init).unwrap();
    element("canvas.sim-canvas").dispatch_event(&event).unwrap();
}

pub fn hash() -> String {
    web_sys::window().unwrap().location().hash().unwrap()
}

/// Resolves once the browser's intersection observers have looked at the
/// element `selector` matches again and told the page: a fresh observer
/// reports after a rendering step that saw the page as it is now, and a
/// second fresh one after a later step, by which time every older
/// observer's report from the first step has run (they queue their reports
/// in the same task source).
pub async fn observers_report(selector: &str) {
    for _ in 0..2 {
        let promise = js(&format!(
            "return new Promise((r, fail) => {{ const el = document.querySelector('{selector}'); \
             if (!el) return fail(new Error('no element matches {selector}')); \
             setTimeout(() => fail(new Error('no observer report for {selector} in 10 s')), 10000); \
             const o = new IntersectionObserver(() => {{ o.disconnect(); r(); }}); o.observe(el); }})"
        ));
        wasm_bindgen_futures::JsFuture::from(js_sys::Promise::from(promise))
            .await
            .unwrap();
    }
}
