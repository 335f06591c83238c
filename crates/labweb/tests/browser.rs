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

/// A stand-in experiment for the shell's status model: it runs for 0.5 s
/// and then reports an ended run; a press on the canvas posts a notice.
#[derive(Clone)]
struct Runner {
    t_s: f64,
    notices: labcore::Notices,
    /// The canvas size the page last told ([`labcore::Experiment::viewport_px`]).
    viewport_px: (f64, f64),
}

impl labcore::Experiment for Runner {
    fn id(&self) -> &'static str {
        "runner"
    }
    fn params(&self) -> &'static [labcore::ParamSpec] {
        &[]
    }
    fn param(&self, _key: &str) -> Option<f64> {
        None
    }
    fn set_param(&mut self, key: &str, _v: f64) -> Result<labcore::Sanitized, labcore::ParamError> {
        Err(labcore::ParamError::UnknownKey { key: key.into() })
    }
    fn input(&mut self, input: labcore::Input) {
        if let labcore::Input::PointerDown(_) = input {
            self.notices
                .post("a waypoint queue is full", labcore::Tone::Warning);
        }
    }
    fn step(&mut self, dt_s: f64) {
        self.t_s += dt_s;
    }
    fn animated(&self) -> bool {
        true
    }
    fn reset(&mut self) {
        self.t_s = 0.0;
    }
}

impl labcore::Presentation for Runner {
    fn view(&self) -> labcore::ViewBox {
        labcore::ViewBox::centered(1.0)
    }
    fn viewport_px(&mut self, width_px: f64, height_px: f64) {
        self.viewport_px = (width_px, height_px);
    }
    fn scene(&self, _out: &mut labcore::Scene) {}
    fn readouts(&self) -> Vec<labcore::Readout> {
        vec![
            labcore::Readout::new("t", "Time", format!("{:.2}", self.t_s)),
            labcore::Readout::new(
                "vp",
                "Canvas",
                format!("{}×{}", self.viewport_px.0, self.viewport_px.1),
            ),
        ]
    }
    fn status(&self) -> labcore::Status {
        if self.t_s >= 0.5 {
            labcore::Status::ended("done", labcore::Tone::Good)
        } else {
            labcore::Status::new("running", labcore::Tone::Neutral)
        }
    }
    fn notice(&self) -> Option<labcore::Notice> {
        self.notices.current()
    }
    fn hint(&self) -> &'static str {
        "test runner"
    }
}

/// Mounts [`Runner`] in a bare Simulation panel and returns its view.
fn mount_runner() -> labweb::sim::SimView {
    labweb::unmount();
    if let Some(old) = document().get_element_by_id("lab-under-test") {
        old.remove();
    }
    let panel = document().create_element("div").unwrap();
    panel.set_id("lab-under-test");
    document().body().unwrap().append_child(&panel).unwrap();
    let exp = Runner {
        t_s: 0.0,
        notices: labcore::Notices::default(),
        viewport_px: (0.0, 0.0),
    };
    panel.set_inner_html(&format!(
        "<style>.sim-canvas{{display:block;width:300px;height:200px}}</style>{}",
        labweb::sim::render(&exp, "test runner")
    ));
    // No animation loop: the test drives the frames itself (`frame_at`).
    let view = labweb::sim::SimView::mount(&panel, Box::new(exp)).unwrap();
    view.paint_now();
    view
}

fn text_of(selector: &str) -> String {
    document()
        .query_selector(selector)
        .unwrap()
        .expect(selector)
        .text_content()
        .unwrap_or_default()
}

fn attr_of(selector: &str, name: &str) -> Option<String> {
    document()
        .query_selector(selector)
        .unwrap()
        .expect(selector)
        .get_attribute(name)
}

fn hidden(selector: &str) -> bool {
    document()
        .query_selector(selector)
        .unwrap()
        .expect(selector)
        .dyn_ref::<HtmlElement>()
        .unwrap()
        .hidden()
}

/// Runs frames 16 ms apart from `from_ms` for `n` frames; returns the next time.
fn frames(view: &labweb::sim::SimView, from_ms: f64, n: usize) -> f64 {
    let mut t = from_ms;
    for _ in 0..n {
        view.frame_at(t);
        t += 16.0;
    }
    t
}

#[wasm_bindgen_test]
fn an_ended_run_stops_the_clock_and_offers_replay_which_starts_it_again() {
    let view = mount_runner();
    let t = frames(&view, 0.0, 3);
    assert_eq!(text_of(".tb-label"), "Pause");
    assert_eq!(text_of(".sim-status"), "running");
    // 0.5 s of simulated time at 1×: about 32 frames of 16 ms.
    let t = frames(&view, t, 60);
    assert_eq!(text_of(".sim-status"), "done");
    assert_eq!(
        attr_of(".sim-status", "data-phase").as_deref(),
        Some("ended")
    );
    assert_eq!(
        text_of(".tb-label"),
        "Replay",
        "an ended run offers Replay, not Pause"
    );
    assert_eq!(
        attr_of(".tb-play", "aria-pressed").as_deref(),
        Some("false")
    );
    let stopped_at = text_of(".tb-time");
    let t = frames(&view, t, 20);
    assert_eq!(text_of(".tb-time"), stopped_at, "the clock stopped");
    // The link does not say "paused": the run ended by itself.
    assert!(!view.hash(labcore::route::Tab::Simulation).contains("run=0"));
    // Replay: back to the start, and playing.
    let play: HtmlElement = document()
        .query_selector(".tb-play")
        .unwrap()
        .unwrap()
        .dyn_into()
        .unwrap();
    play.click();
    let _ = frames(&view, t, 3);
    assert_eq!(text_of(".sim-status"), "running");
    assert_eq!(text_of(".tb-label"), "Pause");
}

