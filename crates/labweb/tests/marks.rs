//! Issue 26 §3 in the page: "Mark this moment" (the time bar's button and
//! `M`), the marks' list with its remove buttons, a point per mark on every
//! plot, `marks=` in the link, and what a reset and an input in the past do
//! to the marks. Frames are driven by the test (see `page/mod.rs`).

use wasm_bindgen::JsCast;
use wasm_bindgen_test::*;
use web_sys::{HtmlElement, HtmlInputElement};

mod page;
use page::{
    attr, document, element, frame, hash, left_alone, mount, press_key_on_canvas, shown, text,
    ONE_STEP_MS,
};

wasm_bindgen_test_configure!(run_in_browser);

fn scrub_to(step: u64) {
    let slider: HtmlInputElement = element(".tb-scrub").dyn_into().unwrap();
    slider.set_value(&step.to_string());
    let init = web_sys::EventInit::new();
    init.set_bubbles(true);
    let event = web_sys::Event::new_with_event_init_dict("input", &init).unwrap();
    slider.dispatch_event(&event).unwrap();
    labweb::paint_now();
}

/// The times the marks' list shows.
fn listed() -> Vec<String> {
    let list = document().query_selector_all(".tb-mark").unwrap();
    (0..list.length())
        .map(|i| {
            let el = list.get(i).unwrap();
            el.dyn_ref::<web_sys::Element>()
                .unwrap()
                .get_attribute("data-mark")
                .unwrap()
        })
        .collect()
}

/// What each plot's canvas says it draws as marks (`data-marks`), by key.
fn drawn_marks(key: &str) -> String {
    attr(&format!("figure[data-plot={key}] canvas"), "data-marks").unwrap_or_default()
}

/// The points marks at `steps` must have on plot `key`: the last sample
/// of each of the run's own series at each step.
fn expected_marks(key: &str, steps: &[u64]) -> String {
    let entry = labcore::find("pid").unwrap();
    let mut points = Vec::new();
    for &s in steps {
        let exp = left_alone(entry, s);
        for (k, pts) in labcore::marks::plot_points(exp.plots()) {
            if k == key {
                points.extend(pts.iter().map(|(x, y)| format!("{x},{y}")));
            }
        }
    }
    points.join(" ")
}

/// The button marks the scrubbed moment, `M` the live one; each mark is a
/// point on every plot at that step's samples; the list shows them and its
/// remove button takes one away; the button says whether the moment shown
/// is marked.
#[wasm_bindgen_test]
fn mark_button_and_m_key_mark_the_moment_shown_and_draw_it_on_every_plot() {
    mount("#/pid/simulation");
    for _ in 0..120 {
        frame(ONE_STEP_MS);
    }
    labweb::paint_now();
    let end = shown().0;
    scrub_to(40);
    element("[data-time=mark]").click();
    labweb::paint_now();
    assert_eq!(listed(), ["40"]);
    assert!(
        text(".tb-marks").contains("0.67 s"),
        "{}",
        text(".tb-marks")
    );
    assert_eq!(
        attr("[data-time=mark]", "aria-pressed").as_deref(),
        Some("true")
    );
    scrub_to(end);
    assert_eq!(
        attr("[data-time=mark]", "aria-pressed").as_deref(),
        Some("false")
    );
    press_key_on_canvas("m");
    labweb::paint_now();
    assert_eq!(listed(), ["40".to_owned(), end.to_string()]);
    let keys: Vec<&str> =
        labweb::inspect_sim(|exp, _| exp.plots().iter().map(|p| p.key).collect()).unwrap();
    assert!(keys.len() >= 2, "{keys:?}");
    for key in keys {
        let drawn = drawn_marks(key);
        assert!(!drawn.is_empty(), "{key}: no mark drawn");
        assert_eq!(drawn, expected_marks(key, &[40, end]), "{key}");
    }
    // The link carries them, in seconds.
    frame(300.0);
    frame(300.0);
    let link = hash();
    assert!(
        link.contains(&format!("marks=0.67,{}", labcore::marks::time_text(end))),
        "{link}"
    );
    // Remove the first: its points go.
    element("[data-unmark=\"40\"]").click();
    labweb::paint_now();
    assert_eq!(listed(), [end.to_string()]);
    assert_eq!(drawn_marks("response"), expected_marks("response", &[end]));
    // `M` again on a marked moment removes it.
    press_key_on_canvas("M");
    labweb::paint_now();
    assert!(listed().is_empty());
    assert!(element(".tb-marks").hidden());
    assert_eq!(drawn_marks("response"), "");
}

/// A link's marks come back exactly (the list, the points once the run
/// gets there); a malformed `marks=` says so and the lab runs on.
#[wasm_bindgen_test]
fn marks_in_the_link_come_back_exactly_and_a_malformed_value_says_so() {
    mount("#/pid/simulation?marks=0.50,1.00&run=0&at=1.50");
    labweb::paint_now();
    assert_eq!(listed(), ["30", "60"]);
    assert_eq!(
        drawn_marks("response"),
        expected_marks("response", &[30, 60])
    );
    frame(300.0);
    frame(300.0);
    assert!(hash().contains("marks=0.50,1.00"), "{}", hash());

    mount("#/pid/simulation?marks=1.2,soon");
    let notice = document().get_element_by_id("notice").unwrap();
    let notice: &HtmlElement = notice.dyn_ref().unwrap();
    assert!(!notice.hidden(), "no notice");
    let said = notice.text_content().unwrap_or_default();
    assert!(
        said.contains("Marks: “soon” is not a time in seconds"),
        "{said}"
    );
    assert!(listed().is_empty());
    for _ in 0..10 {
        frame(ONE_STEP_MS);
    }
    assert!(shown().0 >= 9, "the run goes on");
}

/// Marks belong to the run: Reset clears them; an input in the past that
/// goes on from there (cartpole's gain) starts a new run there and drops
/// the marks after it, keeping those before; one that starts the run again
/// (pid's gain replays the step: issue 53 §1) leaves none.
#[wasm_bindgen_test]
fn reset_clears_the_marks_and_a_new_run_from_the_past_drops_the_later_ones() {
    mount("#/cartpole/simulation");
    for _ in 0..100 {
        frame(ONE_STEP_MS);
    }
    for step in [20, 50, 80] {
        scrub_to(step);
        press_key_on_canvas("m");
    }
    labweb::paint_now();
    assert_eq!(listed(), ["20", "50", "80"]);
    // A new gain at step 50: the run from there is another one.
    scrub_to(50);
    set_param("kth", "30");
    labweb::paint_now();
    assert_eq!(listed(), ["20", "50"]);
    element("[data-time=reset]").click();
    labweb::paint_now();
    assert!(listed().is_empty());
    assert_eq!(drawn_marks("angle"), "");
    // pid: a gain replays the step, a new run at t = 0, with no marks.
    mount("#/pid/simulation");
    for _ in 0..100 {
        frame(ONE_STEP_MS);
    }
    scrub_to(20);
    press_key_on_canvas("m");
    scrub_to(50);
    set_param("kp", "30");
    labweb::paint_now();
    assert!(listed().is_empty());
    assert_eq!(drawn_marks("response"), "");
}

/// Sets parameter `key`'s control to `value` as typing does.
fn set_param(key: &str, value: &str) {
    let input: HtmlInputElement = element(&format!("#p-{key}")).dyn_into().unwrap();
    input.set_value(value);
    let init = web_sys::EventInit::new();
    init.set_bubbles(true);
    input
        .dispatch_event(&web_sys::Event::new_with_event_init_dict("input", &init).unwrap())
        .unwrap();
}
