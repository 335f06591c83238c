//! labweb in headless Chromium: mount the shell, move a slider, read the
//! readout and the canvas pixels; a malformed hash shows a notice.

use wasm_bindgen::JsCast;
use wasm_bindgen_test::*;
use web_sys::{
    CanvasRenderingContext2d, Event, EventInit, HtmlCanvasElement, HtmlElement, HtmlInputElement,
};

wasm_bindgen_test_configure!(run_in_browser);

fn document() -> web_sys::Document {
    web_sys::window().unwrap().document().unwrap()
}

/// A minimal copy of the shell: the elements the app mounts into.
fn mount(hash: &str) {
    // The previous test's app must not hear this test's hash change.
    labweb::unmount();
    // The test runner reports through elements of its own page: keep them,
    // and swap only our wrapper between tests.
    if let Some(old) = document().get_element_by_id("lab-under-test") {
        old.remove();
    }
    let wrapper = document().create_element("div").unwrap();
    wrapper.set_id("lab-under-test");
    document().body().unwrap().append_child(&wrapper).unwrap();
    wrapper.set_inner_html(
        "<nav id=\"lab-nav\"></nav>\
         <div id=\"notice\" hidden><span class=\"notice-text\"></span></div>\
         <div id=\"fatal\" hidden><span class=\"fatal-text\"></span></div>\
         <main id=\"app\" style=\"width:600px\"></main>\
         <style>.sim-canvas{display:block;width:400px;height:400px}</style>",
    );
    web_sys::window()
        .unwrap()
        .location()
        .set_hash(hash)
        .unwrap();
    labweb::boot();
    labweb::paint_now();
}

fn readout(key: &str) -> String {
    document()
        .query_selector(&format!("[data-readout=\"{key}\"]"))
        .unwrap()
        .expect("readout exists")
        .text_content()
        .unwrap_or_default()
}

fn input(selector: &str) -> HtmlInputElement {
    document()
        .query_selector(selector)
        .unwrap()
        .expect("control exists")
        .dyn_into()
        .unwrap()
}

fn fire(target: &web_sys::EventTarget, kind: &str) {
    let init = EventInit::new();
    init.set_bubbles(true);
    let event = Event::new_with_event_init_dict(kind, &init).unwrap();
    target.dispatch_event(&event).unwrap();
}

/// RGBA of the canvas backing store at CSS pixel (x, y).
fn pixel(x: f64, y: f64) -> [u8; 4] {
    let canvas: HtmlCanvasElement = document()
        .query_selector("canvas.sim-canvas")
        .unwrap()
        .unwrap()
        .dyn_into()
        .unwrap();
    let dpr = web_sys::window().unwrap().device_pixel_ratio();
    let ctx: CanvasRenderingContext2d = canvas
        .get_context("2d")
        .unwrap()
        .unwrap()
        .dyn_into()
        .unwrap();
    let data = ctx
        .get_image_data(x * dpr, y * dpr, 1.0, 1.0)
        .unwrap()
        .data();
    [data[0], data[1], data[2], data[3]]
}