/// A mouse press on the focused canvas (one on an unfocused canvas only
/// focuses it).
fn press_canvas() {
    let canvas = document()
        .query_selector("canvas.sim-canvas")
        .unwrap()
        .unwrap();
    canvas
        .dyn_ref::<web_sys::HtmlElement>()
        .unwrap()
        .focus()
        .unwrap();
    let init = web_sys::PointerEventInit::new();
    init.set_is_primary(true);
    init.set_pointer_id(1);
    init.set_pointer_type("mouse");
    init.set_bubbles(true);
    let down = web_sys::PointerEvent::new_with_event_init_dict("pointerdown", &init).unwrap();
    canvas.dispatch_event(&down).unwrap();
    let up = web_sys::PointerEvent::new_with_event_init_dict("pointerup", &init).unwrap();
    canvas.dispatch_event(&up).unwrap();
}

#[wasm_bindgen_test]
fn a_notice_shows_under_the_badge_then_goes_after_six_seconds_or_at_the_next_input() {
    let view = mount_runner();
    let t = frames(&view, 0.0, 2);
    assert!(hidden(".sim-notice"));
    press_canvas();
    let t = frames(&view, t, 2);
    assert!(!hidden(".sim-notice"));
    assert_eq!(text_of(".sim-notice"), "a waypoint queue is full");
    assert_eq!(
        text_of(".sim-status"),
        "running",
        "the badge keeps the run's state"
    );
    assert_eq!(
        attr_of(".sim-notice", "aria-live").as_deref(),
        Some("polite")
    );
    // Six seconds later it is gone.
    view.frame_at(t + 6100.0);
    assert!(hidden(".sim-notice"));
    // A new one (a new serial) shows again; a key press that posts nothing hides it.
    press_canvas();
    let t = frames(&view, t + 6200.0, 2);
    assert!(!hidden(".sim-notice"));
    let canvas = document()
        .query_selector("canvas.sim-canvas")
        .unwrap()
        .unwrap();
    let init = web_sys::KeyboardEventInit::new();
    init.set_key("ArrowLeft");
    init.set_bubbles(true);
    let key = web_sys::KeyboardEvent::new_with_keyboard_event_init_dict("keydown", &init).unwrap();
    canvas.dispatch_event(&key).unwrap();
    let _ = frames(&view, t, 2);
    assert!(hidden(".sim-notice"), "the next input hides the notice");
}

#[wasm_bindgen_test]
fn a_scale_bar_is_drawn_in_the_lower_left_and_an_off_view_mark_on_the_edge_toward_the_point() {
    let canvas: HtmlCanvasElement = document()
        .create_element("canvas")
        .unwrap()
        .dyn_into()
        .unwrap();
    canvas.set_width(300);
    canvas.set_height(200);
    let ctx: CanvasRenderingContext2d = canvas
        .get_context("2d")
        .unwrap()
        .unwrap()
        .dyn_into()
        .unwrap();
    let palette = labweb::draw::Palette::from_css(&canvas);
    let view = labcore::ViewBox {
        min: glam::DVec2::ZERO,
        max: glam::DVec2::new(6.0, 4.0),
    };
    let viewport = labweb::draw::Viewport::fit(view, 300.0, 200.0);
    let mut scene = labcore::Scene::default();
    scene.push(labcore::Item::ScaleBar);
    // Far to the right of the view, level with its centre.
    scene.push(labcore::Item::OffView {
        at: glam::DVec2::new(40.0, 2.0),
        label: String::new(),
        role: labcore::Role::Robot,
    });
    labweb::draw::paint(&ctx, &scene, &viewport, 300.0, 200.0, 1.0, &palette);
    let px = |x: f64, y: f64| {
        let d = ctx.get_image_data(x, y, 1.0, 1.0).unwrap().data();
        [d[0], d[1], d[2]]
    };
    let background = px(150.0, 60.0);
    // 50 px per metre: a 2 m bar (100 px) from x = 14 along y = 186.
    assert_ne!(px(60.0, 186.0), background, "the scale bar's line");
    assert_eq!(px(150.0, 186.0), background, "and no longer than 2 m");
    // The edge mark: an arrowhead at the right edge, at mid-height.
    assert_ne!(px(282.0, 100.0), background, "the mark on the right edge");
    assert_eq!(px(20.0, 100.0), background, "nothing on the left edge");
}

#[wasm_bindgen_test]
fn the_experiment_is_told_the_canvas_size_on_mount_and_on_resize() {
    let view = mount_runner();
    assert_eq!(text_of("[data-readout=vp]"), "300×200");
    let canvas: HtmlElement = document()
        .query_selector("canvas.sim-canvas")
        .unwrap()
        .unwrap()
        .dyn_into()
        .unwrap();
    canvas.style().set_property("width", "240px").unwrap();
    canvas.style().set_property("height", "180px").unwrap();
    view.paint_now();
    assert_eq!(text_of("[data-readout=vp]"), "240×180");
}