#[wasm_bindgen_test]
fn slider_moves_the_readout_and_the_drawn_arm() {
    mount("#/fk/simulation?t1=30&t2=60&l1=1&l2=0.5");
    // Tip (cos 30° + 0.5 cos 90°, sin 30° + 0.5 sin 90°) = (0.866, 1), off every drawn circle.
    assert_eq!(readout("x"), "0.866 m");
    assert_eq!(readout("y"), "1.000 m");
    assert_eq!(readout("reach"), "88.2%");
    // Where the canvas shows a world point (same mapping the app uses).
    // The view the page shows (it frames the arm's current reach).
    let canvas = document()
        .query_selector("canvas.sim-canvas")
        .unwrap()
        .unwrap();
    let v: Vec<f64> = canvas
        .get_attribute("data-view")
        .expect("the canvas names its view")
        .split(',')
        .map(|n| n.parse().unwrap())
        .collect();
    let view = labcore::ViewBox {
        min: glam::DVec2::new(v[0], v[1]),
        max: glam::DVec2::new(v[2], v[3]),
    };
    let viewport = labweb::draw::Viewport::fit(view, 400.0, 400.0);
    let at = |x: f64, y: f64| {
        let p = viewport.to_px(glam::DVec2::new(x, y));
        pixel(p.x, p.y)
    };
    let background = pixel(395.0, 395.0);
    let old_tip = (30f64.to_radians().cos(), 1.0);
    assert_ne!(at(old_tip.0, old_tip.1), background, "the tip is drawn");

    let slider = input("input[type=range][data-param=t1]");
    slider.set_value("120");
    fire(slider.as_ref(), "input");
    labweb::paint_now();
    // Tip now at (cos 120° + 0.5 cos 180°, sin 120°) = (−1, 0.866).
    assert_eq!(readout("x"), "-1.000 m");
    assert_eq!(readout("y"), "0.866 m");
    // The number box mirrors the slider.
    assert_eq!(input("input[type=text][data-param=t1]").value(), "120");
    assert_ne!(at(-1.0, 120f64.to_radians().sin()), background);
    assert_eq!(at(old_tip.0, old_tip.1), background, "the old tip is gone");
}

#[wasm_bindgen_test]
fn typed_nonsense_keeps_the_last_good_value_with_a_message() {
    mount("#/fk/simulation");
    let number = input("input[type=text][data-param=t2]");
    number.set_value("");
    fire(number.as_ref(), "change");
    labweb::paint_now();
    let message = document().query_selector(".sim-message").unwrap().unwrap();
    assert!(!message.dyn_ref::<HtmlElement>().unwrap().hidden());
    assert!(message
        .text_content()
        .unwrap()
        .contains("Kept the previous value"));
    assert_eq!(input("input[type=range][data-param=t2]").value(), "60");
}

#[wasm_bindgen_test]
fn malformed_hash_shows_a_notice_and_clamps() {
    mount("#/fk/simulation?t1=abc&t2=9999");
    let notice = document().get_element_by_id("notice").unwrap();
    assert!(
        !notice.dyn_ref::<HtmlElement>().unwrap().hidden(),
        "notice hidden; text {:?}; hash {:?}",
        notice.text_content(),
        web_sys::window().unwrap().location().hash()
    );
    let text = notice.text_content().unwrap();
    assert!(
        text.contains("not a number") && text.contains("out of range"),
        "{text}"
    );
    assert_eq!(input("input[type=range][data-param=t2]").value(), "180");
}

#[wasm_bindgen_test]
fn every_tab_of_every_experiment_mounts() {
    for entry in labcore::registry() {
        mount(&format!("#/{}/theory", entry.id));
        let theory = document()
            .query_selector("[data-panel=theory]")
            .unwrap()
            .unwrap();
        assert!(
            theory.query_selector("math").unwrap().is_some(),
            "{} has MathML",
            entry.id
        );
        assert_eq!(
            document()
                .query_selector("[role=tab][aria-selected=true]")
                .unwrap()
                .unwrap()
                .get_attribute("data-tab")
                .as_deref(),
            Some("theory")
        );
        assert!(document()
            .query_selector("canvas.sim-canvas")
            .unwrap()
            .is_some());
        assert!(document().count_matches(".quiz-q") >= 8);
    }
}

trait CountExt {
    fn count_matches(&self, selector: &str) -> u32;
}

impl CountExt for web_sys::Document {
    fn count_matches(&self, selector: &str) -> u32 {
        self.query_selector_all(selector).map_or(0, |l| l.length())
    }
}

#[wasm_bindgen_test]
fn a_panic_is_reported_visibly_on_the_page() {
    mount("#/fk/aim");
    labweb::report_panic("test panic at sim.rs:1");
    let fatal = document().get_element_by_id("fatal").unwrap();
    assert!(!fatal.dyn_ref::<HtmlElement>().unwrap().hidden());
    let text = fatal.text_content().unwrap();
    assert!(
        text.contains("test panic") && text.contains("Reload"),
        "{text}"
    );
}
